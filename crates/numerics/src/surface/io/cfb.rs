//! Streams of a Microsoft Compound File (OLE2 structured storage, "CFB"), the container of
//! Digital Surf `.mnt` documents.
//!
//! Layout ([MS-CFB], Microsoft Open Specifications): a header (512 bytes; the first sector of a
//! 4096-byte-sector file) with the signature `D0 CF 11 E0 A1 B1 1A E1`, the sector shift (9 or
//! 12) at byte 30, the mini-sector shift (6) at 32, the number of FAT sectors at 44, the first
//! directory sector at 48, the mini-stream cutoff at 56, the first mini-FAT sector and their
//! count at 60 and 64, the first DIFAT sector and their count at 68 and 72, and the first 109
//! FAT sector numbers (the DIFAT) from byte 76. Sector `s` starts at byte `(s + 1) · sector
//! size`. The FAT maps each sector to the next of its chain, up to `ENDOFCHAIN`. The directory
//! is a chain of 128-byte entries: a UTF-16 name (64 bytes) and its byte length (with the
//! terminator) at 64, the type at 66 (2 stream, 5 root), the first sector at 116 and the size
//! at 120. Streams shorter than the cutoff live in the mini stream (the root entry's chain),
//! in 64-byte mini sectors chained by the mini FAT.
//!
//! Every chain is followed at most as many steps as the FAT has entries (a loop is an error),
//! and every sector must lie in the file, so nothing read is larger than the file.

use super::ParseError;

const SIGNATURE: [u8; 8] = [0xD0, 0xCF, 0x11, 0xE0, 0xA1, 0xB1, 0x1A, 0xE1];
const END_OF_CHAIN: u32 = 0xFFFF_FFFE;
const FREE: u32 = 0xFFFF_FFFF;
const HEADER_FAT_ENTRIES: usize = 109;
const ENTRY_BYTES: usize = 128;
const MINI_SECTOR: usize = 64;

/// `true` when `head` starts with the compound-file signature.
pub(crate) fn is_compound_file(head: &[u8]) -> bool {
    head.starts_with(&SIGNATURE)
}

fn u32_at(bytes: &[u8], at: usize, what: &str) -> Result<u32, ParseError> {
    bytes
        .get(at..at + 4)
        .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .ok_or_else(|| ParseError::truncated(format!("compound file: {what} at byte {at}")))
}

/// An opened compound file: its bytes, sector size and FAT.
struct Compound<'a> {
    bytes: &'a [u8],
    sector: usize,
    fat: Vec<u32>,
}

impl<'a> Compound<'a> {
    fn open(bytes: &'a [u8]) -> Result<Self, ParseError> {
        if !is_compound_file(bytes) {
            return Err(ParseError::malformed(
                "not a compound (OLE2) file: the signature D0 CF 11 E0 A1 B1 1A E1 is missing",
            ));
        }
        let shift = bytes
            .get(30)
            .copied()
            .ok_or_else(|| ParseError::truncated("compound file header (512 bytes)"))?;
        if !matches!(shift, 9 | 12) || bytes.get(32) != Some(&6) {
            return Err(ParseError::malformed(format!(
                "compound file: sector shift {shift} (9 or 12 expected) or mini-sector shift \
                 other than 6"
            )));
        }
        let sector = 1usize << shift;
        let n_fat = u32_at(bytes, 44, "number of FAT sectors")? as usize;
        if n_fat.saturating_mul(sector) > bytes.len() {
            return Err(ParseError::truncated(format!(
                "compound file declares {n_fat} FAT sectors of {sector} bytes, more than its \
                 {} bytes",
                bytes.len()
            )));
        }
        let mut fat_sectors = Vec::with_capacity(n_fat);
        for i in 0..n_fat.min(HEADER_FAT_ENTRIES) {
            fat_sectors.push(u32_at(bytes, 76 + 4 * i, "DIFAT entry")?);
        }
        let mut difat = u32_at(bytes, 68, "first DIFAT sector")?;
        let per_difat = sector / 4 - 1;
        while fat_sectors.len() < n_fat {
            let start = Self::sector_start(sector, difat, bytes.len(), "DIFAT sector")?;
            for i in 0..per_difat.min(n_fat - fat_sectors.len()) {
                fat_sectors.push(u32_at(bytes, start + 4 * i, "DIFAT entry")?);
            }
            difat = u32_at(bytes, start + 4 * per_difat, "next DIFAT sector")?;
        }
        let mut fat = Vec::with_capacity(n_fat * sector / 4);
        for &s in &fat_sectors {
            let start = Self::sector_start(sector, s, bytes.len(), "FAT sector")?;
            for i in 0..sector / 4 {
                fat.push(u32_at(bytes, start + 4 * i, "FAT entry")?);
            }
        }
        Ok(Self { bytes, sector, fat })
    }

