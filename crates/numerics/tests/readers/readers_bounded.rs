//! Hostile X3P files: declared sizes no file could back, nesting built to be quadratic, and data
//! that no longer matches the MD5 sums the file records. Each must fail fast, naming the cause.

use std::io::Write;
use std::path::Path;
use std::time::Instant;

use asperity_numerics::surface::io::{
    declared_points, parse_topography, TopographyData, MAX_POINTS,
};

/// An X3P archive with the given members, deflated.
fn archive(members: &[(&str, &[u8])]) -> Vec<u8> {
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options = zip::write::SimpleFileOptions::default();
    for (name, content) in members {
        zip.start_file(*name, options).unwrap();
        zip.write_all(content).unwrap();
    }
    zip.finish().unwrap().into_inner()
}

/// `main.xml` of an `nx × ny` float64 surface; `extra` goes inside `DataLink`.
fn surface_xml(nx: usize, ny: usize, extra: &str) -> String {
    format!(
        "<ISO5436_2><Record1><FeatureType>SUR</FeatureType><Axes>\
         <CX><AxisType>I</AxisType><Increment>1e-6</Increment></CX>\
         <CY><AxisType>I</AxisType><Increment>1e-6</Increment></CY>\
         <CZ><AxisType>A</AxisType><DataType>D</DataType></CZ></Axes></Record1>\
         <Record3><MatrixDimension><SizeX>{nx}</SizeX><SizeY>{ny}</SizeY><SizeZ>1</SizeZ>\
         </MatrixDimension><DataLink><PointDataLink>bindata/data.bin</PointDataLink>{extra}\
         </DataLink></Record3></ISO5436_2>"
    )
}

