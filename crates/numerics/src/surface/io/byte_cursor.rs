//! Bounds-checked reading of binary file headers and data blocks.
//!
//! Every read names what it was reading, so a short file yields a [`ParseError::Truncated`]
//! that says which field is missing instead of a panic.

use super::limits::check_count;
use super::ParseError;

/// Byte order of multi-byte numbers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Endian {
    Little,
    Big,
}

/// A read position in a byte slice; every read is bounds-checked.
#[derive(Debug, Clone)]
pub(crate) struct ByteCursor<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl<'a> ByteCursor<'a> {
    pub(crate) fn new(bytes: &'a [u8]) -> Self {
        Self { bytes, pos: 0 }
    }

    /// The current position, bytes from the start.
    pub(crate) fn position(&self) -> usize {
        self.pos
    }

    /// Bytes left after the current position.
    pub(crate) fn remaining(&self) -> usize {
        self.bytes.len() - self.pos
    }

    /// Moves to an absolute offset (which must lie inside the slice).
    pub(crate) fn seek(&mut self, pos: usize, what: &str) -> Result<(), ParseError> {
        if pos > self.bytes.len() {
            return Err(ParseError::truncated(format!(
                "{what} starts at byte {pos}, but the file has only {} bytes",
                self.bytes.len()
            )));
        }
        self.pos = pos;
        Ok(())
    }

    /// Takes the next `n` bytes.
    pub(crate) fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8], ParseError> {
        let end = self.pos.checked_add(n).filter(|&e| e <= self.bytes.len());
        let Some(end) = end else {
            return Err(ParseError::truncated(format!(
                "{what} needs {n} bytes at offset {}, only {} left",
                self.pos,
                self.remaining()
            )));
        };
        let slice = &self.bytes[self.pos..end];
        self.pos = end;
        Ok(slice)
    }

    fn array<const N: usize>(&mut self, what: &str) -> Result<[u8; N], ParseError> {
        let mut out = [0u8; N];
        out.copy_from_slice(self.take(N, what)?);
        Ok(out)
    }

    pub(crate) fn u8(&mut self, what: &str) -> Result<u8, ParseError> {
        Ok(self.array::<1>(what)?[0])
    }

    pub(crate) fn u16(&mut self, e: Endian, what: &str) -> Result<u16, ParseError> {
        let b = self.array(what)?;
        Ok(match e {
            Endian::Little => u16::from_le_bytes(b),
            Endian::Big => u16::from_be_bytes(b),
        })
    }

    pub(crate) fn u32(&mut self, e: Endian, what: &str) -> Result<u32, ParseError> {
        let b = self.array(what)?;
        Ok(match e {
            Endian::Little => u32::from_le_bytes(b),
            Endian::Big => u32::from_be_bytes(b),
        })
    }

    pub(crate) fn i32(&mut self, e: Endian, what: &str) -> Result<i32, ParseError> {
        Ok(self.u32(e, what)? as i32)
    }

    pub(crate) fn f32(&mut self, e: Endian, what: &str) -> Result<f32, ParseError> {
        Ok(f32::from_bits(self.u32(e, what)?))
    }

    pub(crate) fn f64(&mut self, e: Endian, what: &str) -> Result<f64, ParseError> {
        let b = self.array(what)?;
        Ok(match e {
            Endian::Little => f64::from_le_bytes(b),
            Endian::Big => f64::from_be_bytes(b),
        })
    }

    /// A fixed-width text field: bytes up to the first NUL, trimmed. UTF-8 when valid,
    /// otherwise Latin-1 (old vendor formats write `µ` as the single byte 0xB5).
    pub(crate) fn text(&mut self, n: usize, what: &str) -> Result<String, ParseError> {
        let raw = self.take(n, what)?;
        let end = raw.iter().position(|&b| b == 0).unwrap_or(raw.len());
        let raw = &raw[..end];
        let s = match std::str::from_utf8(raw) {
            Ok(s) => s.to_string(),
            Err(_) => raw.iter().map(|&b| char::from(b)).collect(),
        };
        Ok(s.trim().to_string())
    }
}

