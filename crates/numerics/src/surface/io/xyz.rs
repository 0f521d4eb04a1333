//! x y z point lists (text with three numeric columns), read by [`super::text`].
//!
//! The points must lie on a regular grid: the distinct x values, and the distinct y values, are
//! each equally spaced (to 10⁻⁶ of the step, enough for coordinates printed with 7 significant
//! digits), every grid node holds at most one point, and at least a quarter of the nodes are
//! present. Nodes absent from the list are missing points (`NaN`), as are `NaN` heights.
//! Scattered (non-uniform) points are refused, never interpolated silently: the message says how
//! to resample them onto a grid first. Lengths are metres unless the caller supplies a scale.

use std::collections::BTreeMap;

use ndarray::Array2;

use super::limits::MAX_POINTS;
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

/// How to turn scattered points into a grid, appended to every refusal.
const RESAMPLE: &str = "resample the points onto a regular grid first (e.g. Gwyddion's XYZ \
     import with `Rasterize`, or scipy.interpolate.griddata) and save the grid as a text matrix \
     or GSF; a 3-column height matrix needs a `w=3 h=<rows>` header line";

/// A regularly spaced set of coordinates.
struct RegularAxis {
    start: f64,
    step: f64,
    count: usize,
}

/// The distinct values of `values` when they are equally spaced; otherwise why not.
fn regular_axis(values: impl Iterator<Item = f64>, name: &str) -> Result<RegularAxis, String> {
    let mut v: Vec<f64> = values.collect();
    if let Some(bad) = v.iter().find(|x| !x.is_finite()) {
        return Err(format!("a {name} coordinate is {bad}"));
    }
    v.sort_by(f64::total_cmp);
    v.dedup();
    let (first, last) = match (v.first(), v.last()) {
        (Some(&f), Some(&l)) if v.len() >= 2 => (f, l),
        _ => return Err(format!("all points have the same {name}")),
    };
    let step = (last - first) / (v.len() - 1) as f64;
    match v
        .iter()
        .enumerate()
        .find(|(i, &x)| (x - (first + *i as f64 * step)).abs() > 1e-6 * step)
    {
        Some((i, x)) => Err(format!(
            "the {} distinct {name} values are not equally spaced ({name} = {x} is off the \
             step of {step} from {first} at index {i})",
            v.len()
        )),
        None => Ok(RegularAxis {
            start: first,
            step,
            count: v.len(),
        }),
    }
}

/// The grid of x y z triples (flattened in `rows`), heights and lengths in metres.
pub(super) fn grid(rows: &[f64]) -> Result<Topography, ParseError> {
    let refuse = |why: String| {
        ParseError::unsupported(format!(
            "x y z point list not on a regular grid: {why}; {RESAMPLE}"
        ))
    };
    let triples = || rows.chunks_exact(3);
    let xs = regular_axis(triples().map(|r| r[0]), "x").map_err(refuse)?;
    let ys = regular_axis(triples().map(|r| r[1]), "y").map_err(refuse)?;
    let (nx, ny) = (xs.count, ys.count);
    let count = rows.len() / 3;
    if nx.saturating_mul(ny) > count.saturating_mul(4).min(MAX_POINTS) {
        return Err(refuse(format!(
            "{count} points cover less than a quarter of the {nx} × {ny} grid their \
             coordinates span"
        )));
    }
    let mut grid = Array2::from_elem((ny, nx), f64::NAN);
    let mut filled = Array2::from_elem((ny, nx), false);
    for row in triples() {
        let ix = ((row[0] - xs.start) / xs.step).round() as usize;
        let iy = ((row[1] - ys.start) / ys.step).round() as usize;
        if std::mem::replace(&mut filled[[iy, ix]], true) {
            return Err(refuse(format!(
                "the point x = {}, y = {} appears twice",
                row[0], row[1]
            )));
        }
        grid[[iy, ix]] = row[2];
    }
    let map = HeightMap::new(grid, xs.step, ys.step)
        .map_err(|e| ParseError::malformed(format!("text: x y z grid: {e}")))?;
    let mut metadata = BTreeMap::new();
    metadata.insert("layout".into(), "xyz".into());
    metadata.insert("x_offset_m".into(), xs.start.to_string());
    metadata.insert("y_offset_m".into(), ys.start.to_string());
    Ok(Topography {
        spacing: ScaleSource::File,
        height_unit: ScaleSource::Assumed,
        data: TopographyData::Areal(map),
        channel: None,
        channels: Vec::new(),
        metadata,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scattered_points_are_refused_with_the_way_out() {
        let rows = [0.0, 0.0, 1.0, 1.0, 0.0, 2.0, 0.3, 1.0, 3.0, 1.0, 1.0, 4.0];
        let err = grid(&rows).unwrap_err().to_string();
        assert!(
            err.contains("not equally spaced") && err.contains("griddata"),
            "{err}"
        );
        let twice = [0.0, 0.0, 1.0, 1.0, 0.0, 2.0, 0.0, 1.0, 3.0, 0.0, 0.0, 4.0];
        let err = grid(&twice).unwrap_err().to_string();
        assert!(err.contains("appears twice"), "{err}");
    }
}
