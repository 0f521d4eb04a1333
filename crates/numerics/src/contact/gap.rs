//! Composite initial gap of two rough surfaces on one grid.

use std::sync::Arc;

use ndarray::{Array2, ArrayView2};

use crate::surface::HeightMap;

/// Which input a gap error refers to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GapSource {
    /// The first surface (or the only surface against a rigid flat).
    FirstSurface,
    /// The second surface.
    SecondSurface,
    /// A gap array given directly.
    GapArray,
}

impl std::fmt::Display for GapSource {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            GapSource::FirstSurface => "first surface",
            GapSource::SecondSurface => "second surface",
            GapSource::GapArray => "gap array",
        })
    }
}

/// Why a [`CompositeGap`] could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GapError {
    #[error(
        "the two surfaces are on different grids: first {nx1} × {ny1} at dx = {dx1} m, dy = {dy1} m, \
         second {nx2} × {ny2} at dx = {dx2} m, dy = {dy2} m (resample one of them first)"
    )]
    GridMismatch {
        nx1: usize,
        ny1: usize,
        dx1: f64,
        dy1: f64,
        nx2: usize,
        ny2: usize,
        dx2: f64,
        dy2: f64,
    },
    #[error("{source_name}: value {value} at (ix = {ix}, iy = {iy}) is not finite (missing points must be filled before contact)")]
    NonFinite {
        source_name: GapSource,
        ix: usize,
        iy: usize,
        value: f64,
    },
    #[error("contact grid needs at least 2 × 2 points, got {nx} × {ny}")]
    TooSmall { nx: usize, ny: usize },
    #[error("pixel spacing must be finite and > 0 m, got dx = {dx} m, dy = {dy} m")]
    BadSpacing { dx: f64, dy: f64 },
    #[error("the composite gap spans {span:e} m, whose rms overflows a 64-bit float: heights this large are no surface topography (check the height unit of the surfaces)")]
    Overflow { span: f64 },
}

/// Initial gap `g₀(x, y) ≥ 0` in metres between two rough bodies before loading, with
/// `min g₀ = 0` at the first point of contact (rigid-body approach `δ = 0`).
///
/// Each height map gives the heights of one body measured outward from its own mean plane,
/// towards the other body. With composite height `z = z₁ + z₂` (Johnson 1985, §13.1; the gap
/// of two rough surfaces equals that of one surface of height `z` against a rigid flat)
/// `g₀ = max z − z`. The gap is symmetric in the two surfaces.
///
/// Indexing is `[[iy, ix]]` with `x` fastest, as in [`HeightMap`]. The values are held once and
/// shared (a clone and the solver's workspace read the same array).
#[derive(Debug, Clone, PartialEq)]
pub struct CompositeGap {
    /// `g₀`, `ny · nx` values row-major.
    gap: Arc<Vec<f64>>,
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
}

/// One body's heights (m, `[[iy, ix]]`, as in [`HeightMap`]) on a grid of spacing `dx`, `dy`
/// (m), borrowed: what [`CompositeGap::from_height_views`] reads without copying a map.
#[derive(Debug, Clone, Copy)]
pub struct HeightsView<'a> {
    /// Heights in m.
    pub heights: ArrayView2<'a, f64>,
    /// Pixel spacing along x in m.
    pub dx: f64,
    /// Pixel spacing along y in m.
    pub dy: f64,
}

impl<'a> HeightsView<'a> {
    /// The heights and spacing of `map`.
    pub fn of(map: &'a HeightMap) -> Self {
        Self {
            heights: map.heights().view(),
            dx: map.dx(),
            dy: map.dy(),
        }
    }
}

fn first_non_finite(z: ArrayView2<f64>, source_name: GapSource) -> Result<(), GapError> {
    match z.indexed_iter().find(|(_, v)| !v.is_finite()) {
        Some(((iy, ix), &value)) => Err(GapError::NonFinite {
            source_name,
            ix,
            iy,
            value,
        }),
        None => Ok(()),
    }
}