    /// The byte where sector `s` starts, which must lie in the file.
    fn sector_start(sector: usize, s: u32, len: usize, what: &str) -> Result<usize, ParseError> {
        (s as usize)
            .checked_add(1)
            .and_then(|n| n.checked_mul(sector))
            .filter(|&start| start < len)
            .ok_or_else(|| {
                ParseError::truncated(format!(
                    "compound file: {what} {s} lies beyond the end of the file ({len} bytes)"
                ))
            })
    }

    /// The sectors of the chain starting at `start`, following `table` (the FAT or mini FAT).
    fn chain(table: &[u32], start: u32, what: &str) -> Result<Vec<u32>, ParseError> {
        let mut out = Vec::new();
        let mut s = start;
        while s != END_OF_CHAIN && !(out.is_empty() && s == FREE) {
            if out.len() >= table.len() {
                return Err(ParseError::malformed(format!(
                    "compound file: the sector chain of {what} loops"
                )));
            }
            out.push(s);
            s = *table.get(s as usize).ok_or_else(|| {
                ParseError::malformed(format!(
                    "compound file: {what} names sector {s}, beyond the allocation table"
                ))
            })?;
        }
        Ok(out)
    }

    /// The bytes of the regular chain starting at `start`: the first `size` (which the chain
    /// must hold), or all of them.
    fn read(&self, start: u32, size: Option<usize>, what: &str) -> Result<Vec<u8>, ParseError> {
        let sectors = Self::chain(&self.fat, start, what)?;
        let capacity = sectors.len() * self.sector;
        let size = size.unwrap_or(capacity);
        let mut out = Vec::with_capacity(size.min(capacity));
        for s in sectors {
            if out.len() >= size {
                break;
            }
            let from = Self::sector_start(self.sector, s, self.bytes.len(), what)?;
            let to = (from + self.sector).min(self.bytes.len());
            out.extend_from_slice(&self.bytes[from..to]);
        }
        if out.len() < size {
            return Err(ParseError::truncated(format!(
                "compound file: {what} declares {size} bytes, its sectors hold {}",
                out.len()
            )));
        }
        out.truncate(size);
        Ok(out)
    }
}

/// One directory entry: type, first sector and size.
struct Entry {
    kind: u8,
    start: u32,
    size: usize,
}

fn entry(dir: &[u8], index: usize, sector: usize) -> Option<(String, Entry)> {
    let e = dir.get(index * ENTRY_BYTES..(index + 1) * ENTRY_BYTES)?;
    let name_len = (u16::from_le_bytes([e[64], e[65]]) as usize).min(64);
    let units: Vec<u16> = e[..name_len.saturating_sub(2)]
        .chunks_exact(2)
        .map(|c| u16::from_le_bytes([c[0], c[1]]))
        .collect();
    let mut size = u64::from_le_bytes(e[120..128].try_into().ok()?);
    if sector == 512 {
        // Version 3 files may leave garbage in the high half ([MS-CFB] 2.6.1).
        size &= 0xFFFF_FFFF;
    }
    let entry = Entry {
        kind: e[66],
        start: u32::from_le_bytes(e[116..120].try_into().ok()?),
        size: usize::try_from(size).unwrap_or(usize::MAX),
    };
    Some((String::from_utf16_lossy(&units), entry))
}

