//! Damaged copies of the issue-34 instrument files (`readers_instruments`): truncated anywhere
//! and with flipped bytes they give an error naming the file (or a consistent map), never a
//! panic; headers claiming 10⁹ points, or more points than the file holds, fail before the
//! heights are allocated.

use crate::common;
use std::path::{Path, PathBuf};

use asperity_numerics::surface::io::{parse_topography, ReadError, TopographyData};

const FILES: [&str; 5] = [
    "nid/nid-1.nid",
    "mi/mi-1.mi",
    "nms/nms-1.nms",
    "frt/frt-1.frt",
    "opdx/opdx-3.opdx",
];

fn load(dir: &Path, file: &str) -> (PathBuf, Vec<u8>) {
    let path = dir.join(file);
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    (path, bytes)
}

/// An error naming the file, or a consistent result.
fn check_outcome(path: &Path, bytes: &[u8], what: &str) {
    match parse_topography(path, bytes) {
        Err(ReadError::Parse { path: p, .. }) => assert_eq!(p, path, "{what}"),
        Err(other) => panic!("{what}: unexpected error kind {other}"),
        Ok(t) => match t.data {
            TopographyData::Areal(m) => assert_eq!(m.heights().len(), m.nx() * m.ny(), "{what}"),
            TopographyData::Line(l) => assert_eq!(l.x.len(), l.z.len(), "{what}"),
        },
    }
}

#[test]
fn truncated_instrument_files_fail_naming_the_file() {
    let Some(dir) = common::data_dir() else {
        return;
    };
    for file in FILES {
        let (path, bytes) = load(&dir, file);
        let n = bytes.len();
        for cut in [
            0,
            1,
            3,
            8,
            16,
            17,
            64,
            100,
            500,
            1000,
            1400,
            4096,
            n / 4,
            n / 2,
        ] {
            let err = parse_topography(&path, &bytes[..cut])
                .map(|_| ())
                .expect_err(&format!("{file} cut at {cut} bytes must fail"));
            assert!(err.to_string().contains(file), "{file} cut at {cut}: {err}");
        }
        // NMS ends with an intensity block it does not read: a lost last byte may go unseen.
        check_outcome(
            &path,
            &bytes[..n - 1],
            &format!("{file} minus its last byte"),
        );
    }
}

#[test]
fn instrument_files_with_flipped_bytes_never_panic() {
    let Some(dir) = common::data_dir() else {
        return;
    };
    for (k, file) in FILES.iter().enumerate() {
        let (path, mut bytes) = load(&dir, file);
        let n = bytes.len();
        let mut state = k as u64 + 1;
        let mut next = |bound: usize| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            ((state >> 33) as usize) % bound
        };
        let spots: Vec<usize> = (0..150)
            .map(|i| {
                if i < 100 {
                    next(n.min(32_768))
                } else {
                    next(n)
                }
            })
            .collect();
        for spot in spots {
            bytes[spot] ^= 0xFF;
            check_outcome(&path, &bytes, &format!("{file} with byte {spot} flipped"));
            bytes[spot] ^= 0xFF;
        }
    }
}

/// `bytes` with the first `from` replaced by `to`.
fn replaced(bytes: &[u8], from: &[u8], to: &[u8]) -> Vec<u8> {
    let at = bytes
        .windows(from.len())
        .position(|w| w == from)
        .unwrap_or_else(|| panic!("{:?} not found", String::from_utf8_lossy(from)));
    [&bytes[..at], to, &bytes[at + from.len()..]].concat()
}

/// `bytes` with `value` written at `at`.
fn patched(bytes: &[u8], at: usize, value: &[u8]) -> Vec<u8> {
    let mut b = bytes.to_vec();
    b[at..at + value.len()].copy_from_slice(value);
    b
}

fn expect_error(path: &Path, bytes: &[u8], expected: &str) {
    let err = parse_topography(path, bytes)
        .map(|_| ())
        .expect_err(&format!("{}: a lying header must fail", path.display()));
    assert!(
        err.to_string().contains(expected),
        "`{err}` lacks `{expected}`"
    );
}

#[test]
fn headers_claiming_a_billion_points_fail_before_allocating() {
    let Some(dir) = common::data_dir() else {
        return;
    };
    let billion = 1_000_000_000u32.to_le_bytes();
    let too_many = "more than the 134217728 points";

    let (path, b) = load(&dir, "nid/nid-1.nid");
    let lie = replaced(&b, b"Points=256\r\nLines=256\r\nFrame=Scan forward\r\nCurLine=255\r\nDim0Name=X*\r\nDim0Unit=m\r\nDim0Range=2e-05\r\nDim0Min=0\r\nDim1Name=Y*\r\nDim1Unit=m\r\nDim1Range=2e-05\r\nDim1Min=0\r\nDim2Name=Z-Axis", b"Points=1000000000\r\nLines=1\r\nFrame=Scan forward\r\nCurLine=255\r\nDim0Name=X*\r\nDim0Unit=m\r\nDim0Range=2e-05\r\nDim0Min=0\r\nDim1Name=Y*\r\nDim1Unit=m\r\nDim1Range=2e-05\r\nDim1Min=0\r\nDim2Name=Z-Axis");
    expect_error(&path, &lie, too_many);
    let lie = replaced(
        &b,
        b"Points=256\r\nLines=256\r\nFrame=Scan forward",
        b"Points=9000\r\nLines=9000\r\nFrame=Scan forward",
    );
    expect_error(&path, &lie, "truncated");

    let (path, b) = load(&dir, "mi/mi-1.mi");
    expect_error(
        &path,
        &replaced(&b, b"xPixels       256", b"xPixels       1000000000"),
        too_many,
    );
    expect_error(
        &path,
        &replaced(&b, b"xPixels       256", b"xPixels       9000"),
        "truncated",
    );

    // NMS: nx (u32) at byte 1368; FRT: nx (u32) at byte 38, the body of block 0x66.
    let (path, b) = load(&dir, "nms/nms-1.nms");
    expect_error(&path, &patched(&b, 1368, &billion), too_many);
    expect_error(
        &path,
        &patched(&b, 1368, &9000u32.to_le_bytes()),
        "truncated",
    );
    let (path, b) = load(&dir, "frt/frt-1.frt");
    expect_error(&path, &patched(&b, 38, &billion), too_many);
    expect_error(
        &path,
        &patched(&b, 38, &9000u32.to_le_bytes()),
        "height block",
    );

    // OPDx: NumPoints (u64) of the profile.
    let (path, b) = load(&dir, "opdx/opdx-3.opdx");
    let at = b.windows(10).position(|w| w == b"NumPoints\x0b").unwrap() + 10;
    expect_error(
        &path,
        &patched(&b, at, &1_000_000_000u64.to_le_bytes()),
        too_many,
    );
    expect_error(
        &path,
        &patched(&b, at, &9000u64.to_le_bytes()),
        "bytes of data for 9000",
    );
}
