//! Truncated, corrupted and lying files: every reader returns an error that names the file and
//! says what is wrong — never a panic, never an allocation sized by an unchecked header.
//!
//! What can be detected depends on the format, and the tests assert exactly that:
//! * X3P: any truncation (the zip directory sits at the end) and any corruption of compressed
//!   data (CRC-32) is an error.
//! * SDF ASCII, text matrices with an `h= w=` header: truncation before the last value, and any
//!   byte flipped inside the data (it becomes a non-ASCII, hence non-numeric, character).
//! * SUR, PLU: truncation anywhere before the end of the height block, and corrupted size
//!   fields. (A flipped byte inside raw binary heights is undetectable: no checksum.)
//! * Gwyddion-style text matrices and CSV line scans carry no point count, so a cut at a line
//!   boundary is not detectable; for them (and for every random flip) the test asserts only
//!   that no panic happens.

use crate::common;
use crate::readers_a_common;
use std::path::{Path, PathBuf};

use asperity_numerics::surface::io::parse_topography;
use readers_a_common::fixture;

/// How much of a file must be present for a reader to notice a cut.
fn detectable_length(path: &Path, bytes: &[u8]) -> usize {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or_default();
    let text = String::from_utf8_lossy(bytes);
    match ext {
        "x3p" | "sur" => bytes.len(),
        // Up to the line `*` that closes the data section.
        "sdf" if bytes.starts_with(b"aISO") => {
            let mut stars = text.match_indices('*').filter(|(i, _)| {
                let before = text[..*i].chars().next_back();
                before.is_none_or(|c| c == '\n')
            });
            stars.nth(1).map_or(bytes.len(), |(i, _)| i)
        }
        "sdf" => bytes.len(),
        // Header 500 B, rows and cols u32, float32 heights; the rest is a colour image.
        "plu" => {
            let word =
                |o: usize| u32::from_le_bytes([bytes[o], bytes[o + 1], bytes[o + 2], bytes[o + 3]]);
            508 + 4 * word(500) as usize * word(504) as usize
        }
        // Files with `h=`: a cut before the last line loses values or rows.
        "txt" if text.starts_with("h=") => text.trim_end().rfind('\n').unwrap_or(0),
        _ => 0,
    }
}

/// Every file of this branch's formats: shared data (when present) plus fixtures.
fn sample_files() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = [
        "sdf-1.sdf",
        "mm11_iso1_ascii_int32.sdf",
        "mm11_iso2_binary_f64.sdf",
        "sdf-1_binary_int32.sdf",
        "tiny_int32_masked.x3p",
    ]
    .iter()
    .map(|f| fixture(f))
    .collect();
    if let Some(dir) = common::data_dir() {
        for sub in [
            "x3p",
            "x3p/x3ptools-2024",
            "sdf",
            "sur",
            "plu",
            "txt",
            "csv",
        ] {
            let mut found: Vec<PathBuf> = std::fs::read_dir(dir.join(sub))
                .expect("data sub-folder must be readable")
                .map(|e| e.expect("directory entry").path())
                .filter(|p| p.is_file())
                .collect();
            found.sort();
            files.extend(found);
        }
    }
    files
}

fn name_of(path: &Path) -> String {
    path.file_name().unwrap().to_string_lossy().into_owned()
}

#[test]
fn truncated_files_give_errors_naming_the_file() {
    for path in sample_files() {
        let bytes = std::fs::read(&path).unwrap();
        let len = bytes.len();
        assert!(
            parse_topography(&path, &bytes).is_ok(),
            "{} must read whole",
            path.display()
        );
        let detectable = detectable_length(&path, &bytes);
        let mut cuts = vec![0, 1, 7, 16, 64, 100, 200, 300, 511, 600];
        cuts.extend([
            len / 10,
            len / 4,
            len / 2,
            3 * len / 4,
            9 * len / 10,
            len - 2,
            len - 1,
        ]);
        cuts.extend([detectable.saturating_sub(1), detectable.saturating_sub(7)]);
        cuts.retain(|&c| c < len);
        for cut in cuts {
            let result = parse_topography(&path, &bytes[..cut]);
            if cut < detectable {
                let err = result.expect_err(&format!("{} cut at {cut} must fail", path.display()));
                assert!(
                    err.to_string().contains(&name_of(&path)),
                    "error must name the file: {err}"
                );
            }
        }
    }
}

