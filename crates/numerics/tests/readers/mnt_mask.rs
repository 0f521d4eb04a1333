//! The mask image of a Digital Surf `.mnt` decides which points are missing, not the height
//! counts: a synthetic document (a compound file holding a `ScopedContents` tree laid out as
//! `mnt.rs` describes, built here) where the two rules differ. Its heights hold counts of 0 at
//! measured points and non-zero counts at points the mask marks non-measured, and its document
//! byte is 12, which once meant "a count of 0 is missing".

use std::path::Path;

use asperity_numerics::surface::io::{parse_topography, TopographyData};
use asperity_numerics::surface::HeightMap;

const NX: usize = 4;
const NY: usize = 3;
/// Counts row by row: zeros at measured points, and 5 and 6 where the mask says non-measured.
const COUNTS: [i32; NX * NY] = [0, 5, 0, 7, 0, 1, 2, 3, 0, 4, 5, 6];
/// The points (row, column) the mask marks non-measured.
const UNMEASURED: [(usize, usize); 2] = [(0, 1), (2, 3)];
/// Mask values: measured, and non-measured as MountainsMap writes it.
const MEASURED: u8 = 9;
const NOT_MEASURED: u8 = 22;
/// z = origin + count · step: 2 µm + count · 0.5 nm.
const ORIGIN_UM: f64 = 2.0;
const STEP_NM: f64 = 0.5;

/// A tag-length-value entry.
fn entry(tag: u16, value: &[u8]) -> Vec<u8> {
    let mut out = tag.to_le_bytes().to_vec();
    out.extend_from_slice(&(value.len() as u64).to_le_bytes());
    out.extend_from_slice(value);
    out
}

/// A container of entries.
fn container(entries: &[Vec<u8>]) -> Vec<u8> {
    entries.concat()
}

/// A text value: the marker byte 4, then UTF-16LE.
fn text(s: &str) -> Vec<u8> {
    let mut out = vec![4];
    s.encode_utf16()
        .for_each(|u| out.extend_from_slice(&u.to_le_bytes()));
    out
}

/// An object: its class number in a container, then its body.
fn object(class: u32, body: &[u8]) -> Vec<u8> {
    container(&[entry(1, &entry(1, &class.to_le_bytes())), entry(2, body)])
}

/// A zlib stream of `data` in stored (uncompressed) deflate blocks, with its Adler-32 sum.
fn zlib_stored(data: &[u8]) -> Vec<u8> {
    let mut out = vec![0x78, 0x01];
    let chunks: Vec<&[u8]> = data.chunks(65535).collect();
    for (k, chunk) in chunks.iter().enumerate() {
        out.push(u8::from(k + 1 == chunks.len()));
        let len = chunk.len() as u16;
        out.extend_from_slice(&len.to_le_bytes());
        out.extend_from_slice(&(!len).to_le_bytes());
        out.extend_from_slice(chunk);
    }
    let (mut a, mut b) = (1u32, 0u32);
    for &byte in data {
        a = (a + u32::from(byte)) % 65521;
        b = (b + a) % 65521;
    }
    out.extend_from_slice(&((b << 16) | a).to_be_bytes());
    out
}

/// A block array of `count` elements: their byte count, then one zlib block.
fn block_array(count: u32, bytes: &[u8]) -> Vec<u8> {
    let stream = zlib_stored(bytes);
    let mut out = (bytes.len() as u64).to_le_bytes().to_vec();
    out.extend_from_slice(&0u64.to_le_bytes());
    out.extend_from_slice(&count.to_le_bytes());
    out.extend_from_slice(&(stream.len() as u32).to_le_bytes());
    out.extend_from_slice(&stream);
    out
}

/// An axis descriptor: index, name, step, unit, origin unit, ratio, origin, 1, points.
fn axis(index: u32, name: &str, step: f64, unit: &str, origin: f64, points: u32) -> Vec<u8> {
    container(&[
        entry(1, &index.to_le_bytes()),
        entry(2, &text(name)),
        entry(1, &step.to_le_bytes()),
        entry(2, &text(unit)),
        entry(3, &text("µm")),
        entry(4, &1000.0f64.to_le_bytes()),
        entry(5, &origin.to_le_bytes()),
        entry(6, &1u32.to_le_bytes()),
        entry(1, &points.to_le_bytes()),
    ])
}

/// The mask object of a `width × height` image: the bordered mask bytes in a byte array.
fn mask_object(width: u32, height: u32, mask: &[u8]) -> Vec<u8> {
    let count = mask.len() as u32;
    let array = object(
        9048,
        &container(&[
            entry(1, &count.to_le_bytes()),
            entry(2, &block_array(count, mask)),
        ]),
    );
    object(
        9056,
        &container(&[
            entry(1, &width.to_le_bytes()),
            entry(2, &height.to_le_bytes()),
            entry(3, &count.to_le_bytes()),
            entry(4, &1u32.to_le_bytes()),
            entry(5, &array),
        ]),
    )
}

/// The `(NX + 2) × (NY + 2)` mask bytes: a border, measured points, and `UNMEASURED`.
fn bordered_mask() -> Vec<u8> {
    let mut mask = vec![NOT_MEASURED; (NX + 2) * (NY + 2)];
    for row in 0..NY {
        for column in 0..NX {
            let unmeasured = UNMEASURED.contains(&(row, column));
            mask[(row + 1) * (NX + 2) + column + 1] =
                if unmeasured { NOT_MEASURED } else { MEASURED };
        }
    }
    mask
}

