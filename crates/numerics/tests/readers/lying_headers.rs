//! Headers that lie about sizes: copies of the shared files (and fixtures) whose header claims
//! 10⁹ points, more points than the file holds, or a structure that loops. Each must fail at
//! once (under a second), before the heights are allocated, with an error naming the file and
//! saying what is wrong.

use std::path::{Path, PathBuf};
use std::time::Instant;

use asperity_numerics::surface::io::parse_topography;

use crate::common;
use crate::damage::{find, load, patched, replaced};
use crate::readers_a_common::fixture;

/// 31 623² ≈ 10⁹ points.
const HUGE: u32 = 31_623;
/// The message of a header declaring more than `MAX_POINTS`.
const TOO_MANY: &str = "more than the 134217728 points";

/// The size of the NID file's first data set.
const NID_FORWARD: &[u8] = b"Points=256\r\nLines=256\r\nFrame=Scan forward";

/// A damaged copy: the file (relative to the shared folder), the edit and a word of the error.
type Lie = (&'static str, fn(&[u8]) -> Vec<u8>, &'static str);

/// The lies told in copies of the shared files.
const LIES: &[Lie] = &[
    // MetroPro: a 65535 × 65535 phase array (cn_width, cn_height at bytes 68, 70, big-endian).
    (
        "metropro-dat/metropro-1.dat",
        |b| patched(b, 68, &[0xFF; 4]),
        "does not match",
    ),
    // OPD: the `Raw` array header (at byte 24020 in this file) claims 65535 × 65535 values.
    ("opd/opd-1.opd", opd_raw_array, "not 65535 × 65535"),
    // AL3D: 10¹² columns (the value of tag 2, `Cols`).
    (
        "al3d/al3d-1.al3d",
        |b| patched(b, 17 + 2 * 52 + 20, b"1000000000000\0"),
        "truncated",
    ),
    // Nanoscope: 999 samples per ZSensor line; 999 × 512 × 4 B still fits in the file, so only
    // the `\Data length` cross-check can catch it.
    ("di/di-5.di", nanoscope_samples, "Data length"),
    // GWY: the data field's `xres` no longer matches its data array.
    (
        "gwy/file_square.gwy",
        |b| patched(b, find(b, b"xres\0i") + 6, &[0xFF, 0xFF, 0xFF, 0x7F]),
        "expected",
    ),
    // NID: 10⁹ points per line, then 9000 × 9000 points.
    (
        "nid/nid-1.nid",
        |b| {
            replaced(
                b,
                NID_FORWARD,
                b"Points=1000000000\r\nLines=1\r\nFrame=Scan forward",
            )
        },
        TOO_MANY,
    ),
    (
        "nid/nid-1.nid",
        |b| {
            replaced(
                b,
                NID_FORWARD,
                b"Points=9000\r\nLines=9000\r\nFrame=Scan forward",
            )
        },
        "truncated",
    ),
    (
        "mi/mi-1.mi",
        |b| replaced(b, b"xPixels       256", b"xPixels       1000000000"),
        TOO_MANY,
    ),
    (
        "mi/mi-1.mi",
        |b| replaced(b, b"xPixels       256", b"xPixels       9000"),
        "truncated",
    ),
    // NMS: nx (u32) at byte 1368.
    (
        "nms/nms-1.nms",
        |b| patched(b, 1368, &1_000_000_000u32.to_le_bytes()),
        TOO_MANY,
    ),
    (
        "nms/nms-1.nms",
        |b| patched(b, 1368, &9000u32.to_le_bytes()),
        "truncated",
    ),
    // FRT: nx (u32) at byte 38, the body of block 0x66.
    (
        "frt/frt-1.frt",
        |b| patched(b, 38, &1_000_000_000u32.to_le_bytes()),
        TOO_MANY,
    ),
    (
        "frt/frt-1.frt",
        |b| patched(b, 38, &9000u32.to_le_bytes()),
        "height block",
    ),
    // OPDx: NumPoints (u64) of the profile.
    (
        "opdx/opdx-3.opdx",
        |b| {
            patched(
                b,
                find(b, b"NumPoints\x0b") + 10,
                &1_000_000_000u64.to_le_bytes(),
            )
        },
        TOO_MANY,
    ),
    (
        "opdx/opdx-3.opdx",
        |b| patched(b, find(b, b"NumPoints\x0b") + 10, &9000u64.to_le_bytes()),
        "bytes of data for 9000",
    ),
    // TMD: 10⁹ points in the first 2 KiB of the file.
    ("tmd/tmd-1.tmd", tmd_huge, "points"),
    // IBW: 10⁹ points, the header checksum made right again; then a flipped spacing byte.
    ("ibw/10x10-one_channel_without_name.ibw", ibw_huge, "points"),
    (
        "ibw/spot_1-1000nm.ibw",
        |b| {
            let mut b = b.to_vec();
            b[64 + 84] ^= 1;
            b
        },
        "checksum",
    ),
    // netCDF: the x and y dimensions.
    (
        "nc/nc-1.nc",
        |b| {
            patched(
                &patched(b, 0x18, &HUGE.to_be_bytes()),
                0x24,
                &HUGE.to_be_bytes(),
            )
        },
        "points",
    ),
    // HDF5: the dimensions of dataset1's dataspace (object header at 800); then the root
    // group's B-tree node (byte 136) made an inner node whose child is itself.
    ("h5/multiple_data_sets.h5", h5_huge, "points"),
    ("h5/multiple_data_sets.h5", h5_btree_loop, "B-tree"),
    // Park TIFF: the sizes in tag 50435 (at byte 1 050 617 in this file).
    ("ps-tiff/example_ps.tiff", tiff_huge, "points"),
    // MNT: the x axis claims 2³¹ − 1 points (× 600 rows); the height block 10⁹ points.
    (
        "mnt/mnt-1.mnt",
        |b| replaced(b, &mnt_x_points(960), &mnt_x_points(i32::MAX as u32)),
        TOO_MANY,
    ),
    (
        "mnt/mnt-1.mnt",
        mnt_block_lie,
        "the height block 1000000000",
    ),
    // MNT: the container claims 2³¹ FAT sectors; ScopedContents 2⁴⁰ bytes (directory entry 2
    // in sector 2, its size at byte 120).
    (
        "mnt/mnt-1.mnt",
        |b| patched(b, 44, &0x8000_0000u32.to_le_bytes()),
        "FAT sectors",
    ),
    (
        "mnt/mnt-1.mnt",
        |b| patched(b, 3 * 4096 + 2 * 128 + 120, &(1u64 << 40).to_le_bytes()),
        "declares 1099511627776 bytes",
    ),
];

