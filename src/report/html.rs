//! The self-contained HTML page: inline CSS, inline SVG figures (maps carry their PNG as a
//! `data:` URI), no scripts, fonts or links to other files.

use std::fmt::Write;

use super::figure::{Figure, Section, ValueTable};

/// Escapes text for HTML and SVG content and attribute values.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

const STYLE: &str = "body{font-family:sans-serif;margin:1.5em auto;max-width:1250px;color:#222;padding:0 1em}\
h1{font-size:1.6em}h2{border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:1.6em}\
.figures{display:flex;flex-wrap:wrap;gap:1.2em}figure{margin:0;max-width:100%}\
figure svg{max-width:100%;height:auto;border:1px solid #eee}figcaption{font-size:.9em;color:#444;max-width:640px}\
table{border-collapse:collapse;font-size:.85em}td,th{border:1px solid #ccc;padding:.15em .5em;text-align:right}\
td:first-child,th:first-child{text-align:left}details{margin-top:.3em}dt{font-weight:bold}\
.note{color:#555}ul.skipped li{color:#8a4b00}";

/// The page head facts.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PageHeader {
    pub title: String,
    /// `(term, description)` pairs shown as a definition list.
    pub facts: Vec<(String, String)>,
    /// What could not be shown, and why.
    pub skipped: Vec<String>,
}

fn write_values(out: &mut String, values: &ValueTable) {
    out.push_str("<details><summary>values</summary><table class=\"values\"><tr>");
    for h in &values.header {
        let _ = write!(out, "<th>{}</th>", escape(h));
    }
    out.push_str("</tr>");
    for row in &values.rows {
        out.push_str("<tr>");
        for cell in row {
            let _ = write!(out, "<td>{}</td>", escape(cell));
        }
        out.push_str("</tr>");
    }
    out.push_str("</table></details>");
}

fn write_figure(out: &mut String, figure: &Figure) {
    out.push_str("<figure>");
    if let Some(svg) = &figure.svg {
        out.push_str(svg);
    }
    let _ = write!(out, "<figcaption>{}", escape(&figure.caption));
    if let Some(values) = &figure.values {
        write_values(out, values);
    }
    out.push_str("</figcaption></figure>");
}

/// The whole page.
pub fn page(header: &PageHeader, sections: &[Section]) -> String {
    let mut out = String::new();
    let _ = write!(
        out,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{}</title><style>{STYLE}</style></head><body><h1>{}</h1><dl>",
        escape(&header.title),
        escape(&header.title)
    );
    for (term, text) in &header.facts {
        let _ = write!(out, "<dt>{}</dt><dd>{}</dd>", escape(term), escape(text));
    }
    out.push_str("</dl>");
    for section in sections {
        let _ = write!(
            out,
            "<section><h2>{}</h2><p class=\"note\">{}</p><div class=\"figures\">",
            escape(&section.title),
            escape(&section.intro)
        );
        for figure in &section.figures {
            write_figure(&mut out, figure);
        }
        out.push_str("</div></section>");
    }
    if !header.skipped.is_empty() {
        out.push_str("<section><h2>Skipped</h2><ul class=\"skipped\">");
        for s in &header.skipped {
            let _ = write!(out, "<li>{}</li>", escape(s));
        }
        out.push_str("</ul></section>");
    }
    out.push_str("</body></html>\n");
    out
}