/// The values of `a` row-major: its own buffer when it holds exactly them in that order (an
/// array made in standard layout), else a copy.
fn row_major_values(a: Array2<f64>) -> Vec<f64> {
    let len = a.len();
    if a.is_standard_layout() {
        let (values, offset) = a.into_raw_vec_and_offset();
        if values.len() == len && offset.unwrap_or(0) == 0 {
            return values;
        }
        let start = offset.unwrap_or(0);
        return values[start..start + len].to_vec();
    }
    a.iter().copied().collect()
}

impl CompositeGap {
    /// Gap of two rough surfaces on the same grid (same `nx`, `ny`, `dx`, `dy`).
    pub fn from_surfaces(first: &HeightMap, second: &HeightMap) -> Result<Self, GapError> {
        Self::from_height_views(HeightsView::of(first), Some(HeightsView::of(second)))
    }

    /// Gap of one rough surface against a rigid (or elastic) flat.
    pub fn against_flat(surface: &HeightMap) -> Result<Self, GapError> {
        Self::from_height_views(HeightsView::of(surface), None)
    }

    /// [`Self::from_surfaces`] of two borrowed height maps, or [`Self::against_flat`] of `first`
    /// without `second`: the composite height `z₁ + z₂` is the one array allocated (it becomes
    /// the gap in place).
    pub fn from_height_views(
        first: HeightsView<'_>,
        second: Option<HeightsView<'_>>,
    ) -> Result<Self, GapError> {
        first_non_finite(first.heights, GapSource::FirstSurface)?;
        let Some(second) = second else {
            return Self::from_composite_height(first.heights.to_owned(), first.dx, first.dy);
        };
        let ((ny1, nx1), (ny2, nx2)) = (first.heights.dim(), second.heights.dim());
        if (nx1, ny1, first.dx, first.dy) != (nx2, ny2, second.dx, second.dy) {
            return Err(GapError::GridMismatch {
                nx1,
                ny1,
                dx1: first.dx,
                dy1: first.dy,
                nx2,
                ny2,
                dx2: second.dx,
                dy2: second.dy,
            });
        }
        first_non_finite(second.heights, GapSource::SecondSurface)?;
        let composite = &first.heights + &second.heights;
        Self::from_composite_height(composite, first.dx, first.dy)
    }

    /// Gap given directly in metres (e.g. `r²/2R` for a sphere); it is shifted so that
    /// `min g₀ = 0`.
    pub fn from_gap_array(gap: ArrayView2<f64>, dx: f64, dy: f64) -> Result<Self, GapError> {
        first_non_finite(gap, GapSource::GapArray)?;
        Self::from_composite_height(gap.mapv(|g| -g), dx, dy)
    }

    fn from_composite_height(height: Array2<f64>, dx: f64, dy: f64) -> Result<Self, GapError> {
        let (ny, nx) = height.dim();
        if nx < 2 || ny < 2 {
            return Err(GapError::TooSmall { nx, ny });
        }
        if !(dx.is_finite() && dx > 0.0 && dy.is_finite() && dy > 0.0) {
            return Err(GapError::BadSpacing { dx, dy });
        }
        let top = height.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let mut gap = height;
        gap.mapv_inplace(|z| top - z);
        // A sum of two finite heights can still overflow to infinity, and so can the squares of
        // finite gaps in their rms, on which every residual of the solver is scaled.
        first_non_finite(gap.view(), GapSource::GapArray)?;
        let gap = Self {
            gap: Arc::new(row_major_values(gap)),
            nx,
            ny,
            dx,
            dy,
        };
        if !gap.rms().is_finite() {
            let span = gap.gap.iter().copied().fold(0.0f64, f64::max);
            return Err(GapError::Overflow { span });
        }
        Ok(gap)
    }

