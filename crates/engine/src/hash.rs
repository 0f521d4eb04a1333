//! Node keys: blake3 over a canonical encoding of exactly what determines a node's result.
//!
//! Encoded, in order: the key-schema version, the node kind, the kind's implementation version,
//! the node's own resolved parameters (SI; sorted by name; floats by bit pattern) and its upstream
//! nodes' keys (sorted by role). Nothing else: not the thread count, paths, output location or
//! parameters the node does not consume. Every item is length-prefixed so encodings are
//! unambiguous.

use std::collections::HashMap;
use std::fmt;
use std::hash::{BuildHasherDefault, Hash, Hasher};

use crate::encoding::{self, Lengths};
use crate::value::{Field, Value};

/// Version of the key encoding itself; bump when this file's encoding changes.
pub const KEY_SCHEMA_VERSION: u32 = 1;

/// The content key of a node instance.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub struct NodeKey(pub [u8; 32]);

/// A key is a blake3 digest, uniformly distributed: its first eight bytes hash it.
impl Hash for NodeKey {
    fn hash<H: Hasher>(&self, state: &mut H) {
        let mut first = [0u8; 8];
        first.copy_from_slice(&self.0[..8]);
        state.write_u64(u64::from_le_bytes(first));
    }
}

/// Hashes a [`NodeKey`] by taking its first eight bytes as they are, for maps keyed by node keys
/// (and a `u64` that is a hash already, as it is).
#[derive(Default)]
pub struct KeyHasher(u64);

impl Hasher for KeyHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = self.0.rotate_left(8) ^ u64::from(b);
        }
    }

    fn write_u64(&mut self, n: u64) {
        self.0 = n;
    }
}

/// A map keyed by node keys.
pub type KeyMap<V> = HashMap<NodeKey, V, BuildHasherDefault<KeyHasher>>;

impl NodeKey {
    /// Lower-case hex, 64 characters.
    pub fn to_hex(&self) -> String {
        const DIGITS: &[u8; 16] = b"0123456789abcdef";
        let mut hex = String::with_capacity(64);
        for b in self.0 {
            hex.push(char::from(DIGITS[usize::from(b >> 4)]));
            hex.push(char::from(DIGITS[usize::from(b & 0xf)]));
        }
        hex
    }

    /// Parses 64 hex characters.
    pub fn from_hex(hex: &str) -> Option<Self> {
        if hex.len() != 64 || !hex.is_ascii() {
            return None;
        }
        let mut out = [0u8; 32];
        for (i, byte) in out.iter_mut().enumerate() {
            *byte = u8::from_str_radix(&hex[2 * i..2 * i + 2], 16).ok()?;
        }
        Some(Self(out))
    }

    /// The first 12 hex characters, for display.
    pub fn short(&self) -> String {
        self.to_hex()[..12].to_string()
    }
}

impl fmt::Debug for NodeKey {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "NodeKey({})", self.short())
    }
}

impl fmt::Display for NodeKey {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.to_hex())
    }
}

/// Computes a node key: the blake3 hash of [`key_encoding`].
pub fn node_key(
    kind: &str,
    version: u32,
    params: &[Field],
    upstream: &[(&str, NodeKey)],
) -> NodeKey {
    NodeKey(*blake3::hash(&key_encoding(kind, version, params, upstream)).as_bytes())
}

/// The canonical encoding a node key hashes, built in one buffer.
fn key_encoding(
    kind: &str,
    version: u32,
    params: &[Field],
    upstream: &[(&str, NodeKey)],
) -> Vec<u8> {
    let mut out = Vec::with_capacity(256 + 48 * params.len() + 64 * upstream.len());
    out.extend_from_slice(b"asperity-node-key");
    out.extend_from_slice(&KEY_SCHEMA_VERSION.to_le_bytes());
    put_str(&mut out, kind);
    out.extend_from_slice(&version.to_le_bytes());
    let mut sorted: Vec<&Field> = params.iter().collect();
    sorted.sort_by(|a, b| a.name.cmp(&b.name));
    encoding::put_len(&mut out, sorted.len(), Lengths::Fixed64);
    for field in sorted {
        put_str(&mut out, &field.name);
        put_str(&mut out, field.dimension.name());
        put_value(&mut out, &field.value);
    }
    let mut roles: Vec<&(&str, NodeKey)> = upstream.iter().collect();
    roles.sort_by(|a, b| a.0.cmp(b.0));
    encoding::put_len(&mut out, roles.len(), Lengths::Fixed64);
    for (role, key) in roles {
        put_str(&mut out, role);
        out.extend_from_slice(&key.0);
    }
    out
}

