//! One definition of each column name (#39): no string literal is the name of a column, a metric
//! or a node's table outside `src/vocabulary.rs` (the application's names) and the engine's
//! `columns.rs`. Checked on the tokens of `src/` and `python/src/`: the name argument of
//! `Field::float/int/text/bool`, of `Table::push_*`, of a table or array inserted by name
//! (`tables.insert(String::from(…))`) and of any local wrapper that passes its first parameter on
//! as such a name (`fn len(name: &'static str, v: f64) -> Field`).

use std::collections::BTreeSet;
use std::path::Path;

use super::architecture::rust_files;
use super::source_scan::{code_tokens, item_end, Token};

/// The folders scanned, below the repository root.
const SCANNED: [&str; 2] = ["src", "python/src"];
/// The one module allowed to spell column names: its file and its folder of submodules.
const VOCABULARY: [&str; 2] = ["src/vocabulary.rs", "src/vocabulary/"];

/// The calls whose first argument is a column name: `Field::<f>(name, …)` (`floats` and
/// `texts` make list columns).
const FIELD_CALLS: [&str; 6] = ["float", "int", "text", "bool", "floats", "texts"];
/// The methods whose first argument is a column name: `table.<m>(name, …)`.
const TABLE_METHODS: [&str; 4] = ["push_float", "push_int", "push_text", "push_bool"];

/// Whether the call at `tokens[i]` (its name) is a column-making call: `Field::float`, a
/// `.push_*` method or one of `wrappers` called as a function.
fn is_column_call(tokens: &[Token], i: usize, wrappers: &BTreeSet<String>) -> bool {
    let t = &tokens[i];
    let before = |k: usize| i.checked_sub(k).map(|j| tokens[j].text.as_str());
    let field = FIELD_CALLS.iter().any(|f| t.is(f))
        && before(1) == Some("::")
        && before(2) == Some("Field");
    let method = TABLE_METHODS.iter().any(|m| t.is(m)) && before(1) == Some(".");
    let wrapper = wrappers.contains(&t.text) && !matches!(before(1), Some(".") | Some("fn"));
    (field || method || wrapper) && tokens.get(i + 1).is_some_and(|n| n.is("("))
}

/// The first parameter and the end of the function or closure defined at `tokens[i]`:
/// `fn name(param: …) { … }`, `fn name<…>(param: …)` or `let name = |param, …| …;`.
fn definition(tokens: &[Token], i: usize) -> Option<(&str, &Token, usize)> {
    let name = tokens.get(i + 1).filter(|t| t.is_ident())?;
    if tokens[i].is("fn") {
        let open = i + tokens[i..].iter().position(|t| t.is("("))?;
        let param = tokens.get(open + 1).filter(|p| p.is_ident())?;
        return Some((&name.text, param, item_end(tokens, open)));
    }
    let closure = tokens[i].is("let")
        && tokens.get(i + 2).is_some_and(|t| t.is("="))
        && tokens.get(i + 3).is_some_and(|t| t.is("|"));
    let param = tokens.get(i + 4).filter(|p| closure && p.is_ident())?;
    Some((&name.text, param, item_end(tokens, i)))
}

/// The functions and closures that pass their first parameter on as the name of a
/// column-making call (found until no new one appears, so a wrapper of a wrapper counts).
fn column_wrappers(files: &[Vec<Token>]) -> BTreeSet<String> {
    let mut wrappers = BTreeSet::new();
    loop {
        let before = wrappers.len();
        for tokens in files {
            for i in 0..tokens.len() {
                let Some((name, param, end)) = definition(tokens, i) else {
                    continue;
                };
                let passes_on = (i + 2..end).any(|k| {
                    is_column_call(tokens, k, &wrappers)
                        && tokens.get(k + 2).is_some_and(|a| a.text == param.text)
                });
                if passes_on {
                    wrappers.insert(name.to_string());
                }
            }
        }
        if wrappers.len() == before {
            return wrappers;
        }
    }
}

/// The literal naming a column at the call whose `(` is `tokens[open]`: `"name"`,
/// `String::from("name")`, or a `format!` whose text spells part of the name
/// (`format!("{side}_modulus")`; `format!("{M0}{suffix}")` spells none).
fn name_literal(tokens: &[Token], open: usize) -> Option<&Token> {
    let starts = |words: &[&str]| {
        tokens
            .get(open + 1..open + 1 + words.len())
            .is_some_and(|t| t.iter().zip(words).all(|(a, b)| a.is(b)))
    };
    let (at, spelt): (usize, fn(&str) -> bool) = if starts(&["String", "::", "from", "("]) {
        (open + 5, |_| true)
    } else if starts(&["format", "!", "("]) {
        (open + 4, |text| {
            text.split('{').enumerate().any(|(i, part)| {
                part.split('}')
                    .nth(usize::from(i > 0))
                    .is_some_and(|s| s.chars().any(char::is_alphanumeric))
            })
        })
    } else {
        (open + 1, |_| true)
    };
    tokens.get(at).filter(|t| t.string().is_some_and(spelt))
}

