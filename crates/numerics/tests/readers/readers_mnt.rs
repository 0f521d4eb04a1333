//! The Digital Surf `.mnt` reader against `mnt/mnt-1.mnt` of the shared folder (SOURCES.md and
//! the `SurfaceTopography_1.27.1` entry of reference_values.json, lengths converted to metres;
//! relative 1e-6). Damaged copies are in `damaged_files` and `lying_headers`, the mask of
//! non-measured points in `mnt_mask`.

use crate::common;
use crate::readers_a_common::{assert_rel, plain_stats};
use std::path::PathBuf;

use asperity_numerics::surface::io::{
    declared_points, detect_format, parse_topography, TopographyData,
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