fn opd_raw_array(b: &[u8]) -> Vec<u8> {
    assert_eq!(
        &b[24020..24024],
        &[0x80, 0x02, 0xE0, 0x01],
        "Raw array header moved"
    );
    patched(b, 24020, &[0xFF; 4])
}

/// The first `\Samps/line: 512` after the first image list (ZSensor's) made 999.
fn nanoscope_samples(b: &[u8]) -> Vec<u8> {
    let key = b"\\Samps/line: 512\r";
    let list = find(b, b"\\*Ciao image list");
    let at = list + find(&b[list..], key) + key.len() - 4;
    patched(b, at, b"999")
}

fn tmd_huge(b: &[u8]) -> Vec<u8> {
    let small = patched(&b[..2048], 56, &HUGE.to_le_bytes());
    patched(&small, 60, &HUGE.to_le_bytes())
}

/// 10⁹ points in the wave header, the header checksum (the 16-bit words of the first 384
/// bytes sum to 0) made right again.
fn ibw_huge(b: &[u8]) -> Vec<u8> {
    let mut b = patched(b, 64 + 68, &HUGE.to_le_bytes());
    b[64 + 72..64 + 76].copy_from_slice(&HUGE.to_le_bytes());
    b[2..4].copy_from_slice(&[0, 0]);
    let sum = b[..384].chunks_exact(2).fold(0u16, |a, w| {
        a.wrapping_add(u16::from_le_bytes([w[0], w[1]]))
    });
    b[2..4].copy_from_slice(&0u16.wrapping_sub(sum).to_le_bytes());
    b
}

fn h5_huge(b: &[u8]) -> Vec<u8> {
    let huge = u64::from(HUGE).to_le_bytes();
    patched(&patched(b, 832, &huge), 840, &huge)
}

fn h5_btree_loop(b: &[u8]) -> Vec<u8> {
    let mut b = b.to_vec();
    b[136 + 5] = 1;
    b[168..176].copy_from_slice(&136u64.to_le_bytes());
    b
}

fn tiff_huge(b: &[u8]) -> Vec<u8> {
    let header = 1_050_617;
    let b = patched(b, header + 100, &HUGE.to_le_bytes());
    patched(&b, header + 104, &HUGE.to_le_bytes())
}

/// An MNT axis's point count: tag 6 (u32 1), then tag 1 (u32 `points`), then tag 2.
fn mnt_x_points(points: u32) -> Vec<u8> {
    let mut b = vec![
        6, 0, 4, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 4, 0, 0, 0, 0, 0, 0, 0,
    ];
    b.extend_from_slice(&points.to_le_bytes());
    b
}