/// A parameter's value in the encoding shared with the cache ([`crate::encoding`]), lengths in 8
/// bytes; `-0.0` is written as `0.0`, alone or in a list: the same physical value, one key.
/// A scalar is its lower-case tag and value (`KEY_SCHEMA_VERSION` 1); a list has an upper-case
/// tag and its length, so no list encodes as a scalar does.
fn put_value(out: &mut Vec<u8>, value: &Value) {
    let zero = |x: f64| if x == 0.0 { 0.0 } else { x };
    match value {
        Value::Float(x) => encoding::put_value(out, &Value::Float(zero(*x)), Lengths::Fixed64),
        Value::Floats(v) if v.contains(&0.0) => {
            let v = v.iter().map(|x| zero(*x)).collect();
            encoding::put_value(out, &Value::Floats(v), Lengths::Fixed64);
        }
        other => encoding::put_value(out, other, Lengths::Fixed64),
    }
}

fn put_str(out: &mut Vec<u8>, s: &str) {
    encoding::put_str(out, s, Lengths::Fixed64);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::units::Dimension;

    #[test]
    fn order_of_params_and_roles_does_not_matter() {
        let a = Field::float("sq", 1e-6, Dimension::Length);
        let b = Field::int("seed", 3);
        let up = NodeKey([7; 32]);
        let up2 = NodeKey([9; 32]);
        assert_eq!(
            node_key("k", 1, &[a.clone(), b.clone()], &[("x", up), ("y", up2)]),
            node_key("k", 1, &[b, a], &[("y", up2), ("x", up)])
        );
    }

    #[test]
    fn everything_keyed_changes_the_key() {
        let p = [Field::float("sq", 1e-6, Dimension::Length)];
        let base = node_key("k", 1, &p, &[]);
        assert_ne!(base, node_key("k", 2, &p, &[]));
        assert_ne!(base, node_key("j", 1, &p, &[]));
        assert_ne!(
            base,
            node_key(
                "k",
                1,
                &[Field::float("sq", 1.1e-6, Dimension::Length)],
                &[]
            )
        );
        assert_ne!(base, node_key("k", 1, &p, &[("u", NodeKey([0; 32]))]));
        assert_eq!(
            base,
            node_key("k", 1, &[Field::float("sq", 1e-6, Dimension::Length)], &[])
        );
    }

    /// The key of scalar parameters is pinned: the blake3 below is of the encoding
    /// `KEY_SCHEMA_VERSION` 1 defines for scalars (lower-case tag, then the value).
    #[test]
    fn scalar_keys_are_unchanged_by_lists() {
        let params = [
            Field::float("sq", 1e-6, Dimension::Length),
            Field::int("seed", 3),
            Field::text("model", "kogut_etsion"),
            Field::bool("periodic", true),
        ];
        assert_eq!(
            node_key("k", 1, &params, &[("lower", NodeKey([7; 32]))]).to_hex(),
            SCALAR_KEY
        );
    }

    const SCALAR_KEY: &str = "9c7911567e0f6e4ab127b713e07c0fec5270301fa58995bed447ab3bcc872d66";

    #[test]
    fn list_parameters_are_keyed_by_every_item_and_their_count() {
        let key =
            |v: Vec<f64>| node_key("k", 1, &[Field::floats("p", v, Dimension::Pressure)], &[]);
        assert_eq!(key(vec![-0.0, 1e6]), key(vec![0.0, 1e6]));
        assert_ne!(key(vec![1e6, 2e6]), key(vec![1e6]));
        assert_ne!(key(vec![1e6, 2e6]), key(vec![2e6, 1e6]));
        let texts = |v: &[&str]| {
            let v = v.iter().map(|s| s.to_string()).collect();
            node_key("k", 1, &[Field::texts("w", v)], &[])
        };
        assert_ne!(texts(&["a,b"]), texts(&["a", "b"]));
        assert_ne!(
            texts(&["a,b"]),
            node_key("k", 1, &[Field::text("w", "a,b")], &[])
        );
    }

    #[test]
    fn hex_is_lower_case_and_byte_ordered() {
        let mut bytes = [0u8; 32];
        bytes[0] = 0x0f;
        bytes[1] = 0xa0;
        bytes[31] = 0xff;
        let hex = NodeKey(bytes).to_hex();
        assert_eq!(&hex[..4], "0fa0");
        assert_eq!(&hex[60..], "00ff");
        assert_eq!(hex.len(), 64);
    }

    #[test]
    fn hex_round_trip() {
        let k = node_key("k", 1, &[], &[]);
        assert_eq!(NodeKey::from_hex(&k.to_hex()), Some(k));
        assert_eq!(NodeKey::from_hex("zz"), None);
    }
}
