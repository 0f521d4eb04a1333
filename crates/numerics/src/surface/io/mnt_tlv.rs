//! The tag-length-value tree of a Digital Surf `.mnt` `ScopedContents` stream.
//!
//! Layout (as SurfaceTopography's `MNT.py` reads it, checked against `mnt/mnt-1.mnt`): an entry
//! is a little-endian `u16` tag and a `u64` length followed by that many bytes, except tag
//! `0xFFFF`, whose `u64` is a value of its own (a marker without payload). A container's value
//! is a list of entries that fills it exactly. The height-data container instead holds a list
//! of sections, each a `u64` length followed by that many bytes (one section per processing
//! step of the document). Texts are one marker byte followed by UTF-16LE.

/// Tag of the markers that carry no payload.
const MARKER: u16 = 0xFFFF;
/// Bytes of a tag and a length.
const HEAD: usize = 10;

/// One entry of a container (markers are left out).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Entry<'a> {
    pub(crate) tag: u16,
    pub(crate) value: &'a [u8],
}

fn u64_at(bytes: &[u8], at: usize) -> Option<u64> {
    let b = bytes.get(at..at.checked_add(8)?)?;
    Some(u64::from_le_bytes(b.try_into().ok()?))
}

/// The entries of `bytes` when they are exactly a list of entries, else `None`.
pub(crate) fn entries(bytes: &[u8]) -> Option<Vec<Entry<'_>>> {
    let mut out = Vec::new();
    let mut pos = 0usize;
    while pos < bytes.len() {
        let tag = u16::from_le_bytes([*bytes.get(pos)?, *bytes.get(pos + 1)?]);
        let len = u64_at(bytes, pos + 2)?;
        pos += HEAD;
        if tag == MARKER {
            continue;
        }
        let end = pos.checked_add(usize::try_from(len).ok()?)?;
        out.push(Entry {
            tag,
            value: bytes.get(pos..end)?,
        });
        pos = end;
    }
    Some(out)
}

/// The sections of `bytes` when they are exactly a list of length-prefixed sections, each
/// returned as an entry of tag 0.
fn sections(bytes: &[u8]) -> Option<Vec<Entry<'_>>> {
    let mut out = Vec::new();
    let mut pos = 0usize;
    while pos < bytes.len() {
        let len = usize::try_from(u64_at(bytes, pos)?).ok()?;
        let end = (pos + 8).checked_add(len)?;
        out.push(Entry {
            tag: 0,
            value: bytes.get(pos + 8..end)?,
        });
        pos = end;
    }
    Some(out)
}

/// The children of a container: its entries, or its sections.
pub(crate) fn children(bytes: &[u8]) -> Option<Vec<Entry<'_>>> {
    if bytes.len() < HEAD {
        return None;
    }
    entries(bytes).or_else(|| sections(bytes))
}

impl Entry<'_> {
    /// The value as a little-endian `u32`, when it is 4 bytes.
    pub(crate) fn u32(&self) -> Option<u32> {
        Some(u32::from_le_bytes(self.value.try_into().ok()?))
    }

    /// The value as a little-endian `f64`, when it is 8 bytes.
    pub(crate) fn f64(&self) -> Option<f64> {
        Some(f64::from_le_bytes(self.value.try_into().ok()?))
    }

    /// The value as a text: a marker byte, then UTF-16LE (trailing NULs dropped).
    pub(crate) fn text(&self) -> Option<String> {
        let raw = self.value.get(1..)?;
        let units: Vec<u16> = raw
            .chunks_exact(2)
            .map(|c| u16::from_le_bytes([c[0], c[1]]))
            .collect();
        let text = String::from_utf16(&units).ok()?;
        Some(text.trim_end_matches('\0').trim().to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entry(tag: u16, value: &[u8]) -> Vec<u8> {
        let mut out = tag.to_le_bytes().to_vec();
        out.extend_from_slice(&(value.len() as u64).to_le_bytes());
        out.extend_from_slice(value);
        out
    }

    #[test]
    fn markers_carry_no_payload_and_sections_are_length_prefixed() {
        let mut bytes = MARKER.to_le_bytes().to_vec();
        bytes.extend_from_slice(&1234u64.to_le_bytes());
        bytes.extend(entry(7, &5u32.to_le_bytes()));
        let list = entries(&bytes).unwrap();
        assert_eq!(list.len(), 1);
        assert_eq!((list[0].tag, list[0].u32()), (7, Some(5)));
        let mut prefixed = (bytes.len() as u64).to_le_bytes().to_vec();
        prefixed.extend_from_slice(&bytes);
        assert!(entries(&prefixed).is_none());
        let list = children(&prefixed).unwrap();
        assert_eq!((list.len(), list[0].value), (1, bytes.as_slice()));
    }

    #[test]
    fn a_length_past_the_end_is_not_a_list() {
        let mut bytes = entry(1, &[0; 4]);
        bytes[2] = 200;
        assert!(entries(&bytes).is_none());
        assert!(children(&bytes).is_none());
    }

    #[test]
    fn texts_are_a_marker_then_utf16() {
        let e = Entry {
            tag: 2,
            value: &[4, 0xb5, 0, b'm', 0],
        };
        assert_eq!(e.text().as_deref(), Some("µm"));
    }
}