/// The `ScopedContents` stream: the main container, the document (its byte 12), the image.
fn scoped_contents(mask: &[u8]) -> Vec<u8> {
    let counts: Vec<u8> = COUNTS.iter().flat_map(|c| c.to_le_bytes()).collect();
    let points = (NX * NY) as u32;
    let heights = object(
        9049,
        &container(&[
            entry(1, &points.to_le_bytes()),
            entry(2, &block_array(points, &counts)),
        ]),
    );
    let image = container(&[
        entry(1, &text("synthetic")),
        entry(1, &axis(1, "X", 1.5, "µm", 0.0, NX as u32)),
        entry(2, &axis(2, "Y", 2.5, "µm", 0.0, NY as u32)),
        entry(3, mask),
        entry(1, &heights),
        entry(2, &axis(3, "Z", STEP_NM, "nm", ORIGIN_UM, 0)),
    ]);
    let document = container(&[entry(1, &[12]), entry(2, &image)]);
    // Padding past the compound file's 4096-byte mini-stream cutoff.
    let tree = container(&[entry(1, &entry(0x02BD, &document)), entry(0x10, &[0; 4096])]);
    let mut stream = (tree.len() as u64).to_le_bytes().to_vec();
    stream.extend_from_slice(&tree);
    stream
}

/// A version-3 compound file (512-byte sectors) holding `stream` as `ScopedContents`:
/// the header, the FAT in sector 0, the directory in sector 1, the stream from sector 2.
fn compound_file(stream: &[u8]) -> Vec<u8> {
    const END: u32 = 0xFFFF_FFFE;
    const FREE: u32 = 0xFFFF_FFFF;
    let sectors = stream.len().div_ceil(512);
    assert!(sectors + 2 <= 128, "one FAT sector");
    let mut file = vec![0u8; 512 * (3 + sectors)];
    let put = |file: &mut Vec<u8>, at: usize, value: u32| {
        file[at..at + 4].copy_from_slice(&value.to_le_bytes())
    };
    file[..8].copy_from_slice(&[0xD0, 0xCF, 0x11, 0xE0, 0xA1, 0xB1, 0x1A, 0xE1]);
    file[24..34].copy_from_slice(&[0x3E, 0, 3, 0, 0xFE, 0xFF, 9, 0, 6, 0]);
    for (at, value) in [
        (44, 1),
        (48, 1),
        (56, 4096),
        (60, END),
        (64, 0),
        (68, END),
        (72, 0),
    ] {
        put(&mut file, at, value);
    }
    put(&mut file, 76, 0);
    for i in 1..109 {
        put(&mut file, 76 + 4 * i, FREE);
    }
    let mut fat = vec![0xFFFF_FFFD, END];
    fat.extend((3..sectors as u32 + 2).chain([END]));
    for i in 0..128 {
        put(&mut file, 512 + 4 * i, *fat.get(i).unwrap_or(&FREE));
    }
    for (index, name, kind, start, size) in [
        (0, "Root Entry", 5, END, 0),
        (1, "ScopedContents", 2, 2, stream.len() as u32),
    ] {
        let at = 1024 + 128 * index;
        for (k, unit) in name.encode_utf16().enumerate() {
            file[at + 2 * k..at + 2 * k + 2].copy_from_slice(&unit.to_le_bytes());
        }
        file[at + 64] = (2 * name.len() + 2) as u8;
        file[at + 66] = kind;
        put(&mut file, at + 116, start);
        put(&mut file, at + 120, size);
    }
    file[1536..1536 + stream.len()].copy_from_slice(stream);
    file
}

fn read(mask: &[u8]) -> Result<HeightMap, String> {
    let file = compound_file(&scoped_contents(mask));
    match parse_topography(Path::new("synthetic.mnt"), &file) {
        Ok(t) => match t.data {
            TopographyData::Areal(map) => Ok(map),
            TopographyData::Line(_) => Err("a line scan".into()),
        },
        Err(e) => Err(e.to_string()),
    }
}

#[test]
fn the_mask_not_a_count_of_zero_decides_which_points_are_missing() {
    let map = read(&mask_object(NX as u32, NY as u32, &bordered_mask())).unwrap();
    assert_eq!((map.nx(), map.ny()), (NX, NY));
    assert_eq!((map.dx(), map.dy()), (1.5 * 1e-6, 2.5 * 1e-6));
    for row in 0..NY {
        for column in 0..NX {
            let z = map.heights()[[row, column]];
            if UNMEASURED.contains(&(row, column)) {
                assert!(z.is_nan(), "({row}, {column}) is not measured: {z}");
            } else {
                let count = f64::from(COUNTS[row * NX + column]);
                let expected = ORIGIN_UM * 1e-6 + count * STEP_NM * 1e-9;
                assert_eq!(z, expected, "({row}, {column})");
            }
        }
    }
    // A count of 0 is a height (four of them here), not a missing point.
    assert_eq!(map.missing_count(), UNMEASURED.len());
}

#[test]
fn an_image_without_a_mask_has_no_missing_point() {
    // As in mnt-1: the mask slot holds an object of class 0.
    let map = read(&object(0, &[])).unwrap();
    assert_eq!(map.missing_count(), 0);
    assert_eq!(map.heights()[[0, 0]], ORIGIN_UM * 1e-6);
}

#[test]
fn a_mask_that_does_not_fit_the_image_is_refused() {
    let mask = bordered_mask();
    let wide = read(&mask_object(NX as u32 + 1, NY as u32, &mask)).unwrap_err();
    assert!(
        wide.contains("synthetic.mnt") && wide.contains("MNT mask"),
        "{wide}"
    );
    let short = read(&mask_object(NX as u32, NY as u32, &mask[..mask.len() - 1])).unwrap_err();
    assert!(short.contains("MNT mask"), "{short}");
}
