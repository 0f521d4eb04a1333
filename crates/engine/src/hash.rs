//! Node keys: blake3 over a canonical encoding of exactly what determines a node's result.
//!
//! Encoded, in order: the key-schema version, the node kind, the kind's implementation version,
//! the node's own resolved parameters (SI; sorted by name; floats by bit pattern) and its upstream
//! nodes' keys (sorted by role). Nothing else: not the thread count, paths, output location or
//! parameters the node does not consume. Every item is length-prefixed so encodings are
//! unambiguous.

use std::fmt;

use crate::value::{Field, Value};

/// Version of the key encoding itself; bump when this file's encoding changes.
pub const KEY_SCHEMA_VERSION: u32 = 1;

/// The content key of a node instance.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct NodeKey(pub [u8; 32]);

impl NodeKey {
    /// Lower-case hex, 64 characters.
    pub fn to_hex(&self) -> String {
        self.0.iter().map(|b| format!("{b:02x}")).collect()
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

/// Computes a node key.
pub fn node_key(
    kind: &str,
    version: u32,
    params: &[Field],
    upstream: &[(&str, NodeKey)],
) -> NodeKey {
    let mut h = blake3::Hasher::new();
    h.update(b"asperity-node-key");
    h.update(&KEY_SCHEMA_VERSION.to_le_bytes());
    put_str(&mut h, kind);
    h.update(&version.to_le_bytes());
    let mut sorted: Vec<&Field> = params.iter().collect();
    sorted.sort_by(|a, b| a.name.cmp(&b.name));
    h.update(&(sorted.len() as u64).to_le_bytes());
    for field in sorted {
        put_str(&mut h, &field.name);
        put_str(&mut h, field.dimension.name());
        match &field.value {
            Value::Float(x) => {
                h.update(b"f");
                // -0.0 and 0.0 are the same physical value: one key.
                let x = if *x == 0.0 { 0.0f64 } else { *x };
                h.update(&x.to_bits().to_le_bytes());
            }
            Value::Int(i) => {
                h.update(b"i");
                h.update(&i.to_le_bytes());
            }
            Value::Bool(b) => {
                h.update(b"b");
                h.update(&[u8::from(*b)]);
            }
            Value::Text(s) => {
                h.update(b"s");
                put_str(&mut h, s);
            }
        }
    }
    let mut roles: Vec<&(&str, NodeKey)> = upstream.iter().collect();
    roles.sort_by(|a, b| a.0.cmp(b.0));
    h.update(&(roles.len() as u64).to_le_bytes());
    for (role, key) in roles {
        put_str(&mut h, role);
        h.update(&key.0);
    }
    NodeKey(*h.finalize().as_bytes())
}

fn put_str(h: &mut blake3::Hasher, s: &str) {
    h.update(&(s.len() as u64).to_le_bytes());
    h.update(s.as_bytes());
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

    #[test]
    fn hex_round_trip() {
        let k = node_key("k", 1, &[], &[]);
        assert_eq!(NodeKey::from_hex(&k.to_hex()), Some(k));
        assert_eq!(NodeKey::from_hex("zz"), None);
    }
}