/// The MNT height block's head (tag 1, 4 bytes, the points; tag 2, its length; the bytes),
/// 576 000 points and 2 304 000 bytes made 10⁹ points and 4 · 10⁹ bytes.
fn mnt_block_lie(b: &[u8]) -> Vec<u8> {
    let head = |points: u32, bytes: u64| {
        let mut h = vec![1, 0, 4, 0, 0, 0, 0, 0, 0, 0];
        h.extend_from_slice(&points.to_le_bytes());
        h.extend_from_slice(&[2, 0, 0xf2, 0xbf, 0x15, 0, 0, 0, 0, 0]);
        h.extend_from_slice(&bytes.to_le_bytes());
        h
    };
    replaced(
        b,
        &head(576_000, 2_304_000),
        &head(1_000_000_000, 4_000_000_000),
    )
}

/// `Err` unless `bytes` (a damaged copy of `path`) fails within a second, naming the file and
/// holding `expected`.
fn refused_fast(path: &Path, bytes: &[u8], expected: &str) -> Result<(), String> {
    let start = Instant::now();
    let result = parse_topography(path, bytes);
    let elapsed = start.elapsed().as_secs_f64();
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    match result {
        Ok(_) => Err(format!(
            "{}: read, must fail with `{expected}`",
            path.display()
        )),
        Err(e) if !e.to_string().contains(expected) || !e.to_string().contains(name.as_ref()) => {
            Err(format!(
                "{}: `{e}` lacks `{expected}` or the file's name",
                path.display()
            ))
        }
        Err(_) if elapsed > 1.0 => Err(format!("{}: refused after {elapsed:.1} s", path.display())),
        Err(_) => Ok(()),
    }
}

#[test]
fn lying_headers_of_shared_files_fail_at_once() {
    let Some(dir) = common::data_dir() else {
        return;
    };
    let problems: Vec<String> = LIES
        .iter()
        .filter_map(|(file, edit, expected)| {
            let (path, bytes) = load(&dir, file);
            refused_fast(&path, &edit(&bytes), expected).err()
        })
        .collect();
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// Lies in the fixtures and in headers built here (formats whose shared file is large or whose
/// header is simplest to write).
#[test]
fn lying_headers_of_fixtures_and_built_files_fail_at_once() {
    let sdf = std::fs::read(fixture("sdf-1.sdf")).unwrap();
    let ascii = replaced(&sdf, b"NumPoints = 7", b"NumPoints = 60000");
    let ascii = replaced(&ascii, b"NumProfiles = 4", b"NumProfiles = 60000");
    let binary = patched(
        &std::fs::read(fixture("mm11_iso2_binary_f64.sdf")).unwrap(),
        42,
        &[0xFF; 4],
    );
    let cases: Vec<(PathBuf, Vec<u8>, &str)> = vec![
        // SDF ASCII claiming 60000 × 60000 points; binary SDF 65535 × 65535 float64 values.
        ("lie.sdf".into(), ascii, "truncated"),
        ("lie.sdf".into(), binary, "truncated"),
        ("lie.sur".into(), sur_header(60_000, 60_000), "truncated"),
        ("huge.bcrf".into(), bcrf_header(), "points"),
        ("huge.top".into(), wsxm_header(), "points"),
    ];
    let problems: Vec<String> = cases
        .iter()
        .filter_map(|(path, bytes, expected)| refused_fast(path, bytes, expected).err())
        .collect();
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// A SUR header claiming `nx × ny` int32 points (a consistent point count) and no data.
fn sur_header(nx: i32, ny: i32) -> Vec<u8> {
    let mut sur = vec![0u8; 512];
    sur[..12].copy_from_slice(b"DIGITAL SURF");
    sur[98..100].copy_from_slice(&32u16.to_le_bytes());
    sur[108..112].copy_from_slice(&nx.to_le_bytes());
    sur[112..116].copy_from_slice(&ny.to_le_bytes());
    sur[116..120].copy_from_slice(&(nx as u32).wrapping_mul(ny as u32).to_le_bytes());
    for (offset, value) in [(120, 1.0f32), (124, 1.0), (128, 1.0)] {
        sur[offset..offset + 4].copy_from_slice(&value.to_le_bytes());
    }
    for offset in [180, 196, 212] {
        sur[offset] = b'm';
    }
    sur
}

fn bcrf_header() -> Vec<u8> {
    let mut bcrf = format!(
        "fileformat = bcrf\nheadersize = 2048\nxpixels = {HUGE}\nypixels = {HUGE}\n\
         xlength = 1\nylength = 1\nintelmode = 1\n"
    )
    .into_bytes();
    bcrf.resize(2048 + 1024, 0);
    bcrf
}

fn wsxm_header() -> Vec<u8> {
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
    wsxm
}