/// Every column name spelt as a literal in `tokens`: (line, literal).
fn literal_names(tokens: &[Token], wrappers: &BTreeSet<String>) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    for i in 0..tokens.len() {
        // `tables.insert(String::from("psd"), …)`, `arrays.insert(…)`: a table or array by name.
        let named_insert = tokens[i].is("insert")
            && i >= 2
            && tokens[i - 1].is(".")
            && (tokens[i - 2].is("tables") || tokens[i - 2].is("arrays"));
        if !(is_column_call(tokens, i, wrappers) || named_insert) {
            continue;
        }
        if let Some(literal) = name_literal(tokens, i + 1) {
            out.push((literal.line, literal.text.clone()));
        }
    }
    out
}

/// The literal column names of `sources` ((file, text) pairs): `file:line: "literal"`.
fn violations(sources: &[(String, String)]) -> Vec<String> {
    let tokens: Vec<Vec<Token>> = sources.iter().map(|(_, text)| code_tokens(text)).collect();
    let wrappers = column_wrappers(&tokens);
    let mut out = Vec::new();
    for ((file, _), tokens) in sources.iter().zip(&tokens) {
        for (line, literal) in literal_names(tokens, &wrappers) {
            out.push(format!("{file}:{line}: {literal}"));
        }
    }
    out
}

#[test]
fn no_column_name_is_a_literal_outside_the_vocabulary() {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut sources = Vec::new();
    for folder in SCANNED {
        for file in rust_files(&repo.join(folder)) {
            let rel = file
                .strip_prefix(repo)
                .unwrap()
                .to_string_lossy()
                .to_string();
            if !(rel == VOCABULARY[0] || rel.starts_with(VOCABULARY[1])) {
                sources.push((rel, std::fs::read_to_string(&file).unwrap()));
            }
        }
    }
    assert!(sources.len() > 50, "only {} files scanned", sources.len());
    let found = violations(&sources);
    assert!(
        found.is_empty(),
        "column names spelt as literals (define them once in {} and use the constant):\n{}",
        VOCABULARY[0],
        found.join("\n")
    );
}

#[test]
fn the_check_finds_literal_names_in_every_form_and_passes_constants() {
    let text = "use crate::vocabulary::metrics::SQ;\n\
                fn len(name: &'static str, v: f64) -> Field { Field::float(name, v, D::Length) }\n\
                fn num(n: impl Into<Cow<'static, str>>, v: f64) -> Field { len2(n, v) }\n\
                fn len2(n: &'static str, v: f64) -> Field { Field::float(n, v, D::None) }\n\
                fn report(t: &mut Table) -> Vec<Field> {\n\
                    t.push_float(\"q\", D::None, vec![]);\n\
                    t.push_int(\n        \"ix\",\n        vec![]);\n\
                    tables.insert(String::from(\"psd\"), t);\n\
                    vec![Field::int(\"count\", 1), len(SQ, 1.0), num(\"beta\", 2.0),\n\
                         Field::text(String::from(\"state\"), \"x\"), len(SQ, \"sq\".len() as f64)]\n\
                }\n\
                fn closure() { let area = |name: &'static str, v| Field::float(name, v, D::Area);\n\
                    area(\"a\", 1.0); }\n\
                fn formats(s: &str) { num(format!(\"{M0}{s}\"), 1.0); num(format!(\"{s}_modulus\"), 1.0); }\n\
                fn lists() { Field::floats(\"loads\", vec![], D::Force); Field::texts(\"notes\", vec![]); }\n\
                #[cfg(test)]\nmod tests { fn t() { Field::int(\"in_a_test\", 1); } }\n";
    let found = violations(&[(String::from("src/x.rs"), String::from(text))]);
    assert_eq!(
        found,
        [
            "src/x.rs:6: \"q\"",
            "src/x.rs:8: \"ix\"",
            "src/x.rs:10: \"psd\"",
            "src/x.rs:11: \"count\"",
            "src/x.rs:11: \"beta\"",
            "src/x.rs:12: \"state\"",
            "src/x.rs:15: \"a\"",
            "src/x.rs:16: \"{s}_modulus\"",
            "src/x.rs:17: \"loads\"",
            "src/x.rs:17: \"notes\"",
        ]
    );
}
