//! The `main.xml` of an X3P file (ISO 25178-72 / ISO 5436-2), flattened to element paths.
//!
//! The reader is deliberately loose about the document shell, because real files differ: the
//! root element may be `p:ISO5436_2` (openGPS namespace) or a bare `ISO5436` (x3ptools), and
//! namespace prefixes are ignored everywhere. Element paths are relative to the root element,
//! e.g. `Record1/Axes/CZ/Offset`. An empty element (`<Offset/>`) has the value `""`.

use std::collections::HashMap;

use quick_xml::events::Event;
use quick_xml::Reader;

use super::ParseError;

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
        // Local names of the open elements, root first.
        let mut stack: Vec<String> = Vec::new();
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
                    stack.push(e.local_name().as_ref().to_string());
                    current_text.clear();
                }
                Event::Empty(e) => {
                    stack.push(e.local_name().as_ref().to_string());
                    doc.close_element(&stack, "")?;
                    stack.pop();
                }
                Event::Text(t) => current_text.push_str(&t),
                Event::CData(t) => current_text.push_str(&t),
                Event::End(_) => {
                    doc.close_element(&stack, &current_text)?;
                    current_text.clear();
                    stack.pop();
                }
                Event::Eof => break,
                _ => {}
            }
        }
        if !stack.is_empty() {
            return Err(ParseError::truncated(format!(
                "x3p: main.xml ends inside <{}>",
                stack.join("/")
            )));
        }
        if doc.root.is_empty() {
            return Err(ParseError::malformed("x3p: main.xml has no root element"));
        }
        Ok(doc)
    }

    fn close_element(&mut self, stack: &[String], text: &str) -> Result<(), ParseError> {
        let Some((root, rest)) = stack.split_first() else {
            return Ok(());
        };
        if self.root.is_empty() {
            self.root = root.clone();
        }
        if rest.is_empty() {
            return Ok(());
        }
        let path = rest.join("/");
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
            self.values.entry(path).or_insert_with(|| text.to_string());
        }
        Ok(())
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
    fn reports_unclosed_document() {
        let err = X3pDocument::parse(b"<ISO5436><Record1>").unwrap_err();
        assert!(err.to_string().contains("main.xml"), "{err}");
    }
}
