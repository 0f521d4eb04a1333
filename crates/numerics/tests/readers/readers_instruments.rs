//! The readers of issue 34 (NID, MI, …) against the reference values of the shared folder's
//! SOURCES.md / reference_values.json (`SurfaceTopography_1.27.1` entries, lengths converted to
//! metres), and against damaged copies of the same files: truncated anywhere, bytes flipped, and
//! headers claiming 10⁹ points, which must fail before anything is allocated.
//!
//! Tolerance: relative 1e-6, the acceptance criterion.

use crate::common;
use crate::readers_a_common::{assert_rel, plain_stats};
use std::path::{Path, PathBuf};

use asperity_numerics::surface::io::{
    detect_format, parse_topography, parse_topography_channel, Topography, TopographyData,
};

const RTOL: f64 = 1e-6;
const UM: f64 = 1e-6;

/// One file's expected values (lengths in metres).
struct Reference {
    file: &'static str,
    format: &'static str,
    /// The channel read by default, and every channel the file lists.
    channel: &'static str,
    channels: &'static [&'static str],
    grid: (usize, usize),
    size: (f64, f64),
    n_invalid: usize,
    sq: f64,
    sa: f64,
    sz: f64,
}

fn load(dir: &Path, file: &str) -> (PathBuf, Vec<u8>) {
    let path = dir.join(file);
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    (path, bytes)
}

fn check(r: &Reference) -> Option<Topography> {
    let dir = common::data_dir()?;
    let (path, bytes) = load(&dir, r.file);
    let format = detect_format(&path, &bytes).map(|f| f.name);
    assert_eq!(format, Some(r.format), "{}: detected format", r.file);
    let t = parse_topography(&path, &bytes).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(t.channel.as_deref(), Some(r.channel), "{}: channel", r.file);
    assert_eq!(t.channels, r.channels, "{}: channels", r.file);
    let TopographyData::Areal(map) = &t.data else {
        panic!("{}: not an areal map", r.file)
    };
    assert_eq!((map.nx(), map.ny()), r.grid, "{}: grid", r.file);
    let (lx, ly) = map.size();
    assert_rel(&format!("{} Lx", r.file), lx, r.size.0, RTOL);
    assert_rel(&format!("{} Ly", r.file), ly, r.size.1, RTOL);
    assert_eq!(map.missing_count(), r.n_invalid, "{}: missing", r.file);
    let s = plain_stats(map.heights().iter());
    assert_rel(&format!("{} Sq", r.file), s.sq, r.sq, RTOL);
    assert_rel(&format!("{} Sa", r.file), s.sa, r.sa, RTOL);
    assert_rel(&format!("{} Sz", r.file), s.sz, r.sz, RTOL);
    Some(t)
}

/// Sq of the channel `channel` of `file`.
fn channel_sq(file: &str, channel: &str) -> Option<f64> {
    let dir = common::data_dir()?;
    let (path, bytes) = load(&dir, file);
    let t =
        parse_topography_channel(&path, &bytes, Some(channel)).unwrap_or_else(|e| panic!("{e}"));
    let TopographyData::Areal(map) = &t.data else {
        panic!("{file}: not an areal map")
    };
    Some(plain_stats(map.heights().iter()).sq)
}

const NID_CHANNELS: &[&str] = &[
    "Scan forward (Deflection)",
    "Scan forward (Z-Axis)",
    "Scan forward (Friction force)",
    "Scan forward (Z-AxisSensor)",
    "Scan backward (Deflection)",
    "Scan backward (Z-Axis)",
    "Scan backward (Friction force)",
    "Scan backward (Z-AxisSensor)",
];

#[test]
fn nid_reproduces_reference() {
    let Some(t) = check(&Reference {
        file: "nid/nid-1.nid",
        format: "nid",
        channel: "Scan forward (Z-Axis)",
        channels: NID_CHANNELS,
        grid: (256, 256),
        // ASSERTED (rtol 1e-6): size 2e-5 m, Sq of the four height channels.
        size: (2e-5, 2e-5),
        n_invalid: 0,
        sq: 2.395896706764167e-07,
        sa: 2.046859270431451e-07,
        sz: 1.0571865769699216e-06,
    }) else {
        return;
    };
    assert_eq!(t.metadata["instrument"], "DriveAFM");
    for (channel, sq) in [
        ("Scan forward (Z-AxisSensor)", 3.026701737129839e-07),
        ("Scan backward (Z-Axis)", 2.3941867686171115e-07),
        ("Scan backward (Z-AxisSensor)", 3.029781629305204e-07),
    ] {
        let got = channel_sq("nid/nid-1.nid", channel).unwrap();
        assert_rel(&format!("nid-1 {channel} Sq"), got, sq, RTOL);
    }
}

