//! Readers on small files built in memory: X3P profiles and layout errors, Digital Surf int16
//! with unit names and non-measured points, Sensofar's not-measured marker.

use crate::readers_a_common;
use asperity_numerics::surface::io::TopographyData;
use readers_a_common::assert_rel;

/// A minimal X3P written in memory with `main_xml` and an optional binary point file.
fn x3p_bytes(main_xml: &str, data: Option<&[u8]>) -> Vec<u8> {
    use std::io::Write;
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options = zip::write::SimpleFileOptions::default();
    zip.start_file("main.xml", options).unwrap();
    zip.write_all(main_xml.as_bytes()).unwrap();
    if let Some(data) = data {
        zip.start_file("bindata/data.bin", options).unwrap();
        zip.write_all(data).unwrap();
    }
    zip.finish().unwrap().into_inner()
}

const PROFILE_XML: &str = "<p:ISO5436_2 xmlns:p=\"http://www.opengps.eu/2008/ISO5436_2\">\
    <Record1><Revision>ISO5436 - 2000</Revision><FeatureType>PRF</FeatureType><Axes>\
    <CX><AxisType>I</AxisType><DataType>D</DataType><Increment>0.5e-6</Increment><Offset>0</Offset></CX>\
    <CY><AxisType>I</AxisType><DataType>D</DataType><Increment>1</Increment><Offset>0</Offset></CY>\
    <CZ><AxisType>A</AxisType><DataType>I</DataType><Increment>0.25e-6</Increment><Offset>-1e-6</Offset></CZ>\
    </Axes></Record1><Record3><MatrixDimension><SizeX>3</SizeX><SizeY>1</SizeY><SizeZ>1</SizeZ>\
    </MatrixDimension><DataLink><PointDataLink>bindata/data.bin</PointDataLink></DataLink></Record3>\
    </p:ISO5436_2>";

#[test]
fn x3p_profile_becomes_a_line_scan_and_bad_layouts_are_refused() {
    let data: Vec<u8> = [4i16, 8, -4].iter().flat_map(|v| v.to_le_bytes()).collect();
    let path = std::path::Path::new("profile.x3p");
    let t = asperity_numerics::surface::io::parse_topography(
        path,
        &x3p_bytes(PROFILE_XML, Some(&data)),
    )
    .expect("profile must read");
    let TopographyData::Line(line) = t.data else {
        panic!("a PRF file is a line scan")
    };
    // z = raw · 0.25e-6 − 1e-6, x = i · 0.5e-6: raw and i are powers of two times small
    // integers, so every product is exact and the comparison can be exact too.
    assert_eq!(line.x, vec![0.0, 0.5e-6, 1.0e-6]);
    assert_eq!(line.z, vec![0.0, 1e-6, -2e-6]);

    // int16 data but 4 bytes too many: the size check names the entry.
    let mut long = data.clone();
    long.extend([0, 0, 0, 0]);
    let err = asperity_numerics::surface::io::parse_topography(
        path,
        &x3p_bytes(PROFILE_XML, Some(&long)),
    )
    .unwrap_err();
    assert!(err.to_string().contains("bindata/data.bin"), "{err}");

    // Point clouds are refused as unsupported, not misread.
    let cloud = PROFILE_XML.replace("<FeatureType>PRF", "<FeatureType>PCL");
    let err =
        asperity_numerics::surface::io::parse_topography(path, &x3p_bytes(&cloud, Some(&data)))
            .unwrap_err();
    assert!(err.to_string().contains("unsupported"), "{err}");
}