/// The content of the stream named `name` (ASCII case ignored) anywhere in the compound file.
pub(crate) fn read_stream(bytes: &[u8], name: &str) -> Result<Vec<u8>, ParseError> {
    let file = Compound::open(bytes)?;
    let first_dir = u32_at(bytes, 48, "first directory sector")?;
    let dir = file.read(first_dir, None, "the directory")?;
    let n_entries = dir.len() / ENTRY_BYTES;
    let (_, root) = entry(&dir, 0, file.sector)
        .filter(|(_, e)| e.kind == 5)
        .ok_or_else(|| ParseError::malformed("compound file: no root directory entry"))?;
    let stream = (1..n_entries)
        .filter_map(|i| entry(&dir, i, file.sector))
        .find(|(n, e)| e.kind == 2 && n.eq_ignore_ascii_case(name))
        .map(|(_, e)| e)
        .ok_or_else(|| ParseError::malformed(format!("compound file: no stream named `{name}`")))?;
    let cutoff = u32_at(bytes, 56, "mini stream cutoff")? as usize;
    if stream.size >= cutoff {
        return file.read(stream.start, Some(stream.size), name);
    }
    let mini_stream = file.read(root.start, Some(root.size), "the mini stream")?;
    let mini_fat: Vec<u32> = file
        .read(
            u32_at(bytes, 60, "first mini FAT sector")?,
            None,
            "the mini FAT",
        )?
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    let mut out = Vec::with_capacity(stream.size.min(mini_stream.len()));
    for s in Compound::chain(&mini_fat, stream.start, name)? {
        let from = s as usize * MINI_SECTOR;
        let to = (from + MINI_SECTOR).min(mini_stream.len());
        let block = mini_stream.get(from..to).ok_or_else(|| {
            ParseError::truncated(format!("compound file: mini sector {s} of `{name}`"))
        })?;
        out.extend_from_slice(block);
    }
    if out.len() < stream.size {
        return Err(ParseError::truncated(format!(
            "compound file: `{name}` declares {} bytes, its mini sectors hold {}",
            stream.size,
            out.len()
        )));
    }
    out.truncate(stream.size);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn put(file: &mut [u8], at: usize, value: u32) {
        file[at..at + 4].copy_from_slice(&value.to_le_bytes());
    }

    /// A version-3 compound file (512-byte sectors): FAT, directory, mini FAT, mini stream, and
    /// a 70-byte stream `Small` in mini sectors 0 and 1.
    fn small_file() -> (Vec<u8>, Vec<u8>) {
        let mut file = vec![0u8; 5 * 512];
        file[..8].copy_from_slice(&SIGNATURE);
        file[24..34].copy_from_slice(&[0x3E, 0, 3, 0, 0xFE, 0xFF, 9, 0, 6, 0]);
        for (at, value) in [
            (44, 1),
            (48, 1),
            (56, 4096),
            (60, 2),
            (64, 1),
            (68, END_OF_CHAIN),
        ] {
            put(&mut file, at, value);
        }
        put(&mut file, 76, 0);
        for i in 1..HEADER_FAT_ENTRIES {
            put(&mut file, 76 + 4 * i, FREE);
        }
        let fat = [0xFFFF_FFFD, END_OF_CHAIN, END_OF_CHAIN, END_OF_CHAIN];
        for i in 0..128 {
            put(&mut file, 512 + 4 * i, *fat.get(i).unwrap_or(&FREE));
        }
        let mut entry = |index: usize, name: &str, kind: u8, start: u32, size: u32| {
            let at = 1024 + index * ENTRY_BYTES;
            for (k, unit) in name.encode_utf16().enumerate() {
                file[at + 2 * k..at + 2 * k + 2].copy_from_slice(&unit.to_le_bytes());
            }
            file[at + 64] = (2 * name.len() + 2) as u8;
            file[at + 66] = kind;
            put(&mut file, at + 116, start);
            put(&mut file, at + 120, size);
        };
        entry(0, "Root Entry", 5, 3, 128);
        entry(1, "Small", 2, 0, 70);
        for i in 0..128 {
            put(
                &mut file,
                1536 + 4 * i,
                [1, END_OF_CHAIN].get(i).copied().unwrap_or(FREE),
            );
        }
        let content: Vec<u8> = (0..70u8).collect();
        file[2048..2118].copy_from_slice(&content);
        (file, content)
    }

    #[test]
    fn a_short_stream_is_read_from_the_mini_stream() {
        let (file, content) = small_file();
        assert_eq!(read_stream(&file, "small").unwrap(), content);
        let err = read_stream(&file, "Other").unwrap_err().to_string();
        assert!(err.contains("no stream named `Other`"), "{err}");
    }

    #[test]
    fn a_looping_chain_and_a_missing_sector_are_errors() {
        let (mut file, _) = small_file();
        put(&mut file, 512 + 4, 1);
        let err = read_stream(&file, "Small").unwrap_err().to_string();
        assert!(err.contains("loops"), "{err}");
        let (file, _) = small_file();
        let err = read_stream(&file[..1800], "Small").unwrap_err().to_string();
        assert!(err.contains("beyond the end of the file"), "{err}");
    }
}