#[test]
fn mi_reproduces_reference() {
    let Some(t) = check(&Reference {
        file: "mi/mi-1.mi",
        format: "mi",
        channel: "Topography",
        channels: &[
            "Topography",
            "Deflection",
            "Friction (Trace)",
            "Friction (Retrace)",
        ],
        grid: (256, 256),
        // ASSERTED: 256×256, unit µm, channel names, heights[0,0]; size 20 µm as ST 1.27.1.
        size: (20.0 * UM, 20.0 * UM),
        n_invalid: 0,
        sq: 0.033215426493512654 * UM,
        sa: 0.028720236316624015 * UM,
        sz: 0.16563949584960935 * UM,
    }) else {
        return;
    };
    let TopographyData::Areal(map) = &t.data else {
        unreachable!()
    };
    assert_rel(
        "mi-1 z[0,0]",
        map.heights()[[0, 0]],
        -0.4986900329589844 * UM,
        RTOL,
    );
}

#[test]
fn nms_reproduces_reference() {
    check(&Reference {
        file: "nms/nms-1.nms",
        format: "nms",
        channel: "height",
        channels: &["height"],
        grid: (512, 512),
        // ST 1.27.1 reports 1.59999995e8 µm, reading the spacing field (312.4999912) in mm; we
        // read it in nm (SOURCES.md: "almost certainly in nm"), 10⁻⁶ of ST's size.
        size: (
            1.5999999547489095e8 * UM * 1e-6,
            1.5999999547489095e8 * UM * 1e-6,
        ),
        n_invalid: 0,
        sq: 0.7187185984110469 * UM,
        sa: 0.6054505339622984 * UM,
        sz: 3.3183284702927356 * UM,
    });
}

#[test]
fn frt_reproduces_reference() {
    let Some(t) = check(&Reference {
        file: "frt/frt-1.frt",
        format: "frt",
        channel: "height",
        channels: &["height"],
        grid: (500, 500),
        // ASSERTED (rtol 1e-6): 500×500, 0.012 × 0.012 m; Sq over the valid points as ST 1.27.1
        // (the asserted 2.047476e-05 divides by all points, masked ones included).
        size: (0.012, 0.012),
        n_invalid: 76456,
        sq: 4.915785774480653e-06,
        sa: 1.9270923715598076e-06,
        sz: 0.0003052143925290689,
    }) else {
        return;
    };
    assert_eq!(t.metadata["serial_number"], "SN_1036");
    assert_eq!(t.metadata["vendor"], "FRT");
}

#[test]
fn opdx_profile_reproduces_reference_and_its_text_export() {
    let Some(dir) = common::data_dir() else {
        return;
    };
    let (path, bytes) = load(&dir, "opdx/opdx-3.opdx");
    assert_eq!(detect_format(&path, &bytes).map(|f| f.name), Some("opdx"));
    let t = parse_topography(&path, &bytes).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(t.channels, ["Raw"]);
    assert_eq!(t.metadata["instrument"], "Dektak Profiler");
    assert_eq!(t.metadata["vendor"], "Bruker");
    let TopographyData::Line(line) = &t.data else {
        panic!("opdx-3 is a profile")
    };
    assert_eq!(line.z.len(), 3001);
    // ST 1.27.1: length n·dx = 49.983344425752584 µm, so dx = that / n (SOURCES.md:
    // 0.01665556295 µm); this reader keeps the x range (n − 1)·dx.
    let dx = 49.983344425752584 * UM / 3001.0;
    assert_rel("opdx-3 dx", line.x[1] - line.x[0], dx, RTOL);
    assert_rel("opdx-3 range", line.x[3000], 3000.0 * dx, RTOL);
    let s = plain_stats(line.z.iter());
    assert_rel("opdx-3 Sq", s.sq, 0.005307508577129646 * UM, RTOL);
    assert_rel("opdx-3 Sa", s.sa, 0.004748390746531892 * UM, RTOL);
    assert_rel("opdx-3 Sz", s.sz, 0.017151821248876244 * UM, RTOL);
    // ASSERTED upstream: the heights equal the text export's second column (metres), rtol 1e-7.
    let (txt, txt_bytes) = load(&dir, "opdx/opdx-3.txt");
    let export = parse_topography(&txt, &txt_bytes).unwrap_or_else(|e| panic!("{e}"));
    let TopographyData::Line(export) = &export.data else {
        panic!("opdx-3.txt is a profile")
    };
    assert_eq!(export.z.len(), line.z.len());
    for (i, (a, b)) in line.z.iter().zip(&export.z).enumerate() {
        assert!((a - b).abs() <= 1e-7 * b.abs(), "point {i}: {a:e} vs {b:e}");
    }
}