#[test]
fn corrupted_bytes_never_panic_and_structural_damage_is_an_error() {
    for path in sample_files() {
        let bytes = std::fs::read(&path).unwrap();
        let len = bytes.len();
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .unwrap_or_default();
        // Deterministic pseudo-random positions (64-bit LCG, Knuth's MMIX constants).
        let mut state = len as u64;
        let mut positions: Vec<usize> = (0..24)
            .map(|_| {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (state >> 33) as usize % len
            })
            .collect();
        // Positions whose corruption the format makes detectable.
        let must_fail: Vec<usize> = match ext {
            // Inside the compressed data of the main entries (CRC-32 / inflate errors); in the
            // 1 kB fixture len/2 is a local header, whose name field zip readers ignore.
            "x3p" if len > 4000 => vec![len / 4, len / 2],
            "x3p" => vec![len / 4],
            "sur" => vec![0, 108, 112],
            "plu" => vec![500, 504],
            "sdf" if bytes.starts_with(b"aISO") => vec![0, detectable_length(&path, &bytes) - 3],
            // Magic, NumPoints, DataType.
            "sdf" => vec![0, 42, 79],
            "txt" | "csv" => vec![len / 2, 3 * len / 4],
            _ => vec![],
        };
        positions.extend(&must_fail);
        for pos in positions {
            let mut damaged = bytes.clone();
            damaged[pos] ^= 0xFF;
            let result = parse_topography(&path, &damaged);
            if must_fail.contains(&pos) {
                let err = result.expect_err(&format!(
                    "{} with byte {pos} flipped must fail",
                    path.display()
                ));
                assert!(err.to_string().contains(&name_of(&path)), "{err}");
            }
        }
    }
}

/// Headers that claim far more points than the file holds are refused before allocating.
#[test]
fn lying_headers_are_refused_cheaply() {
    // SDF ASCII claiming 60000 × 60000 points.
    let sdf = std::fs::read(fixture("sdf-1.sdf")).unwrap();
    let text = String::from_utf8(sdf)
        .unwrap()
        .replace("NumPoints = 7", "NumPoints = 60000")
        .replace("NumProfiles = 4", "NumProfiles = 60000");
    let err = parse_topography(Path::new("lie.sdf"), text.as_bytes()).unwrap_err();
    assert!(err.to_string().contains("truncated"), "{err}");

    // Binary SDF claiming 65535 × 65535 float64 values.
    let mut bin = std::fs::read(fixture("mm11_iso2_binary_f64.sdf")).unwrap();
    bin[42..46].copy_from_slice(&[0xFF; 4]);
    let err = parse_topography(Path::new("lie.sdf"), &bin).unwrap_err();
    assert!(err.to_string().contains("truncated"), "{err}");

    // A SUR header claiming 60000 × 60000 int32 points (consistent point count, no data).
    let mut sur = vec![0u8; 512];
    sur[..12].copy_from_slice(b"DIGITAL SURF");
    sur[98..100].copy_from_slice(&32u16.to_le_bytes());
    sur[108..112].copy_from_slice(&60_000i32.to_le_bytes());
    sur[112..116].copy_from_slice(&60_000i32.to_le_bytes());
    sur[116..120].copy_from_slice(&3_600_000_000u32.to_le_bytes());
    for (offset, value) in [(120, 1.0f32), (124, 1.0), (128, 1.0)] {
        sur[offset..offset + 4].copy_from_slice(&value.to_le_bytes());
    }
    for offset in [180, 196, 212] {
        sur[offset] = b'm';
    }
    let err = parse_topography(Path::new("lie.sur"), &sur).unwrap_err();
    assert!(err.to_string().contains("truncated"), "{err}");
}

/// npy has no real sample file: a 40 × 30 float64 map built here, cut at every length.
#[test]
fn truncated_npy_is_an_error_at_every_length() {
    let dict = "{'descr': '<f8', 'fortran_order': False, 'shape': (30, 40), }";
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend((dict.len() as u16).to_le_bytes());
    bytes.extend(dict.as_bytes());
    bytes.extend((0..1200).flat_map(|i| (f64::from(i) * 1e-9).to_le_bytes()));
    let path = Path::new("map.npy");
    assert!(parse_topography(path, &bytes).is_ok());
    for cut in 0..bytes.len() {
        let err = parse_topography(path, &bytes[..cut]).expect_err("a cut npy must fail");
        assert!(err.to_string().contains("map.npy"), "{err}");
    }
}

/// A device, a pipe or a directory is refused by its file type before anything is read
/// (`/dev/zero` would otherwise be read until memory runs out).
#[cfg(unix)]
#[test]
fn files_that_are_not_regular_are_refused_before_reading() {
    for path in ["/dev/zero", "/dev/null", "/tmp"] {
        let error = asperity_numerics::surface::io::read_topography(Path::new(path))
            .expect_err("not a regular file")
            .to_string();
        assert!(
            error.contains(path) && error.contains("not a regular file"),
            "{path}: {error}"
        );
    }
}
