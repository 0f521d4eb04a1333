//! Truncated, corrupted and lying files of the formats read by `readers_b` must give a clear
//! error (or a consistent result) — never a panic, never an allocation driven by a header value.
//!
//! Data folder as in `readers_b.rs`: `$ASPERITY_TEST_DATA`, else
//! `CARGO_MANIFEST_DIR/../shared/data/topography`; missing → fail under `CI`, skip otherwise.

use crate::common;
use std::path::{Path, PathBuf};

use asperity_numerics::surface::io::{parse_topography, ReadError, TopographyData};

const FILES: [&str; 6] = [
    "metropro-dat/metropro-1.dat",
    "opd/opd-1.opd",
    "di/di-5.di",
    "gwy/file_square.gwy",
    "al3d/al3d-1.al3d",
    "zon/test_1.zon",
];
fn load(dir: &Path, file: &str) -> (PathBuf, Vec<u8>) {
    let path = dir.join(file);
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    (path, bytes)
}

/// A parse result is acceptable when it is an error naming the file, or a consistent map.
fn check_outcome(path: &Path, bytes: &[u8], what: &str) {
    match parse_topography(path, bytes) {
        Err(ReadError::Parse { path: p, .. }) => {
            assert_eq!(p, path, "{what}: error names the file")
        }
        Err(other) => panic!("{what}: unexpected error kind {other}"),
        Ok(t) => match t.data {
            // HeightMap::new already rejects infinite heights and bad spacings.
            TopographyData::Areal(m) => assert_eq!(m.heights().len(), m.nx() * m.ny(), "{what}"),
            TopographyData::Line(l) => assert_eq!(l.x.len(), l.z.len(), "{what}"),
        },
    }
}

#[test]
fn truncated_files_give_errors_naming_the_file() {
    let Some(dir) = common::data_dir() else {
        return;
    };
    for file in FILES {
        let (path, bytes) = load(&dir, file);
        let n = bytes.len();
        // Cuts inside the magic, the header, the directory/tag area and the height data: all
        // must fail (each file's height data extends past n/2).
        for cut in [
            0,
            1,
            3,
            4,
            8,
            16,
            17,
            64,
            100,
            500,
            1000,
            4096,
            n / 4,
            n / 2,
        ] {
            let err = parse_topography(&path, &bytes[..cut])
                .map(|_| ())
                .expect_err(&format!("{file} cut at {cut} bytes must fail"));
            let text = err.to_string();
            assert!(
                text.contains(file),
                "{file} cut at {cut}: `{text}` does not name the file"
            );
        }
        // Cutting the last byte may leave the height data intact (e.g. the second Nanoscope
        // channel loses a byte): either outcome is fine, a panic is not.
        check_outcome(
            &path,
            &bytes[..n - 1],
            &format!("{file} minus its last byte"),
        );
    }
}

/// Deterministic positions (64-bit LCG, Knuth's MMIX constants) below `bound`.
fn positions(seed: u64, count: usize, bound: usize) -> Vec<usize> {
    let mut state = seed;
    (0..count)
        .map(|_| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            ((state >> 33) as usize) % bound
        })
        .collect()
}

#[test]
fn flipped_bytes_never_panic() {
    let Some(dir) = common::data_dir() else {
        return;
    };
    for (k, file) in FILES.iter().enumerate() {
        let (path, mut bytes) = load(&dir, file);
        let n = bytes.len();
        // Headers and directories sit at the start (all formats) and at the end (ZIP directory
        // of .zon, trailing blocks of .opd): probe both densely, and the body sparsely.
        let mut spots = positions(k as u64 + 1, 60, n.min(4096));
        spots.extend(positions(k as u64 + 101, 30, n));
        spots.extend(
            positions(k as u64 + 201, 30, n.min(8192))
                .into_iter()
                .map(|p| n - 1 - p),
        );
        for spot in spots {
            bytes[spot] ^= 0xFF;
            check_outcome(&path, &bytes, &format!("{file} with byte {spot} flipped"));
            bytes[spot] ^= 0xFF;
        }
    }
}

/// Overwrites `bytes[at..]` with `value` and expects a parse error mentioning `expected`.
fn expect_error(path: &Path, bytes: &[u8], at: usize, value: &[u8], expected: &str) {
    let mut edited = bytes.to_vec();
    edited[at..at + value.len()].copy_from_slice(value);
    let err = parse_topography(path, &edited)
        .map(|_| ())
        .expect_err(&format!("{} edited at {at} must fail", path.display()));
    let text = err.to_string();
    assert!(
        text.contains(expected),
        "{}: `{text}` lacks `{expected}`",
        path.display()
    );
}

#[test]
fn lying_headers_fail_before_allocating() {
    let Some(dir) = common::data_dir() else {
        return;
    };
    // MetroPro: 65535 × 65535 phase array (cn_width, cn_height at bytes 68, 70, big-endian).
    let (path, bytes) = load(&dir, "metropro-dat/metropro-1.dat");
    expect_error(
        &path,
        &bytes,
        68,
        &[0xFF, 0xFF, 0xFF, 0xFF],
        "does not match",
    );
    // OPD: the `Raw` array header (at byte 24020 in this file) claims 65535 × 65535 values.
    let (path, bytes) = load(&dir, "opd/opd-1.opd");
    assert_eq!(
        &bytes[24020..24024],
        &[0x80, 0x02, 0xE0, 0x01],
        "Raw array header moved"
    );
    expect_error(
        &path,
        &bytes,
        24020,
        &[0xFF, 0xFF, 0xFF, 0xFF],
        "not 65535 × 65535",
    );
    // AL3D: 10^12 columns (tag value field of `Cols`, tag 2, at byte 17 + 2·52 + 20).
    let (path, bytes) = load(&dir, "al3d/al3d-1.al3d");
    expect_error(
        &path,
        &bytes,
        17 + 2 * 52 + 20,
        b"1000000000000\0",
        "truncated",
    );
    // Nanoscope: 99 999 999 samples per line in the ZSensor channel.
    let (path, bytes) = load(&dir, "di/di-5.di");
    let key = b"\\Samps/line: 512\r";
    let image_list = bytes
        .windows(17)
        .position(|w| w == b"\\*Ciao image list")
        .unwrap_or_else(|| panic!("no image list in di-5.di"));
    // The first `Samps/line` after the first image list belongs to ZSensor.
    let at = bytes[image_list..]
        .windows(key.len())
        .position(|w| w == key)
        .map(|p| image_list + p + key.len() - 4)
        .unwrap_or_else(|| panic!("no `\\Samps/line: 512` in di-5.di"));
    // Same-length edit "512" → "999" keeps the header layout; 999 × 512 × 4 B still fits in
    // the file, so only the `\Data length` cross-check can catch it.
    expect_error(&path, &bytes, at, b"999", "Data length");
    // GWY: the data field's `xres` no longer matches the data array.
    let (path, bytes) = load(&dir, "gwy/file_square.gwy");
    let key = b"xres\0i";
    let at = bytes
        .windows(key.len())
        .position(|w| w == key)
        .map(|p| p + key.len())
        .unwrap_or_else(|| panic!("no `xres` in file_square.gwy"));
    expect_error(&path, &bytes, at, &[0xFF, 0xFF, 0xFF, 0x7F], "expected");
}