/// A 3 × 2 int16 Digital Surf file: dx 0.5 µm (unit written as the Latin-1 byte 0xB5 + `m`),
/// dy 2 nm, dz 0.25 nm (field offsets as in the table of `crates/numerics/src/surface/io/sur.rs`).
fn sur_int16(raw: &[i16], zmin: i32, special_points: u16) -> Vec<u8> {
    let mut b = vec![0u8; 512];
    b[..12].copy_from_slice(b"DIGITAL SURF");
    b[86..88].copy_from_slice(&special_points.to_le_bytes());
    b[98..100].copy_from_slice(&16u16.to_le_bytes());
    b[100..104].copy_from_slice(&zmin.to_le_bytes());
    b[104..108].copy_from_slice(&100i32.to_le_bytes());
    b[108..112].copy_from_slice(&3i32.to_le_bytes());
    b[112..116].copy_from_slice(&2i32.to_le_bytes());
    b[116..120].copy_from_slice(&6u32.to_le_bytes());
    for (offset, value) in [(120, 0.5f32), (124, 2.0), (128, 0.25)] {
        b[offset..offset + 4].copy_from_slice(&value.to_le_bytes());
    }
    b[180..182].copy_from_slice(b"\xB5m");
    b[196..198].copy_from_slice(b"nm");
    b[212..214].copy_from_slice(b"nm");
    b.extend(raw.iter().flat_map(|v| v.to_le_bytes()));
    b
}

#[test]
fn sur_int16_units_and_non_measured_points() {
    let path = std::path::Path::new("synthetic.sur");
    let raw = [10i16, 8, 12, 100, 11, 10];
    let parse = |bytes: &[u8]| match asperity_numerics::surface::io::parse_topography(path, bytes)
        .expect("synthetic SUR must read")
        .data
    {
        TopographyData::Areal(m) => m,
        TopographyData::Line(_) => panic!("expected an areal map"),
    };
    let map = parse(&sur_int16(&raw, 10, 1));
    assert_eq!((map.nx(), map.ny()), (3, 2));
    // Spacings and heights are float32 steps times a unit factor: relative 1e-15.
    assert_rel("sur dx", map.dx(), 0.5e-6, 1e-15);
    assert_rel("sur dy", map.dy(), 2e-9, 1e-15);
    assert!(
        map.heights()[[0, 1]].is_nan(),
        "raw zmin − 2 is non-measured"
    );
    assert_eq!(map.missing_count(), 1);
    assert_rel("sur z", map.heights()[[1, 0]], 100.0 * 0.25e-9, 1e-15);
    // Without the special-points flag the same value is a height.
    assert_eq!(parse(&sur_int16(&raw, 10, 0)).missing_count(), 0);
}

#[test]
fn plu_not_measured_marker_is_missing() {
    let mut b = vec![0u8; 500];
    b[..24].copy_from_slice(b"Fri Mar 10 16:35:59 2023");
    b[388..392].copy_from_slice(&2u32.to_le_bytes()); // yres
    b[392..396].copy_from_slice(&3u32.to_le_bytes()); // xres
    b[404..408].copy_from_slice(&1.5f32.to_le_bytes()); // mppx, µm
    b[408..412].copy_from_slice(&0.5f32.to_le_bytes()); // mppy, µm
    b.extend(2u32.to_le_bytes());
    b.extend(3u32.to_le_bytes());
    let z = [1.0f32, 2.0, 1_000_001.0, -1.0, 0.5, 4.0];
    b.extend(z.iter().flat_map(|v| v.to_le_bytes()));
    let t = asperity_numerics::surface::io::parse_topography(std::path::Path::new("s.plu"), &b)
        .expect("synthetic PLU must read");
    let TopographyData::Areal(map) = t.data else {
        panic!("expected an areal map")
    };
    assert_eq!((map.nx(), map.ny()), (3, 2));
    assert_rel("plu dx", map.dx(), 1.5e-6, 1e-15);
    assert_rel("plu dy", map.dy(), 0.5e-6, 1e-15);
    assert!(map.heights()[[0, 2]].is_nan());
    assert_eq!(map.missing_count(), 1);
    assert_rel("plu z", map.heights()[[1, 0]], -1e-6, 1e-15);
}
