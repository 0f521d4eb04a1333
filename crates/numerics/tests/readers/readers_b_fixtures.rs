//! Small hand-built files for the code paths the measured files in `shared/data/topography` do
//! not reach: 16-bit Nanoscope data with a one-value scan size, a `KPK0` (not zstd-wrapped)
//! Keyence ZON with a plain (non-ZIP64) archive and a status map, AL3D row padding and invalid
//! pixels. No data folder is needed.

use std::path::Path;

use asperity_numerics::surface::io::{parse_topography, Topography, TopographyData};
use asperity_numerics::surface::HeightMap;

fn areal(t: &Topography) -> &HeightMap {
    match &t.data {
        TopographyData::Areal(m) => m,
        TopographyData::Line(_) => panic!("expected an areal map"),
    }
}

fn read(name: &str, bytes: &[u8]) -> Topography {
    parse_topography(Path::new(name), bytes).unwrap_or_else(|e| panic!("{e}"))
}

/// Relative comparison; 1e-12 covers the few float operations between header text and result.
#[track_caller]
fn assert_close(got: f64, want: f64) {
    assert!(
        ((got - want) / want).abs() < 1e-12,
        "got {got:e}, want {want:e}"
    );
}

#[test]
fn nanoscope_16_bit_with_single_scan_size_and_aspect_ratio() {
    const OFFSET: usize = 2048;
    let header = format!(
        "\\*File list\r\n\\Version: 0x05120130\r\n\\Data length: {OFFSET}\r\n\
         \\*Equipment list\r\n\\Description: Fixture scope\r\n\
         \\*Ciao scan list\r\n\\@Sens. Zsens: V 20.0 nm/V\r\n\
         \\*Ciao image list\r\n\\Data offset: {OFFSET}\r\n\\Data length: 12\r\n\\Bytes/pixel: 2\r\n\
         \\Samps/line: 3\r\n\\Number of lines: 2\r\n\\Aspect Ratio: 3:2\r\n\\Scan Size: 3 ~m\r\n\
         \\@2:Image Data: S [Height] \"Height\"\r\n\
         \\@2:Z scale: V [Sens. Zsens] (0.0001 V/LSB) 6.5536 V\r\n\\*File list end\r\n"
    );
    let mut bytes = header.into_bytes();
    bytes.resize(OFFSET, 0);
    for raw in [-2i16, -1, 0, 1, 2, i16::MAX] {
        bytes.extend_from_slice(&raw.to_le_bytes());
    }
    let t = read("fixture.spm", &bytes);
    assert_eq!(t.channel.as_deref(), Some("Height"));
    assert_eq!(
        t.metadata.get("instrument").map(String::as_str),
        Some("Fixture scope")
    );
    let m = areal(&t);
    assert_eq!((m.nx(), m.ny()), (3, 2));
    // Scan size 3 µm along x; aspect 3:2 gives 2 µm along y.
    assert_close(m.dx(), 1e-6);
    assert_close(m.dy(), 1e-6);
    // z = raw · 6.5536 V / 2^16 · 20 nm/V = raw · 2e-3 nm.
    assert_close(m.heights()[[0, 0]], -2.0 * 2e-12);
    assert_close(m.heights()[[1, 2]], f64::from(i16::MAX) * 2e-12);
    assert_eq!(m.heights()[[0, 2]], 0.0);
}

/// Minimal stored ZIP (APPNOTE 4.3) with offsets relative to its own start.
fn stored_zip(members: &[(&str, Vec<u8>)]) -> Vec<u8> {
    let mut zip = Vec::new();
    let mut central = Vec::new();
    for (name, content) in members {
        let offset = zip.len() as u32;
        let sizes = [content.len() as u32; 2];
        zip.extend_from_slice(
            b"PK\x03\x04\x14\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00",
        );
        sizes
            .iter()
            .for_each(|s| zip.extend_from_slice(&s.to_le_bytes()));
        zip.extend_from_slice(&(name.len() as u16).to_le_bytes());
        zip.extend_from_slice(&[0, 0]);
        zip.extend_from_slice(name.as_bytes());
        zip.extend_from_slice(content);
        central.extend_from_slice(
            b"PK\x01\x02\x14\x00\x14\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00",
        );
        sizes
            .iter()
            .for_each(|s| central.extend_from_slice(&s.to_le_bytes()));
        central.extend_from_slice(&(name.len() as u16).to_le_bytes());
        central.extend_from_slice(&[0; 12]);
        central.extend_from_slice(&offset.to_le_bytes());
        central.extend_from_slice(name.as_bytes());
    }
    let cd_offset = zip.len() as u32;
    zip.extend_from_slice(&central);
    zip.extend_from_slice(b"PK\x05\x06\x00\x00\x00\x00");
    let n = members.len() as u16;
    zip.extend_from_slice(&n.to_le_bytes());
    zip.extend_from_slice(&n.to_le_bytes());
    zip.extend_from_slice(&(central.len() as u32).to_le_bytes());
    zip.extend_from_slice(&cd_offset.to_le_bytes());
    zip.extend_from_slice(&[0, 0]);
    zip
}

/// A ZON array member: `nx, ny, element size, row bytes` then padded rows.
fn zon_array(nx: i32, ny: i32, elem: i32, row_bytes: i32, rows: &[Vec<u8>]) -> Vec<u8> {
    let mut b = Vec::new();
    for v in [nx, ny, elem, row_bytes] {
        b.extend_from_slice(&v.to_le_bytes());
    }
    for row in rows {
        let mut r = row.clone();
        r.resize(row_bytes as usize, 0xAB);
        b.extend_from_slice(&r);
    }
    b
}

