//! The ZIP archive inside a `.zon` file: stored members only, ZIP64 records supported.
//!
//! Layout (PKWARE APPNOTE.TXT 6.3, sections 4.3.6–4.3.16): the end-of-central-directory record
//! (`PK\5\6`) at the end; when its counts or offsets are saturated (`0xFFFF`/`0xFFFFFFFF`), a
//! ZIP64 locator (`PK\6\7`, 20 bytes) just before it points at the ZIP64 end record (`PK\6\6`)
//! holding the 64-bit entry count, directory size and directory offset. Central-directory
//! entries (`PK\1\2`) give method, sizes and local-header offset, with saturated fields
//! replaced by the ZIP64 extra field (id 1, values in the order uncompressed size, compressed
//! size, offset). The archive follows the thumbnail, so recorded offsets are shifted by the
//! difference between where a record is and where the archive says it is.

use std::collections::BTreeMap;

use super::super::ParseError;

const EOCD: &[u8] = b"PK\x05\x06";
const ZIP64_LOCATOR: &[u8] = b"PK\x06\x07";
const ZIP64_EOCD: &[u8] = b"PK\x06\x06";
const CENTRAL: &[u8] = b"PK\x01\x02";
const LOCAL: &[u8] = b"PK\x03\x04";
const SATURATED_32: u64 = 0xFFFF_FFFF;

fn le(b: &[u8], at: usize, n: usize) -> Option<u64> {
    let s = b.get(at..at.checked_add(n)?)?;
    Some(
        s.iter()
            .rev()
            .fold(0u64, |acc, &x| (acc << 8) | u64::from(x)),
    )
}

fn to_usize(v: u64, what: &str) -> Result<usize, ParseError> {
    usize::try_from(v).map_err(|_| ParseError::malformed(format!("ZON ZIP: {what} {v} too large")))
}

/// Absolute start of the central directory, its entry count, and the shift to add to the
/// offsets recorded in the archive.
fn central_directory(bytes: &[u8]) -> Result<(usize, u64, u64), ParseError> {
    let search_from = bytes.len().saturating_sub(22 + 65_535);
    let eocd = bytes[search_from..]
        .windows(4)
        .rposition(|w| w == EOCD)
        .map(|p| p + search_from)
        .ok_or_else(|| ParseError::truncated("ZON: end of the ZIP archive not found"))?;
    let bad = || ParseError::truncated("ZON: ZIP end-of-directory record");
    let entries = le(bytes, eocd + 10, 2).ok_or_else(bad)?;
    let cd_size = le(bytes, eocd + 12, 4).ok_or_else(bad)?;
    let cd_offset = le(bytes, eocd + 16, 4).ok_or_else(bad)?;
    let locator = eocd.checked_sub(20);
    let is_zip64 = locator.is_some_and(|l| bytes.get(l..l + 4) == Some(ZIP64_LOCATOR));
    if let (true, Some(locator)) = (is_zip64, locator) {
        let bad64 = || ParseError::malformed("ZON: ZIP64 end-of-directory record is damaged");
        let declared = le(bytes, locator + 8, 8).ok_or_else(bad64)?;
        // The ZIP64 end record (56 bytes without extensible data) sits right before the locator.
        let record = locator.checked_sub(56).ok_or_else(bad64)?;
        if bytes.get(record..record + 4) != Some(ZIP64_EOCD) {
            return Err(ParseError::unsupported(
                "ZON: ZIP64 end record with extensible data",
            ));
        }
        let shift = (record as u64).checked_sub(declared).ok_or_else(bad64)?;
        let entries = le(bytes, record + 32, 8).ok_or_else(bad64)?;
        let cd_offset = le(bytes, record + 48, 8).ok_or_else(bad64)?;
        let start = cd_offset.checked_add(shift).ok_or_else(bad64)?;
        return Ok((to_usize(start, "central directory offset")?, entries, shift));
    }
    let start = (eocd as u64)
        .checked_sub(cd_size)
        .ok_or_else(|| ParseError::malformed("ZON: ZIP central directory larger than the file"))?;
    let shift = start.checked_sub(cd_offset).ok_or_else(|| {
        ParseError::malformed("ZON: ZIP central directory offset beyond its position")
    })?;
    Ok((to_usize(start, "central directory offset")?, entries, shift))
}

