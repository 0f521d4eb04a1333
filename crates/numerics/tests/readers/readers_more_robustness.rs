//! Truncated, corrupted and lying files of the formats read by `readers_more` must give a clear
//! error naming the file (or a consistent result), never a panic and never an allocation driven
//! by a header value: a header claiming 10⁹ points in a small file is an error, at once.
//!
//! Data folder as in `readers_b.rs`; missing → fail under `CI`, skip otherwise.

use crate::common;
use std::path::{Path, PathBuf};
use std::time::Instant;

use asperity_numerics::surface::io::{parse_topography, ReadError, TopographyData};

/// Binary files: every cut inside them must fail.
const BINARY: [&str; 9] = [
    "tmd/tmd-1.tmd",
    "bcrf/bcrf-1.bcrf",
    "ibw/spot_1-1000nm.ibw",
    "ibw/10x10-one_channel_without_name.ibw",
    "ps-tiff/example_ps.tiff",
    "wsxm/top-1.top",
    "wsxm/stp-1.stp",
    "nc/nc-1.nc",
    "h5/multiple_data_sets.h5",
];

fn load(dir: &Path, file: &str) -> (PathBuf, Vec<u8>) {
    let path = dir.join(file);
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    (path, bytes)
}

/// An error naming the file, or a consistent map or line scan.
fn check_outcome(path: &Path, bytes: &[u8], what: &str) {
    match parse_topography(path, bytes) {
        Err(ReadError::Parse { path: p, .. }) => {
            assert_eq!(p, path, "{what}: error names the file")
        }
        Err(ReadError::UnknownFormat { path: p }) => assert_eq!(p, path, "{what}"),
        Err(other) => panic!("{what}: unexpected error kind {other}"),
        Ok(t) => match t.data {
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
    for file in BINARY {
        let (path, bytes) = load(&dir, file);
        let n = bytes.len();
        let cuts = [
            0,
            1,
            3,
            8,
            16,
            40,
            64,
            100,
            383,
            500,
            1000,
            4096,
            n / 4,
            n / 2,
        ];
        for cut in cuts.into_iter().filter(|&c| c < n) {
            let err = parse_topography(&path, &bytes[..cut])
                .map(|_| ())
                .expect_err(&format!("{file} cut at {cut} bytes must fail"));
            let text = err.to_string();
            assert!(
                text.contains(file),
                "{file} cut at {cut}: `{text}` does not name the file"
            );
        }
        check_outcome(
            &path,
            &bytes[..n - 1],
            &format!("{file} minus its last byte"),
        );
    }
    // A text profile cut inside its data is a shorter profile; cut in its header it is an error.
    let (path, bytes) = load(&dir, "hfm/hfm-1.hfm");
    for cut in [0, 5, 12, 20] {
        assert!(
            parse_topography(&path, &bytes[..cut]).is_err(),
            "hfm cut at {cut}"
        );
    }
    check_outcome(&path, &bytes[..bytes.len() / 2], "hfm cut in half");
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
    for (k, file) in BINARY.iter().chain(["hfm/hfm-1.hfm"].iter()).enumerate() {
        let (path, mut bytes) = load(&dir, file);
        let n = bytes.len();
        let mut spots = positions(k as u64 + 1, 80, n.min(4096));
        spots.extend(positions(k as u64 + 101, 20, n));
        for spot in spots {
            bytes[spot] ^= 0xFF;
            check_outcome(&path, &bytes, &format!("{file} with byte {spot} flipped"));
            bytes[spot] ^= 0xFF;
        }
    }
}

/// Fails fast (under a second) with an error naming `file`.
#[track_caller]
fn refused_fast(file: &str, bytes: &[u8], expected: &str) {
    let start = Instant::now();
    let err = parse_topography(Path::new(file), bytes)
        .map(|_| ())
        .expect_err(&format!("{file}: a header claiming 10⁹ points must fail"));
    assert!(
        start.elapsed().as_secs_f64() < 1.0,
        "{file}: {:?}",
        start.elapsed()
    );
    let text = err.to_string();
    assert!(
        text.contains(file) && text.contains(expected),
        "{file}: {text}"
    );
}

/// 31 623² ≈ 10⁹ points.
const HUGE: u32 = 31_623;

/// Resets the IBW header checksum (the 16-bit words of the first 384 bytes sum to 0).
fn fix_ibw_checksum(bytes: &mut [u8]) {
    bytes[2..4].copy_from_slice(&[0, 0]);
    let sum = bytes[..384].chunks_exact(2).fold(0u16, |a, w| {
        a.wrapping_add(u16::from_le_bytes([w[0], w[1]]))
    });
    bytes[2..4].copy_from_slice(&0u16.wrapping_sub(sum).to_le_bytes());
}

#[test]
fn headers_claiming_a_billion_points_are_errors() {
    let Some(dir) = common::data_dir() else {
        return;
    };
    let (_, tmd) = load(&dir, "tmd/tmd-1.tmd");
    let mut small = tmd[..2048].to_vec();
    small[56..60].copy_from_slice(&HUGE.to_le_bytes());
    small[60..64].copy_from_slice(&HUGE.to_le_bytes());
    refused_fast("huge.tmd", &small, "points");

    let (_, ibw) = load(&dir, "ibw/10x10-one_channel_without_name.ibw");
    let mut small = ibw.clone();
    small[64 + 68..64 + 72].copy_from_slice(&HUGE.to_le_bytes());
    small[64 + 72..64 + 76].copy_from_slice(&HUGE.to_le_bytes());
    fix_ibw_checksum(&mut small);
    refused_fast("huge.ibw", &small, "points");

    let (_, nc) = load(&dir, "nc/nc-1.nc");
    let mut small = nc.clone();
    small[0x18..0x1C].copy_from_slice(&HUGE.to_be_bytes());
    small[0x24..0x28].copy_from_slice(&HUGE.to_be_bytes());
    refused_fast("huge.nc", &small, "points");

    let (_, h5) = load(&dir, "h5/multiple_data_sets.h5");
    let mut small = h5.clone();
    // The dimensions in dataset1's dataspace message (object header at 800).
    small[832..840].copy_from_slice(&u64::from(HUGE).to_le_bytes());
    small[840..848].copy_from_slice(&u64::from(HUGE).to_le_bytes());
    refused_fast("huge.h5", &small, "points");

    let (_, tiff) = load(&dir, "ps-tiff/example_ps.tiff");
    let mut small = tiff.clone();
    let header = 1_050_617; // the offset of tag 50435 in this file
    small[header + 100..header + 104].copy_from_slice(&HUGE.to_le_bytes());
    small[header + 104..header + 108].copy_from_slice(&HUGE.to_le_bytes());
    refused_fast("huge.tiff", &small, "points");

    let mut bcrf = format!(
        "fileformat = bcrf\nheadersize = 2048\nxpixels = {HUGE}\nypixels = {HUGE}\n\
         xlength = 1\nylength = 1\nintelmode = 1\n"
    )
    .into_bytes();
    bcrf.resize(2048 + 1024, 0);
    refused_fast("huge.bcrf", &bcrf, "points");

    let header = format!(
        "[General Info]\nNumber of columns: {HUGE}\nNumber of rows: {HUGE}\n\
         Image Data Type: double\nZ Amplitude: 1 nm\n[Control]\nX Amplitude: 1 nm\n\
         Y Amplitude: 1 nm\n[Header end]\n"
    );
    let preamble = "WSxM file copyright UAM\nSxM Image file\nImage header size: ";
    let size = preamble.len() + 5 + header.len();
    let mut wsxm = format!("{preamble}{size:04}\n{header}").into_bytes();
    assert_eq!(wsxm.len(), size);
    wsxm.resize(size + 1024, 0);
    refused_fast("huge.top", &wsxm, "points");
}

#[test]
fn a_damaged_ibw_header_fails_its_checksum() {
    let Some(dir) = common::data_dir() else {
        return;
    };
    let (path, mut bytes) = load(&dir, "ibw/spot_1-1000nm.ibw");
    bytes[64 + 84] ^= 0x01; // the x spacing
    let err = parse_topography(&path, &bytes).map(|_| ()).unwrap_err();
    assert!(err.to_string().contains("checksum"), "{err}");
}

#[test]
fn an_hdf5_btree_pointing_to_itself_fails_fast() {
    let Some(dir) = common::data_dir() else {
        return;
    };
    let (path, mut bytes) = load(&dir, "h5/multiple_data_sets.h5");
    // The root group's B-tree node at byte 136: make it an inner node whose child is itself.
    bytes[136 + 5] = 1;
    bytes[168..176].copy_from_slice(&136u64.to_le_bytes());
    let start = Instant::now();
    let err = parse_topography(&path, &bytes).map(|_| ()).unwrap_err();
    assert!(start.elapsed().as_secs_f64() < 1.0, "{:?}", start.elapsed());
    assert!(err.to_string().contains("B-tree"), "{err}");
}