    /// Initial gap in metres, `[[iy, ix]]`.
    pub fn gap(&self) -> ArrayView2<'_, f64> {
        ArrayView2::from_shape((self.ny, self.nx), &self.gap)
            .unwrap_or_else(|_| unreachable!("ny · nx values"))
    }

    /// The gap's values, `ny · nx` row-major, shared with this gap (no copy).
    pub(crate) fn shared_values(&self) -> Arc<Vec<f64>> {
        Arc::clone(&self.gap)
    }

    /// Number of points along x.
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Number of points along y.
    pub fn ny(&self) -> usize {
        self.ny
    }

    /// Pixel spacing along x in metres.
    pub fn dx(&self) -> f64 {
        self.dx
    }

    /// Pixel spacing along y in metres.
    pub fn dy(&self) -> f64 {
        self.dy
    }

    /// Root-mean-square deviation of the gap about its mean in metres (the composite `S_q`).
    pub fn rms(&self) -> f64 {
        let gap = self.gap();
        let n = gap.len() as f64;
        let mean = gap.sum() / n;
        let mut sum_sq = 0.0;
        gap.for_each(|&g| sum_sq += (g - mean) * (g - mean));
        (sum_sq / n).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ndarray::array;

    #[test]
    fn gap_is_symmetric_and_touches_at_zero() {
        let a = HeightMap::new(array![[0.0, 1.0], [2.0, 0.5]], 1e-6, 1e-6).unwrap();
        let b = HeightMap::new(array![[1.0, -1.0], [0.0, 0.5]], 1e-6, 1e-6).unwrap();
        let ab = CompositeGap::from_surfaces(&a, &b).unwrap();
        let ba = CompositeGap::from_surfaces(&b, &a).unwrap();
        assert_eq!(ab, ba);
        // z = [[1, 0], [2, 1]] ⇒ g₀ = 2 − z.
        assert_eq!(ab.gap(), array![[1.0, 2.0], [0.0, 1.0]]);
    }

    /// A gap array in column-major order gives the gap of the same array in row-major order.
    #[test]
    fn a_column_major_gap_array_gives_the_same_gap() {
        let rows = Array2::from_shape_fn((3, 4), |(y, x)| (y * 4 + x) as f64 * 0.5);
        let columns = rows.t().as_standard_layout().into_owned();
        let from_rows = CompositeGap::from_gap_array(rows.view(), 1.0, 2.0).unwrap();
        let from_columns = CompositeGap::from_gap_array(columns.t(), 1.0, 2.0).unwrap();
        assert_eq!(from_rows, from_columns);
        assert_eq!(from_rows.gap(), rows);
        assert_eq!((from_rows.nx(), from_rows.ny()), (4, 3));
    }

    #[test]
    fn rejects_mismatched_grids_and_missing_points() {
        let a = HeightMap::new(Array2::zeros((3, 3)), 1e-6, 1e-6).unwrap();
        let b = HeightMap::new(Array2::zeros((3, 3)), 2e-6, 1e-6).unwrap();
        assert!(matches!(
            CompositeGap::from_surfaces(&a, &b),
            Err(GapError::GridMismatch { .. })
        ));
        let mut z = Array2::zeros((3, 3));
        z[[2, 1]] = f64::NAN;
        let c = HeightMap::new(z, 1e-6, 1e-6).unwrap();
        let err = CompositeGap::from_surfaces(&a, &c).unwrap_err();
        assert!(matches!(
            err,
            GapError::NonFinite {
                source_name: GapSource::SecondSurface,
                ix: 1,
                iy: 2,
                ..
            }
        ));
        assert!(err.to_string().contains("second surface"));
        let g = array![[0.0, f64::INFINITY], [0.0, 0.0]];
        assert!(matches!(
            CompositeGap::from_gap_array(g.view(), 1.0, 1.0),
            Err(GapError::NonFinite { .. })
        ));
    }
}