/// The members of the archive.
pub(super) struct Members<'a> {
    /// Stored members, `name → content`.
    pub stored: BTreeMap<String, &'a [u8]>,
    /// Members with another compression method, `name → method` (not decoded).
    pub other_method: BTreeMap<String, u64>,
}

/// Lists the members of the archive.
pub(super) fn members(bytes: &[u8]) -> Result<Members<'_>, ParseError> {
    let (cd_start, entries, shift) = central_directory(bytes)?;
    let mut stored = BTreeMap::new();
    let mut other = BTreeMap::new();
    let mut pos = cd_start;
    for i in 0..entries {
        let bad =
            || ParseError::malformed(format!("ZON: ZIP central directory entry {i} is damaged"));
        if bytes.get(pos..pos + 4) != Some(CENTRAL) {
            return Err(bad());
        }
        let method = le(bytes, pos + 10, 2).ok_or_else(bad)?;
        let mut size = le(bytes, pos + 20, 4).ok_or_else(bad)?;
        let mut uncompressed = le(bytes, pos + 24, 4).ok_or_else(bad)?;
        let name_len = to_usize(le(bytes, pos + 28, 2).ok_or_else(bad)?, "name length")?;
        let extra_len = to_usize(le(bytes, pos + 30, 2).ok_or_else(bad)?, "extra length")?;
        let comment_len = to_usize(le(bytes, pos + 32, 2).ok_or_else(bad)?, "comment length")?;
        let mut local = le(bytes, pos + 42, 4).ok_or_else(bad)?;
        let name = bytes.get(pos + 46..pos + 46 + name_len).ok_or_else(bad)?;
        let name = String::from_utf8_lossy(name).into_owned();
        let extra = bytes
            .get(pos + 46 + name_len..pos + 46 + name_len + extra_len)
            .ok_or_else(bad)?;
        apply_zip64_extra(extra, &mut uncompressed, &mut size, &mut local).ok_or_else(bad)?;
        pos += 46 + name_len + extra_len + comment_len;
        if method != 0 {
            other.insert(name, method);
            continue;
        }
        let local = to_usize(
            local.checked_add(shift).ok_or_else(bad)?,
            "local header offset",
        )?;
        if bytes.get(local..local + 4) != Some(LOCAL) {
            return Err(ParseError::malformed(format!(
                "ZON: ZIP member `{name}` has no local header"
            )));
        }
        let local_name = to_usize(le(bytes, local + 26, 2).ok_or_else(bad)?, "name length")?;
        let local_extra = to_usize(le(bytes, local + 28, 2).ok_or_else(bad)?, "extra length")?;
        let start = local + 30 + local_name + local_extra;
        let content = to_usize(size, "member size")
            .ok()
            .and_then(|size| bytes.get(start..start.checked_add(size)?))
            .ok_or_else(|| {
                ParseError::truncated(format!("ZON: ZIP member `{name}` ({size} bytes)"))
            })?;
        stored.insert(name, content);
    }
    Ok(Members {
        stored,
        other_method: other,
    })
}

/// Replaces saturated 32-bit fields by the values of the ZIP64 extra field (id 1), if present.
fn apply_zip64_extra(
    extra: &[u8],
    uncompressed: &mut u64,
    compressed: &mut u64,
    offset: &mut u64,
) -> Option<()> {
    let mut at = 0;
    while at + 4 <= extra.len() {
        let id = le(extra, at, 2)?;
        let len = usize::try_from(le(extra, at + 2, 2)?).ok()?;
        let body = extra.get(at + 4..at + 4 + len)?;
        if id == 1 {
            let mut k = 0;
            for field in [uncompressed, compressed, offset] {
                if *field == SATURATED_32 {
                    *field = le(body, k, 8)?;
                    k += 8;
                }
            }
            return Some(());
        }
        at += 4 + len;
    }
    Some(())
}
