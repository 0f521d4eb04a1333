//! The `main.xml` of an X3P file (ISO 25178-72 / ISO 5436-2), flattened to element paths.
//!
//! The reader is deliberately loose about the document shell, because real files differ: the
//! root element may be `p:ISO5436_2` (openGPS namespace) or a bare `ISO5436` (x3ptools), and
//! namespace prefixes are ignored everywhere. Element paths are relative to the root element,
//! e.g. `Record1/Axes/CZ/Offset`. An empty element (`<Offset/>`) has the value `""`.
//!
//! Work is linear in the size of `main.xml`: the path of the open element is one string that
//! grows and shrinks with the nesting (never rebuilt from the element stack), and nesting deeper
//! than [`MAX_DEPTH`] is refused.

use std::collections::HashMap;

use quick_xml::events::Event;
use quick_xml::Reader;

use super::ParseError;

/// Deepest element nesting accepted in `main.xml`, root included. ISO 5436-2 needs 5 levels
/// (`ISO5436_2/Record1/Axes/CZ/Increment`), vendor extensions under `Record2` a few more; 64
/// leaves ample room while refusing a hostile document of thousands of nested elements
/// before its paths cost memory quadratic in the depth.
pub(crate) const MAX_DEPTH: usize = 64;

/// `main.xml` content: the text of every element (first occurrence of each path) and the
/// optional inline point list.
#[derive(Debug, Default)]
pub(crate) struct X3pDocument {
    /// Name of the root element, without namespace prefix.
    pub(crate) root: String,
    values: HashMap<String, String>,
    /// `Record3/DataList/Datum` values in document order; `None` for an empty `<Datum/>`.
    pub(crate) data_list: Option<Vec<Option<f64>>>,
}

impl X3pDocument {
    /// Trimmed text of the element at `path`, `None` when the element is absent.
    pub(crate) fn get(&self, path: &str) -> Option<&str> {
        self.values.get(path).map(|s| s.trim())
    }

    /// Parses `main.xml`.
    pub(crate) fn parse(xml: &[u8]) -> Result<Self, ParseError> {
        let text = std::str::from_utf8(xml)
            .map_err(|e| ParseError::malformed(format!("x3p: main.xml is not UTF-8: {e}")))?;
        let mut reader = Reader::from_str(text);
        let mut doc = X3pDocument::default();
        let mut path = ElementPath::default();
        let mut current_text = String::new();
        loop {
            let event = reader.read_event().map_err(|e| {
                ParseError::malformed(format!(
                    "x3p: main.xml is not well-formed XML near byte {}: {e}",
                    reader.buffer_position()
                ))
            })?;
            match event {
                Event::Start(e) => {
                    path.push(e.local_name().as_ref(), &reader)?;
                    current_text.clear();
                }
                Event::Empty(e) => {
                    path.push(e.local_name().as_ref(), &reader)?;
                    doc.close_element(&path, "")?;
                    path.pop();
                }
                Event::Text(t) => current_text.push_str(&t),
                Event::CData(t) => current_text.push_str(&t),
                Event::End(_) => {
                    doc.close_element(&path, &current_text)?;
                    current_text.clear();
                    path.pop();
                }
                Event::Eof => break,
                _ => {}
            }
        }
        if path.depth() > 0 {
            return Err(ParseError::truncated(format!(
                "x3p: main.xml ends inside <{}>",
                path.full()
            )));
        }
        if doc.root.is_empty() {
            return Err(ParseError::malformed("x3p: main.xml has no root element"));
        }
        Ok(doc)
    }

    fn close_element(&mut self, path: &ElementPath, text: &str) -> Result<(), ParseError> {
        if path.depth() == 0 {
            return Ok(());
        }
        if self.root.is_empty() {
            self.root = path.root().to_string();
        }
        let Some(path) = path.below_root() else {
            return Ok(());
        };
        if path == "Record3/DataList/Datum" {
            let t = text.trim();
            let value = if t.is_empty() {
                None
            } else {
                Some(t.parse::<f64>().map_err(|_| {
                    ParseError::malformed(format!("x3p: DataList datum {t:?} is not a number"))
                })?)
            };
            self.data_list.get_or_insert_with(Vec::new).push(value);
        } else {
            if path == "Record3/DataList" {
                self.data_list.get_or_insert_with(Vec::new);
            }
            if !self.values.contains_key(path) {
                self.values.insert(path.to_string(), text.to_string());
            }
        }
        Ok(())
    }
}

/// The path of the open element, `root/child/…`, kept as one string with the end of each
/// level, so a push or pop costs the length of one name.
#[derive(Debug, Default)]
struct ElementPath {
    text: String,
    /// `ends[k]`: length of `text` up to and including level `k`.
    ends: Vec<usize>,
}

impl ElementPath {
    fn depth(&self) -> usize {
        self.ends.len()
    }

    fn push(&mut self, name: &str, reader: &Reader<&[u8]>) -> Result<(), ParseError> {
        if self.ends.len() >= MAX_DEPTH {
            return Err(ParseError::malformed(format!(
                "x3p: main.xml nests elements deeper than {MAX_DEPTH} levels near byte {} \
                 (ISO 5436-2 needs 5); not an X3P document",
                reader.buffer_position()
            )));
        }
        if !self.ends.is_empty() {
            self.text.push('/');
        }
        self.text.push_str(name);
        self.ends.push(self.text.len());
        Ok(())
    }

    fn pop(&mut self) {
        self.ends.pop();
        let start = self.ends.last().copied().unwrap_or(0);
        self.text.truncate(start);
    }

    fn full(&self) -> &str {
        &self.text
    }

    fn root(&self) -> &str {
        &self.text[..self.ends[0]]
    }

    /// The path relative to the root element; `None` for the root itself.
    fn below_root(&self) -> Option<&str> {
        let root_end = *self.ends.first()?;
        (self.ends.len() > 1).then(|| &self.text[root_end + 1..])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flattens_paths_without_namespace() {
        let xml = br#"<?xml version="1.0"?><p:ISO5436_2 xmlns:p="x"><Record1><Axes><CZ>
            <Increment>1e-3</Increment><Offset/></CZ></Axes></Record1>
            <Record3><DataList><Datum>1.5</Datum><Datum/></DataList></Record3></p:ISO5436_2>"#;
        let doc = X3pDocument::parse(xml).unwrap();
        assert_eq!(doc.root, "ISO5436_2");
        assert_eq!(doc.get("Record1/Axes/CZ/Increment"), Some("1e-3"));
        assert_eq!(doc.get("Record1/Axes/CZ/Offset"), Some(""));
        assert_eq!(doc.data_list, Some(vec![Some(1.5), None]));
    }

    #[test]
    fn refuses_deep_nesting_in_linear_time() {
        let depth = 50_000;
        let xml = format!("{}{}", "<a>".repeat(depth), "</a>".repeat(depth));
        let start = std::time::Instant::now();
        let err = X3pDocument::parse(xml.as_bytes()).unwrap_err().to_string();
        assert!(err.contains("deeper than 64 levels"), "{err}");
        assert!(start.elapsed().as_secs_f64() < 0.5, "{:?}", start.elapsed());
        let at_limit = format!("{}{}", "<a>".repeat(MAX_DEPTH), "</a>".repeat(MAX_DEPTH));
        let doc = X3pDocument::parse(at_limit.as_bytes()).unwrap();
        assert_eq!(doc.root, "a");
    }

    #[test]
    fn reports_unclosed_document() {
        let err = X3pDocument::parse(b"<ISO5436><Record1>").unwrap_err();
        assert!(err.to_string().contains("main.xml"), "{err}");
    }
}
