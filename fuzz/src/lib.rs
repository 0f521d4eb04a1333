//! The shared body of the reader fuzz targets: each target names one reader.

use asperity_numerics::surface::io::reader_named;

/// Parses `data` with the reader of the format `name` ("al3d", "x3p", …): `Ok` or a
/// `ParseError`, never a panic; libFuzzer's `-rss_limit_mb` and `-timeout` catch unbounded
/// allocation or work.
pub fn read_as(name: &str, data: &[u8]) {
    let reader = reader_named(name).unwrap_or_else(|| panic!("no reader named {name}"));
    let _ = reader.parse(data, None);
}