fn md5_hex(bytes: &[u8]) -> String {
    use md5::{Digest, Md5};
    Md5::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

fn heights(n: usize) -> Vec<u8> {
    (0..n)
        .flat_map(|i| (i as f64 * 1e-9).to_le_bytes())
        .collect()
}

/// 16384² float64 points (2 GiB of heights) declared over a tiny zero payload: refused from the
/// header, before any member is inflated.
#[test]
fn x3p_declaring_16384_squared_points_fails_fast() {
    let xml = surface_xml(16384, 16384, "");
    let bytes = archive(&[
        ("main.xml", xml.as_bytes()),
        ("bindata/data.bin", &[0; 4096]),
    ]);
    let start = Instant::now();
    let err = parse_topography(Path::new("huge.x3p"), &bytes)
        .unwrap_err()
        .to_string();
    assert!(start.elapsed().as_secs_f64() < 1.0, "{:?}", start.elapsed());
    assert!(
        err.contains("huge.x3p")
            && err.contains("16384 × 16384")
            && err.contains(&MAX_POINTS.to_string()),
        "{err}"
    );
}

/// The point count an X3P header declares is read without inflating the data (memory estimates
/// use it); formats whose size bounds their points give `None`.
#[test]
fn declared_points_come_from_the_x3p_header() {
    let dir = std::env::temp_dir().join(format!("asperity-declared-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let x3p = dir.join("huge.x3p");
    let xml = surface_xml(16384, 16384, "");
    std::fs::write(
        &x3p,
        archive(&[
            ("main.xml", xml.as_bytes()),
            ("bindata/data.bin", &[0; 4096]),
        ]),
    )
    .unwrap();
    assert_eq!(declared_points(&x3p), Some(16384 * 16384));
    let text = dir.join("map.txt");
    std::fs::write(&text, "1 2 3\n4 5 6\n").unwrap();
    assert_eq!(declared_points(&text), None);
    assert_eq!(declared_points(Path::new("/dev/zero")), None);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A `main.xml` nesting 50 000 elements is refused at the depth limit, in linear time.
#[test]
fn x3p_main_xml_nested_50000_deep_fails_fast() {
    let depth = 50_000;
    let xml = format!("{}{}", "<a>".repeat(depth), "</a>".repeat(depth));
    let bytes = archive(&[("main.xml", xml.as_bytes())]);
    let start = Instant::now();
    let err = parse_topography(Path::new("deep.x3p"), &bytes)
        .unwrap_err()
        .to_string();
    assert!(start.elapsed().as_secs_f64() < 1.0, "{:?}", start.elapsed());
    assert!(
        err.contains("deep.x3p") && err.contains("deeper than 64"),
        "{err}"
    );
}

/// The point data's MD5 in `main.xml` is checked: the file reads while they match (either hex
/// case) and a flipped data byte is an error naming the member and both sums.
#[test]
fn x3p_point_data_checksum_is_verified() {
    let data = heights(12);
    let sum = md5_hex(&data);
    let element = |s: &str| format!("<MD5ChecksumPointData>{s}</MD5ChecksumPointData>");
    for recorded in [sum.clone(), sum.to_uppercase()] {
        let xml = surface_xml(4, 3, &element(&recorded));
        let bytes = archive(&[("main.xml", xml.as_bytes()), ("bindata/data.bin", &data)]);
        let t = parse_topography(Path::new("ok.x3p"), &bytes).expect("matching sums read");
        assert!(matches!(t.data, TopographyData::Areal(_)));
    }
    let mut flipped = data.clone();
    flipped[20] ^= 0x01;
    let xml = surface_xml(4, 3, &element(&sum));
    let bytes = archive(&[("main.xml", xml.as_bytes()), ("bindata/data.bin", &flipped)]);
    let err = parse_topography(Path::new("edited.x3p"), &bytes)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("edited.x3p")
            && err.contains("bindata/data.bin")
            && err.contains(&sum)
            && err.contains(&md5_hex(&flipped)),
        "{err}"
    );
}

/// `md5checksum.hex` holds the MD5 of `main.xml`, with or without the ` *main.xml` suffix; an
/// edited `main.xml` is an error naming both sums.
#[test]
fn x3p_main_xml_checksum_is_verified() {
    let data = heights(6);
    let xml = surface_xml(3, 2, "");
    let sum = md5_hex(xml.as_bytes());
    for hex in [format!("{sum} *main.xml\n"), sum.clone()] {
        let bytes = archive(&[
            ("main.xml", xml.as_bytes()),
            ("bindata/data.bin", &data),
            ("md5checksum.hex", hex.as_bytes()),
        ]);
        parse_topography(Path::new("ok.x3p"), &bytes).expect("matching sum reads");
    }
    let edited = xml.replace("1e-6</Increment></CX>", "2e-6</Increment></CX>");
    let bytes = archive(&[
        ("main.xml", edited.as_bytes()),
        ("bindata/data.bin", &data),
        ("md5checksum.hex", format!("{sum} *main.xml\n").as_bytes()),
    ]);
    let err = parse_topography(Path::new("edited.x3p"), &bytes)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("main.xml")
            && err.contains("md5checksum.hex")
            && err.contains(&sum)
            && err.contains(&md5_hex(edited.as_bytes())),
        "{err}"
    );
}

/// A data member whose declared size is not what the matrix needs is refused before it is
/// inflated, naming both sizes.
#[test]
fn x3p_member_size_must_match_the_matrix() {
    let xml = surface_xml(64, 64, "");
    let bytes = archive(&[
        ("main.xml", xml.as_bytes()),
        ("bindata/data.bin", &[0; 4096]),
    ]);
    let err = parse_topography(Path::new("short.x3p"), &bytes)
        .unwrap_err()
        .to_string();
    assert!(err.contains("4096") && err.contains("32768"), "{err}");
}

/// A text matrix is kept in one flat buffer: a million values on 250 000 lines read in well
/// under two seconds (debug build).
#[test]
fn text_matrix_is_read_without_per_line_allocations() {
    let text: String = (0..250_000).map(|i| format!("{} 1 2 3\n", i % 7)).collect();
    let start = Instant::now();
    let t = parse_topography(Path::new("column.txt"), text.as_bytes()).unwrap();
    let TopographyData::Areal(map) = t.data else {
        panic!("one column is a matrix")
    };
    assert_eq!((map.nx(), map.ny()), (4, 250_000));
    assert!(start.elapsed().as_secs_f64() < 2.0, "{:?}", start.elapsed());
}
