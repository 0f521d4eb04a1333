//! NumPy `.npy` (format version 1.0) for the `f64` arrays the cache stores, so users can open
//! cache payloads with `numpy.load`. Only what the cache writes is read back: little-endian
//! `<f8`, C order.

use ndarray::{ArrayD, IxDyn};

/// Why bytes are not an `.npy` array the cache wrote.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("not a cache .npy array: {0}")]
pub struct NpyError(pub String);

const MAGIC: &[u8] = b"\x93NUMPY\x01\x00";

/// Encodes an array as `.npy` bytes.
pub fn encode(array: &ArrayD<f64>) -> Vec<u8> {
    let shape = match array.shape() {
        [] => String::from("()"),
        [n] => format!("({n},)"),
        dims => format!(
            "({})",
            dims.iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    let mut header = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': {shape}, }}");
    // Pad so that magic + length + header + '\n' is a multiple of 64 bytes.
    let unpadded = MAGIC.len() + 2 + header.len() + 1;
    header.push_str(&" ".repeat((64 - unpadded % 64) % 64));
    header.push('\n');
    let mut out = Vec::with_capacity(MAGIC.len() + 2 + header.len() + array.len() * 8);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    for x in array.iter() {
        out.extend_from_slice(&x.to_le_bytes());
    }
    out
}

/// Decodes `.npy` bytes written by [`encode`].
pub fn decode(bytes: &[u8]) -> Result<ArrayD<f64>, NpyError> {
    let err = |m: &str| NpyError(m.to_string());
    if bytes.len() < MAGIC.len() + 2 || &bytes[..MAGIC.len()] != MAGIC {
        return Err(err("missing NUMPY v1.0 magic"));
    }
    let header_len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    let data_start = 10 + header_len;
    let header = bytes
        .get(10..data_start)
        .and_then(|h| std::str::from_utf8(h).ok())
        .ok_or_else(|| err("truncated header"))?;
    if !header.contains("'descr': '<f8'") || !header.contains("'fortran_order': False") {
        return Err(err("expected little-endian f8 in C order"));
    }
    let shape_text = header
        .split("'shape': (")
        .nth(1)
        .and_then(|s| s.split(')').next())
        .ok_or_else(|| err("no shape"))?;
    let shape = shape_text
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse::<usize>().map_err(|_| err("bad shape")))
        .collect::<Result<Vec<_>, _>>()?;
    let count = shape
        .iter()
        .try_fold(1usize, |a, &d| a.checked_mul(d))
        .ok_or_else(|| err("shape overflows"))?;
    let data = &bytes[data_start.min(bytes.len())..];
    if data.len() != count.checked_mul(8).ok_or_else(|| err("shape overflows"))? {
        return Err(err("data length does not match the shape"));
    }
    let values = data
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
        .collect();
    ArrayD::from_shape_vec(IxDyn(&shape), values).map_err(|e| NpyError(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_and_aligns() {
        let a = ArrayD::from_shape_fn(IxDyn(&[3, 4]), |i| (i[0] * 10 + i[1]) as f64 + 0.5);
        let bytes = encode(&a);
        assert_eq!((bytes.len() - a.len() * 8) % 64, 0);
        assert_eq!(decode(&bytes).unwrap(), a);
        let v = ArrayD::from_shape_vec(IxDyn(&[2]), vec![1.0, 2.0]).unwrap();
        assert_eq!(decode(&encode(&v)).unwrap(), v);
    }

    #[test]
    fn rejects_truncation() {
        let a = ArrayD::from_shape_fn(IxDyn(&[2, 2]), |i| i[0] as f64);
        let bytes = encode(&a);
        for cut in [0, 5, 20, bytes.len() - 1] {
            assert!(decode(&bytes[..cut]).is_err(), "cut at {cut}");
        }
    }
}
