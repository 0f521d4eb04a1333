//! Header values a reader can check (sizes against the bytes, scales finite and plausible,
//! duplicate fields that must agree), on damaged copies of the shared files: a damaged value is
//! refused with an error naming the file and the field, instead of reading as a surface with a
//! silently wrong Sq.

use asperity_numerics::surface::io::{parse_topography, TopographyData};

use crate::common;
use crate::damage::{check_outcome, expect_error, load, patched, shared_files};
use crate::readers_a_common;

/// The NMS example's header fields: z range (2 × f64), header size (u32), nx, ny (u32),
/// spacing (2 × f64).
const NMS_Z: usize = 16;
const NMS_HEADER_SIZE: usize = 1352;
const NMS_POINTS: usize = 1368;
const NMS_SPACING: usize = 1376;

/// `bytes` with bit `bit` of byte `at` flipped.
fn flipped(bytes: &[u8], at: usize, bit: u8) -> Vec<u8> {
    let mut b = bytes.to_vec();
    b[at] ^= 1 << bit;
    b
}

#[test]
fn nms_size_and_scale_damage_is_refused_naming_the_field() {
    let Some(dir) = common::data_dir() else {
        return;
    };
    let (path, b) = load(&dir, "nms/nms-1.nms");
    // ny 512 → 513 and nx 512 → 576: the heights would take rows from the intensity block.
    expect_error(
        &path,
        &flipped(&b, NMS_POINTS + 4, 0),
        "does not hold 512 × 513 points",
    );
    expect_error(
        &path,
        &flipped(&b, NMS_POINTS + 1, 0),
        "does not hold 768 × 512 points",
    );
    expect_error(&path, &flipped(&b, NMS_POINTS, 6), "576 × 512");
    expect_error(
        &path,
        &patched(&b, NMS_HEADER_SIZE, &3469u32.to_le_bytes()),
        "states its size as 3469",
    );
    // zmax below zmin, a NaN, a value beyond a metre.
    let z = |zmin: f64, zmax: f64| {
        patched(
            &patched(&b, NMS_Z, &zmin.to_le_bytes()),
            NMS_Z + 8,
            &zmax.to_le_bytes(),
        )
    };
    expect_error(&path, &z(6.0, 2.0), "NMS z range [6, 2]");
    expect_error(&path, &z(f64::NAN, 6.0), "NMS z range");
    expect_error(&path, &z(2.0, 3e6), "within ±1000000 µm");
    expect_error(
        &path,
        &patched(&b, NMS_SPACING, &1e30f64.to_le_bytes()),
        "NMS spacing 1e30",
    );
    // Zeroed first 256 bytes: an empty z range (every height would be the same).
    expect_error(&path, &patched(&b, 0, &[0; 256]), "NMS z range [0, 0]");
}

/// Every single-bit flip of the NMS grid size and header-size fields is refused; of the
/// spacing's exponent bits, every flip that leaves 1 pm – 1 m.
#[test]
fn every_bit_flip_of_the_nms_sizes_is_refused() {
    let Some(dir) = common::data_dir() else {
        return;
    };
    let (path, b) = load(&dir, "nms/nms-1.nms");
    let mut accepted = Vec::new();
    for at in (NMS_HEADER_SIZE..NMS_HEADER_SIZE + 4).chain(NMS_POINTS..NMS_POINTS + 8) {
        for bit in 0..8 {
            if parse_topography(&path, &flipped(&b, at, bit)).is_ok() {
                accepted.push((at, bit));
            }
        }
    }
    assert!(accepted.is_empty(), "flips read as valid: {accepted:?}");
    for field in [NMS_SPACING, NMS_SPACING + 8] {
        // Bits 52–62 of the f64: the exponent.
        for bit in 52..63u32 {
            let (at, b8) = (field + bit as usize / 8, (bit % 8) as u8);
            let damaged = flipped(&b, at, b8);
            let d = f64::from_le_bytes(damaged[field..field + 8].try_into().unwrap()) * 1e-9;
            let read = parse_topography(&path, &damaged).is_ok();
            assert_eq!(
                read,
                (1e-12..=1.0).contains(&d),
                "spacing {d:e} m (bit {bit}): read {read}"
            );
        }
    }
}

