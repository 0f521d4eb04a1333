//! Shared helpers of the reader tests: fixtures and plain statistics.

#![allow(dead_code)] // each test crate uses a different subset of these helpers

use std::path::{Path, PathBuf};

use asperity_numerics::surface::io::{
    read_topography, reader_named, ParseError, Topography, TopographyData,
};
use asperity_numerics::surface::HeightMap;

/// Path of a fixture in the repository's `tests/data/` (two levels above this crate).
pub fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data")
        .join(name)
}

/// Parses `bytes` with the registry's reader `format` (its `Reader::name`), reading the channel
/// `channel` (`None`: the height channel): the path every reader test goes through.
pub fn parse_as(
    format: &str,
    bytes: &[u8],
    channel: Option<&str>,
) -> Result<Topography, ParseError> {
    reader_named(format)
        .unwrap_or_else(|| panic!("no reader named {format}"))
        .parse(bytes, channel)
}

pub fn read_areal(path: &Path) -> HeightMap {
    let t: Topography =
        read_topography(path).unwrap_or_else(|e| panic!("{} must read: {e}", path.display()));
    match t.data {
        TopographyData::Areal(m) => m,
        TopographyData::Line(_) => panic!("{} read as a line scan", path.display()),
    }
}

/// Plain amplitude statistics over the valid (non-NaN) points, heights relative to their mean,
/// no levelling: the definitions of the shared data's SOURCES.md.
#[derive(Debug, Clone, Copy)]
pub struct PlainStats {
    pub n_valid: usize,
    pub sq: f64,
    pub sa: f64,
    pub sz: f64,
    pub ssk: f64,
    pub sku: f64,
}

pub fn plain_stats<'a>(values: impl Iterator<Item = &'a f64> + Clone) -> PlainStats {
    let valid = values.filter(|z| !z.is_nan());
    let n = valid.clone().count();
    let mean = valid.clone().sum::<f64>() / n as f64;
    let (mut m2, mut m3, mut m4, mut sa) = (0.0, 0.0, 0.0, 0.0);
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for &z in valid {
        let d = z - mean;
        m2 += d * d;
        m3 += d * d * d;
        m4 += d * d * d * d;
        sa += d.abs();
        lo = lo.min(z);
        hi = hi.max(z);
    }
    let nf = n as f64;
    let sq = (m2 / nf).sqrt();
    PlainStats {
        n_valid: n,
        sq,
        sa: sa / nf,
        sz: hi - lo,
        ssk: m3 / nf / sq.powi(3),
        sku: m4 / nf / sq.powi(4),
    }
}

/// Rq as SurfaceTopography defines it: every profile along x relative to its own mean, the
/// squares averaged over all points (no missing points allowed).
pub fn rq_profiles_along_x(map: &HeightMap) -> f64 {
    let h = map.heights();
    let mut sum = 0.0;
    for row in h.rows() {
        let mean = row.sum() / row.len() as f64;
        sum += row.iter().map(|z| (z - mean).powi(2)).sum::<f64>();
    }
    (sum / h.len() as f64).sqrt()
}

/// SurfaceTopography's `rms_gradient`: sqrt(mean((dh/dx)² + (dh/dy)²)) with forward differences
/// on the cropped (nx−1)×(ny−1) grid. Sensitive to swapped or wrong dx, dy.
pub fn rms_gradient(map: &HeightMap) -> f64 {
    let h = map.heights();
    let (ny, nx) = h.dim();
    let mut sum = 0.0;
    for iy in 0..ny - 1 {
        for ix in 0..nx - 1 {
            let gx = (h[[iy, ix + 1]] - h[[iy, ix]]) / map.dx();
            let gy = (h[[iy + 1, ix]] - h[[iy, ix]]) / map.dy();
            sum += gx * gx + gy * gy;
        }
    }
    (sum / ((nx - 1) * (ny - 1)) as f64).sqrt()
}

/// Asserts `|actual − expected| ≤ rtol·|expected|`.
#[track_caller]
pub fn assert_rel(what: &str, actual: f64, expected: f64, rtol: f64) {
    assert!(
        (actual - expected).abs() <= rtol * expected.abs(),
        "{what}: got {actual:e}, expected {expected:e} (rtol {rtol:e})"
    );
}