/// Binary sample types found in topography files.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum SampleType {
    U8,
    I8,
    U16,
    I16,
    U32,
    I32,
    F32,
    F64,
}

impl SampleType {
    /// Size of one sample in bytes.
    pub(crate) fn size(self) -> usize {
        match self {
            Self::U8 | Self::I8 => 1,
            Self::U16 | Self::I16 => 2,
            Self::U32 | Self::I32 | Self::F32 => 4,
            Self::F64 => 8,
        }
    }

    /// `true` for integer types (which need a scale factor to become heights).
    pub(crate) fn is_integer(self) -> bool {
        !matches!(self, Self::F32 | Self::F64)
    }
}

/// Checks that `count` samples of `size` bytes fit in `available` bytes, before anything is
/// allocated: a header that lies about its dimensions must not cause a huge allocation.
pub(crate) fn check_block_size(
    count: usize,
    size: usize,
    available: usize,
    what: &str,
) -> Result<usize, ParseError> {
    let needed = count
        .checked_mul(size)
        .ok_or_else(|| ParseError::malformed(format!("{what}: {count} points overflow")))?;
    if needed > available {
        return Err(ParseError::truncated(format!(
            "{what} needs {needed} bytes ({count} points × {size} B), only {available} left"
        )));
    }
    Ok(needed)
}

/// Decodes `count` samples from `bytes` into `f64` (raw values, no scaling), at most
/// [`super::MAX_POINTS`].
pub(crate) fn decode_samples(
    bytes: &[u8],
    count: usize,
    ty: SampleType,
    endian: Endian,
    what: &str,
) -> Result<Vec<f64>, ParseError> {
    let size = ty.size();
    let needed = check_block_size(count, size, bytes.len(), what)?;
    check_count(count, what)?;
    let mut out = Vec::with_capacity(count);
    for chunk in bytes[..needed].chunks_exact(size) {
        out.push(decode_one(chunk, ty, endian));
    }
    Ok(out)
}

fn decode_one(c: &[u8], ty: SampleType, e: Endian) -> f64 {
    macro_rules! num {
        ($t:ty, $n:expr) => {{
            let mut b = [0u8; $n];
            b.copy_from_slice(c);
            match e {
                Endian::Little => <$t>::from_le_bytes(b),
                Endian::Big => <$t>::from_be_bytes(b),
            }
        }};
    }
    match ty {
        SampleType::U8 => f64::from(c[0]),
        SampleType::I8 => f64::from(c[0] as i8),
        SampleType::U16 => f64::from(num!(u16, 2)),
        SampleType::I16 => f64::from(num!(i16, 2)),
        SampleType::U32 => f64::from(num!(u32, 4)),
        SampleType::I32 => f64::from(num!(i32, 4)),
        SampleType::F32 => f64::from(num!(f32, 4)),
        SampleType::F64 => num!(f64, 8),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_and_reports_truncation() {
        let bytes = [1u8, 0, 0, 0, 0x3f, 0x80, 0, 0];
        let mut c = ByteCursor::new(&bytes);
        assert_eq!(c.u32(Endian::Little, "a").unwrap(), 1);
        assert_eq!(c.f32(Endian::Big, "b").unwrap(), 1.0);
        let err = c.u16(Endian::Little, "field c").unwrap_err();
        assert!(err.to_string().contains("field c"), "{err}");
    }

    #[test]
    fn rejects_lying_block_size_without_allocating() {
        let err = decode_samples(
            &[0u8; 8],
            usize::MAX / 2,
            SampleType::F64,
            Endian::Little,
            "z",
        );
        assert!(err.is_err());
        let v = decode_samples(&[0, 1, 0xff, 0xff], 2, SampleType::I16, Endian::Big, "z").unwrap();
        assert_eq!(v, vec![1.0, -1.0]);
    }
}