/// Zeroed header bytes of any shared file never read as a flat surface or with an impossible
/// scale: an error naming the file, or a plausible map.
#[test]
fn zeroed_headers_are_refused_or_read_plausibly() {
    let Some(dir) = common::data_dir() else {
        return;
    };
    let mut problems = Vec::new();
    for path in shared_files(&dir) {
        let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        for start in [0, 256] {
            if bytes.len() < start + 256 {
                continue;
            }
            let damaged = patched(&bytes, start, &[0; 256]);
            let what = format!(
                "{} with bytes {start}–{} zeroed",
                path.display(),
                start + 255
            );
            problems.extend(check_outcome(&path, &damaged, &what).err());
            if let Ok(t) = parse_topography(&path, &damaged) {
                problems.extend(implausible(&t.data).map(|why| format!("{what}: {why}")));
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// What no reader may return: a flat surface, or heights or spacings far outside an
/// instrument's range (the limits `plausible.rs` enforces).
fn implausible(data: &TopographyData) -> Option<String> {
    let (z, spacing): (Vec<f64>, Vec<f64>) = match data {
        TopographyData::Areal(m) => (m.heights().iter().copied().collect(), vec![m.dx(), m.dy()]),
        TopographyData::Line(l) => (l.z.clone(), Vec::new()),
    };
    let valid: Vec<f64> = z.into_iter().filter(|z| !z.is_nan()).collect();
    let (lo, hi) = valid
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &z| {
            (a.min(z), b.max(z))
        });
    if valid.len() > 1 && lo == hi {
        return Some(format!("read as flat ({lo:e} m)"));
    }
    spacing
        .iter()
        .find(|d| !(1e-12..=1.0).contains(*d))
        .map(|d| format!("read with a spacing of {d:e} m"))
}

/// A scale field damaged into a value no instrument produces is refused by the registry's
/// plausibility check, naming the file and the scale (SUR: dx and dz as float32 at 120, 128).
#[test]
fn implausible_scales_are_refused_naming_the_file() {
    let Some(dir) = common::data_dir() else {
        return;
    };
    let (path, b) = load(&dir, "sur/sur-2.sur");
    expect_error(
        &path,
        &patched(&b, 120, &1e30f32.to_le_bytes()),
        "lateral scale gives dx",
    );
    expect_error(
        &path,
        &patched(&b, 128, &1e30f32.to_le_bytes()),
        "height scale gives heights",
    );
}

/// A flipped byte in the first data line of a text matrix (a `.` made a control character)
/// no longer passes that line as a header line, dropping a row and changing dy.
#[test]
fn a_damaged_first_data_line_of_a_text_matrix_is_refused() {
    let Some(dir) = common::data_dir() else {
        return;
    };
    let (path, b) = load(&dir, "txt/matrix-3.txt");
    let at = crate::damage::find(&b, b"-6.5574e-008");
    expect_error(
        &path,
        &patched(&b, at + 2, &[b'.' ^ 0x20]),
        "a data line with a damaged value",
    );
}

/// The binary SDF fixture's fields (ISO 25178-71): NumPoints (u16) at 42, Xscale, Yscale,
/// Zscale (f64) at 46, 54, 62, DataType (u8) at 79, then 7 × 4 int32 samples.
const SDF_NUM_POINTS: usize = 42;
const SDF_ZSCALE: usize = 62;
const SDF_DATA_TYPE: usize = 79;

/// A damaged binary SDF header is refused where the format allows it: a height scale whose
/// heights exceed the field of view by orders of magnitude (the campaign's flip turned Sq
/// 1.36e-8 m into 3.99e-3 m on a 7 µm × 4 µm map) by the rms slope, fewer declared points or a
/// smaller sample type by the bytes after the data, which are no text trailer. A text trailer
/// is still read.
#[test]
fn sdf_binary_header_damage_is_refused() {
    let path = readers_a_common::fixture("sdf-1_binary_int32.sdf");
    let b = std::fs::read(&path).unwrap();
    let zscale = f64::from_le_bytes(b[SDF_ZSCALE..SDF_ZSCALE + 8].try_into().unwrap());
    expect_error(
        &path,
        &patched(&b, SDF_ZSCALE, &(zscale * 2.93e5).to_le_bytes()),
        "rms slope",
    );
    for bit in 0..3 {
        expect_error(&path, &flipped(&b, SDF_NUM_POINTS, bit), "no text trailer");
    }
    expect_error(&path, &flipped(&b, SDF_DATA_TYPE, 1), "no text trailer");
    let mut with_trailer = b.clone();
    with_trailer.extend_from_slice(b"Operator = test\r\nComment = a text trailer\r\n");
    let t = parse_topography(&path, &with_trailer).expect("a text trailer reads");
    assert!(matches!(t.data, TopographyData::Areal(ref m) if m.nx() == 7 && m.ny() == 4));
}
