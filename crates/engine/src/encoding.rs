//! The one byte encoding of values, shared by node keys (`hash.rs`) and cache summaries
//! (`cache/summary.rs`): a [`Value`] is a type tag (`f`, `i`, `b`, `s`, `F`, `S`) and then a
//! float's IEEE 754 bits, an integer's 8 bytes, a boolean's byte, a text, or a list: its count,
//! then its floats' bits (`F`) or its texts (`S`); every number little-endian, a text its length
//! and its UTF-8 bytes. Every list and text is length-prefixed, so no two values share an
//! encoding (`[1, 2]` and `[1]` then `2`, `["a,b"]` and `["a", "b"]` differ). How lengths are
//! written is each format's own ([`Lengths`]): changing a node key's would change every key.

use crate::value::Value;

/// How a format writes lengths and counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Lengths {
    /// 8 bytes, little-endian (node keys, `KEY_SCHEMA_VERSION` 1).
    Fixed64,
    /// Unsigned LEB128: seven bits a byte, low bits first, the high bit set on every byte but
    /// the last (cache summaries).
    Varint,
}

/// Appends the length or count `n`.
pub(crate) fn put_len(out: &mut Vec<u8>, n: usize, lengths: Lengths) {
    match lengths {
        Lengths::Fixed64 => out.extend_from_slice(&(n as u64).to_le_bytes()),
        Lengths::Varint => {
            let mut n = n as u64;
            while n >= 0x80 {
                out.push((n & 0x7f) as u8 | 0x80);
                n >>= 7;
            }
            out.push(n as u8);
        }
    }
}

/// Appends a text: its length, then its UTF-8 bytes.
pub(crate) fn put_str(out: &mut Vec<u8>, s: &str, lengths: Lengths) {
    put_len(out, s.len(), lengths);
    out.extend_from_slice(s.as_bytes());
}

/// Appends a float's IEEE 754 bits (so it reads back exactly, NaN and infinities included).
pub(crate) fn put_f64(out: &mut Vec<u8>, x: f64) {
    out.extend_from_slice(&x.to_bits().to_le_bytes());
}

/// Appends a value: its type tag, then the value.
pub(crate) fn put_value(out: &mut Vec<u8>, value: &Value, lengths: Lengths) {
    match value {
        Value::Float(x) => {
            out.push(b'f');
            put_f64(out, *x);
        }
        Value::Int(i) => {
            out.push(b'i');
            out.extend_from_slice(&i.to_le_bytes());
        }
        Value::Bool(b) => {
            out.push(b'b');
            out.push(u8::from(*b));
        }
        Value::Text(s) => {
            out.push(b's');
            put_str(out, s, lengths);
        }
        Value::Floats(v) => {
            out.push(b'F');
            put_len(out, v.len(), lengths);
            v.iter().for_each(|x| put_f64(out, *x));
        }
        Value::Texts(v) => {
            out.push(b'S');
            put_len(out, v.len(), lengths);
            v.iter().for_each(|s| put_str(out, s, lengths));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_encode_as_tag_and_bytes_with_the_formats_lengths() {
        let mut fixed = Vec::new();
        put_value(
            &mut fixed,
            &Value::Text(String::from("ab")),
            Lengths::Fixed64,
        );
        assert_eq!(fixed, [b's', 2, 0, 0, 0, 0, 0, 0, 0, b'a', b'b']);
        let mut varint = Vec::new();
        put_value(
            &mut varint,
            &Value::Text(String::from("ab")),
            Lengths::Varint,
        );
        assert_eq!(varint, [b's', 2, b'a', b'b']);
        let mut long = Vec::new();
        put_len(&mut long, 300, Lengths::Varint);
        assert_eq!(long, [0xac, 0x02]);
        let mut float = Vec::new();
        put_value(&mut float, &Value::Float(-0.0), Lengths::Varint);
        assert_eq!(float[0], b'f');
        assert_eq!(&float[1..], (-0.0f64).to_bits().to_le_bytes());
    }

    #[test]
    fn lists_are_counted_so_no_two_lists_share_bytes() {
        let bytes = |v: Value| {
            let mut out = Vec::new();
            put_value(&mut out, &v, Lengths::Varint);
            out
        };
        let floats = bytes(Value::Floats(vec![1.0, 2.0]));
        assert_eq!(floats[..2], [b'F', 2]);
        assert_eq!(floats.len(), 2 + 16);
        let texts = |v: &[&str]| bytes(Value::Texts(v.iter().map(|s| s.to_string()).collect()));
        assert_eq!(texts(&["a,b"]), [b'S', 1, 3, b'a', b',', b'b']);
        assert_eq!(texts(&["a", "b"]), [b'S', 2, 1, b'a', 1, b'b']);
        assert_ne!(texts(&[]), bytes(Value::Floats(Vec::new())));
        assert_ne!(texts(&["a,b"]), bytes(Value::Text(String::from("a,b"))));
    }
}