#[test]
fn zon_kpk0_plain_zip_with_status_map() {
    let calibration = b"<?xml version=\"1.0\"?><Calibration><XYCalibration><MeterPerPixel>2E-06\
        </MeterPerPixel></XYCalibration><ZCalibration><MeterPerUnit>1E-09</MeterPerUnit>\
        </ZCalibration></Calibration>"
        .to_vec();
    let counts = [[10i32, -20, 30], [40, 50, -60]];
    let height_rows: Vec<Vec<u8>> = counts
        .iter()
        .map(|r| r.iter().flat_map(|v| v.to_le_bytes()).collect())
        .collect();
    // Row bytes padded beyond nx · element size (12 → 16 and 3 → 4).
    let height = zon_array(3, 2, 4, 16, &height_rows);
    // Status: 0x01 (no measurement) masks (1, 0); 0x04 has no invalid bit and stays valid.
    let status = zon_array(3, 2, 1, 4, &[vec![0, 0, 4], vec![0, 1, 0]]);
    let zip = stored_zip(&[
        ("686613b8-27b5-4a29-8ffc-438c2780873e", calibration),
        ("4cdb0c75-5706-48cc-a9a1-adf395d609ae", height),
        ("9e7ca6dd-0e6a-4d7b-8986-f0a7b773c916", status),
    ]);
    let mut bytes = b"KPK0".to_vec();
    bytes.extend_from_slice(&4u32.to_le_bytes());
    bytes.extend_from_slice(b"BM\0\0");
    bytes.extend_from_slice(&zip);
    let t = read("fixture.zon", &bytes);
    let m = areal(&t);
    assert_eq!((m.nx(), m.ny()), (3, 2));
    assert_eq!((m.dx(), m.dy()), (2e-6, 2e-6));
    let z = m.heights();
    assert_close(z[[0, 1]], -20e-9);
    assert_close(z[[0, 2]], 30e-9);
    assert!(z[[1, 1]].is_nan());
    assert_eq!(m.missing_count(), 1);
}

/// An AL3D file with the given tags (after Version and TagCount) and depth data at 1024.
fn al3d_bytes(cols: usize, row_values: usize, depth: &[[f32; 2]]) -> Vec<u8> {
    const OFFSET: usize = 1024;
    let tags = [
        ("Cols", cols.to_string()),
        ("Rows", "2".to_string()),
        ("PixelSizeXMeter", "1e-06".to_string()),
        ("PixelSizeYMeter", "2e-06".to_string()),
        ("DepthImageOffset", OFFSET.to_string()),
        ("TextureImageOffset", "0".to_string()),
        ("InvalidPixelValue", "3.000000028082e+15".to_string()),
    ];
    let mut b = b"AliconaImaging\0\r\n".to_vec();
    let mut tag = |key: &str, value: &str| {
        let mut t = [0u8; 52];
        t[..key.len()].copy_from_slice(key.as_bytes());
        t[20..20 + value.len()].copy_from_slice(value.as_bytes());
        t[50..].copy_from_slice(b"\r\n");
        b.extend_from_slice(&t);
    };
    tag("Version", "1");
    tag("TagCount", &tags.len().to_string());
    for (k, v) in &tags {
        tag(k, v);
    }
    b.resize(OFFSET, 0);
    for row in 0..2 {
        for col in 0..row_values {
            let v = depth.get(col).map_or(-1.0, |pair| pair[row]);
            b.extend_from_slice(&v.to_le_bytes());
        }
    }
    b
}

#[test]
fn al3d_padded_rows_and_invalid_pixels() {
    // The header's `InvalidPixelValue` text, rounded to f32 as the reader does.
    let invalid = "3.000000028082e+15"
        .parse::<f64>()
        .map_or(f32::NAN, |v| v as f32);
    let depth = [
        [1e-6, 6e-6],
        [2e-6, invalid],
        [3e-6, 8e-6],
        [4e-6, 9e-6],
        [5e-6, 10e-6],
    ];
    // Five columns are stored in rows of eight values (padding to a multiple of 8).
    let t = read("padded.al3d", &al3d_bytes(5, 8, &depth));
    let m = areal(&t);
    assert_eq!((m.nx(), m.ny()), (5, 2));
    assert_eq!((m.dx(), m.dy()), (1e-6, 2e-6));
    assert_eq!(m.heights()[[0, 4]], f64::from(5e-6f32));
    assert_eq!(m.heights()[[1, 0]], f64::from(6e-6f32));
    assert!(m.heights()[[1, 1]].is_nan());
    assert_eq!(m.missing_count(), 1);
    // A writer that does not pad: the file is too short for padded rows, so rows are Cols long.
    let t = read("unpadded.al3d", &al3d_bytes(5, 5, &depth));
    assert_eq!(areal(&t).heights()[[1, 4]], f64::from(10e-6f32));
}

#[test]
fn fixtures_truncated_anywhere_fail() {
    let fixture = al3d_bytes(5, 5, &[[1e-6, 2e-6]; 5]);
    // Every cut shorter than the depth image must fail (the last row needs all 20 bytes).
    for cut in 0..fixture.len() {
        assert!(
            parse_topography(Path::new("cut.al3d"), &fixture[..cut]).is_err(),
            "AL3D fixture cut at {cut} bytes parsed"
        );
    }
}