/// Items of a synthetic OPDx file (layout of `surface/io/opdx_items.rs`).
mod opdx_bytes {
    pub fn name(s: &str) -> Vec<u8> {
        [&(s.len() as u32).to_le_bytes()[..], s.as_bytes()].concat()
    }
    fn varlen(n: usize) -> Vec<u8> {
        [&[4u8][..], &(n as u32).to_le_bytes()].concat()
    }
    pub fn item(n: &str, kind: u8, payload: &[u8]) -> Vec<u8> {
        [name(n), vec![kind], payload.to_vec()].concat()
    }
    pub fn container(n: &str, items: &[Vec<u8>]) -> Vec<u8> {
        let body = [items.concat(), item("", 0x7f, &[0xff, 0xff])].concat();
        item(n, 0x7d, &[varlen(body.len()), body].concat())
    }
    pub fn text(n: &str, value: &str) -> Vec<u8> {
        item(
            n,
            0x12,
            &[varlen(value.len()), value.as_bytes().to_vec()].concat(),
        )
    }
    pub fn quantity(n: &str, value: f64, unit: &str, symbol: &str) -> Vec<u8> {
        let body = [value.to_le_bytes().to_vec(), name(unit), name(symbol)].concat();
        item(n, 0x13, &[varlen(body.len()), body].concat())
    }
    pub fn matrix(n: &str, rows: u32, columns: u32, data: &[f32]) -> Vec<u8> {
        let values: Vec<u8> = data.iter().flat_map(|v| v.to_le_bytes()).collect();
        let body = [
            name("Matrix"),
            7u32.to_le_bytes().to_vec(),
            name("float"),
            varlen(8 + values.len()),
            rows.to_le_bytes().to_vec(),
            columns.to_le_bytes().to_vec(),
            values,
        ]
        .concat();
        item(n, 0x00, &body)
    }
}

#[test]
fn opdx_height_map_is_read_with_its_extents_scale_and_missing_points() {
    use opdx_bytes::{container, item, matrix, quantity, text};
    let map = container(
        "Height",
        &[
            item("Dimension1Points", 0x07, &2u32.to_le_bytes()),
            item("Dimension2Points", 0x07, &3u32.to_le_bytes()),
            quantity("Dimension1Extent", 20.0, "Micrometer", "µm"),
            quantity("Dimension2Extent", 0.03, "Millimeter", "mm"),
            quantity("DataScale", 0.5, "Nanometer", "nm"),
            matrix("Matrix", 2, 3, &[1.0, 2.0, 3.0, 4.0, 5.0, f32::NAN]),
        ],
    );
    let bytes = [
        b"VCA DATA\x01\x00\x00\x55".to_vec(),
        container("2D_Data", &[map]),
        container(
            "MetaData",
            &[
                text("DataKind", "Surface Height"),
                text("PrimaryData2D", "Height"),
            ],
        ),
        item("", 0x7f, &[]),
    ]
    .concat();
    let path = Path::new("map.opdx");
    let t = parse_topography(path, &bytes).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(t.channels, ["Height"]);
    let TopographyData::Areal(m) = &t.data else {
        panic!("a map")
    };
    assert_eq!((m.nx(), m.ny()), (3, 2));
    assert_rel("dx", m.dx(), 10.0 * UM, 1e-12);
    assert_rel("dy", m.dy(), 10.0 * UM, 1e-12);
    assert_rel("z[1, 0]", m.heights()[[1, 0]], 2e-9, 1e-12);
    assert_eq!(m.missing_count(), 1);
    let err = parse_topography_channel(path, &bytes, Some("Phase")).unwrap_err();
    assert!(err.to_string().contains("`Height`"), "{err}");
}
