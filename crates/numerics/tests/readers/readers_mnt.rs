//! The Digital Surf `.mnt` reader against `mnt/mnt-1.mnt` of the shared folder (SOURCES.md and
//! the `SurfaceTopography_1.27.1` entry of reference_values.json, lengths converted to metres;
//! relative 1e-6), and against damaged copies: truncated, bytes flipped, and headers that lie
//! about the container or the number of points, which must fail before the heights are
//! allocated.

use crate::common;
use crate::readers_a_common::{assert_rel, plain_stats};
use std::path::{Path, PathBuf};

use asperity_numerics::surface::io::{
    declared_points, detect_format, parse_topography, ReadError, TopographyData,
};

const FILE: &str = "mnt/mnt-1.mnt";
const UM: f64 = 1e-6;
const RTOL: f64 = 1e-6;

fn load() -> Option<(PathBuf, Vec<u8>)> {
    let path = common::data_dir()?.join(FILE);
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    Some((path, bytes))
}

#[test]
fn mnt_1_matches_surface_topography() {
    let Some((path, bytes)) = load() else { return };
    assert_eq!(detect_format(&path, &bytes).map(|r| r.name), Some("mnt"));
    // Compressed: memory estimates take the count from the header, not from the file size.
    assert_eq!(declared_points(&path), Some(576_000));
    let t = parse_topography(&path, &bytes).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(t.channel.as_deref(), Some("A48_10x_P1"));
    assert_eq!(t.channels, ["A48_10x_P1"]);
    assert_eq!(
        t.metadata.get("vendor").map(String::as_str),
        Some("Digital Surf")
    );
    let TopographyData::Areal(map) = &t.data else {
        panic!("{FILE}: not an areal map")
    };
    assert_eq!((map.nx(), map.ny()), (960, 600));
    assert_rel("dx", map.dx(), 1.853393117831074 * UM, RTOL);
    assert_rel("dy", map.dy(), 1.8545542570951588 * UM, RTOL);
    let (lx, ly) = map.size();
    assert_rel("Lx", lx, 1779.257393117831 * UM, RTOL);
    assert_rel("Ly", ly, 1112.7325542570952 * UM, RTOL);
    assert_eq!(map.missing_count(), 0);
    let s = plain_stats(map.heights().iter());
    assert_rel("Sq", s.sq, 0.024560210679676394 * UM, RTOL);
    assert_rel("Sa", s.sa, 0.00798960995774422 * UM, RTOL);
    assert_rel("Sz", s.sz, 2.2237586999999976 * UM, RTOL);
    let mean = map.heights().iter().sum::<f64>() / map.heights().len() as f64;
    assert_rel("mean", mean, 50.631545534565205 * UM, RTOL);
}

/// An error naming the file, or a consistent map.
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
fn truncated_mnt_fails_naming_the_file() {
    let Some((path, bytes)) = load() else { return };
    let n = bytes.len();
    for cut in [0, 1, 8, 30, 64, 512, 4096, 8192, 20_000, n / 4, n / 2] {
        let err = parse_topography(&path, &bytes[..cut])
            .map(|_| ())
            .expect_err(&format!("{FILE} cut at {cut} bytes must fail"));
        assert!(err.to_string().contains(FILE), "cut at {cut}: {err}");
    }
    // The last sectors may belong to a stream the reader does not need.
    check_outcome(&path, &bytes[..n - 1], "mnt-1 minus its last byte");
}

#[test]
fn mnt_with_flipped_bytes_never_panics() {
    let Some((path, mut bytes)) = load() else {
        return;
    };
    let n = bytes.len();
    let mut state = 7u64;
    let mut next = |bound: usize| {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((state >> 33) as usize) % bound
    };
    // The container header and directory, the tree of ScopedContents (sector 37, from byte 155 648), and
    // anywhere.
    let spots: Vec<usize> = (0..150)
        .map(|i| match i {
            0..=49 => next(16_384),
            50..=99 => 155_648 + next(8_192),
            _ => next(n),
        })
        .collect();
    for spot in spots {
        bytes[spot] ^= 0xFF;
        check_outcome(&path, &bytes, &format!("{FILE} with byte {spot} flipped"));
        bytes[spot] ^= 0xFF;
    }
}

/// `bytes` with the first occurrence of `from` replaced by `to` (same length).
fn replaced(bytes: &[u8], from: &[u8], to: &[u8]) -> Vec<u8> {
    let at = bytes
        .windows(from.len())
        .position(|w| w == from)
        .unwrap_or_else(|| panic!("{from:02x?} not found"));
    let mut out = bytes.to_vec();
    out[at..at + to.len()].copy_from_slice(to);
    out
}

fn expect_error(path: &Path, bytes: &[u8], expected: &str) {
    let err = parse_topography(path, bytes)
        .map(|_| ())
        .expect_err("a lying header must fail");
    let text = err.to_string();
    assert!(text.contains(expected), "`{text}` lacks `{expected}`");
}

/// The height block's head: tag 1, 4 bytes, 576 000 points; tag 2, its length; 2 304 000 bytes.
fn block_head(points: u32, bytes: u64) -> Vec<u8> {
    let mut b = vec![1, 0, 4, 0, 0, 0, 0, 0, 0, 0];
    b.extend_from_slice(&points.to_le_bytes());
    b.extend_from_slice(&[2, 0, 0xf2, 0xbf, 0x15, 0, 0, 0, 0, 0]);
    b.extend_from_slice(&bytes.to_le_bytes());
    b
}

/// The x axis's point count: tag 6 (u32 1), then tag 1 (u32 960), then tag 2 (u32 0).
fn x_points(points: u32) -> Vec<u8> {
    let mut b = vec![
        6, 0, 4, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 4, 0, 0, 0, 0, 0, 0, 0,
    ];
    b.extend_from_slice(&points.to_le_bytes());
    b
}

#[test]
fn mnt_headers_that_lie_fail_before_allocating() {
    let Some((path, b)) = load() else { return };
    // The x axis claims 2³¹ − 1 points (× 600 rows).
    let lie = replaced(&b, &x_points(960), &x_points(i32::MAX as u32));
    expect_error(&path, &lie, "more than the 134217728 points");
    // The height block claims 10⁹ points and 4 · 10⁹ bytes.
    let lie = replaced(
        &b,
        &block_head(576_000, 2_304_000),
        &block_head(1_000_000_000, 4_000_000_000),
    );
    expect_error(&path, &lie, "the height block 1000000000");
    // The container claims 2³¹ FAT sectors, and ScopedContents 2⁴⁰ bytes (directory entry 2 in
    // sector 2, its size at byte 120).
    let patched = |at: usize, value: &[u8]| {
        let mut lie = b.clone();
        lie[at..at + value.len()].copy_from_slice(value);
        lie
    };
    expect_error(
        &path,
        &patched(44, &0x8000_0000u32.to_le_bytes()),
        "FAT sectors",
    );
    let size_at = 3 * 4096 + 2 * 128 + 120;
    expect_error(
        &path,
        &patched(size_at, &(1u64 << 40).to_le_bytes()),
        "declares 1099511627776 bytes",
    );
}
