//! The areal height map every stage works on.

use ndarray::Array2;
use rayon::prelude::*;

/// An areal topography on a regular grid, in SI units.
///
/// * `heights[[iy, ix]]` is the height in metres at `x = ix·dx`, `y = iy·dy`: rows are `y`,
///   columns are `x` (x is the fastest-varying index, as in every topography file format).
/// * A missing (non-measured, invalid) point is `NaN`. It is never stored as zero. Stages that need
///   a full grid (spectra, contact) must fill missing points explicitly first.
/// * `dx`, `dy` are the pixel spacings in metres (they may differ: anisotropic pixels).
#[derive(Debug, Clone, PartialEq)]
pub struct HeightMap {
    heights: Array2<f64>,
    dx: f64,
    dy: f64,
}

/// Why a [`HeightMap`] could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum HeightMapError {
    #[error("height map needs at least 2 × 2 points, got {nx} × {ny}")]
    TooSmall { nx: usize, ny: usize },
    #[error("pixel spacing must be finite and > 0 m, got dx = {dx} m, dy = {dy} m")]
    BadSpacing { dx: f64, dy: f64 },
    #[error("height at (ix = {ix}, iy = {iy}) is infinite; use NaN for missing points")]
    Infinite { ix: usize, iy: usize },
}

impl HeightMap {
    /// Builds a height map from heights in metres (`NaN` = missing) and spacings in metres.
    pub fn new(heights: Array2<f64>, dx: f64, dy: f64) -> Result<Self, HeightMapError> {
        let (ny, nx) = heights.dim();
        if nx < 2 || ny < 2 {
            return Err(HeightMapError::TooSmall { nx, ny });
        }
        if !(dx.is_finite() && dx > 0.0 && dy.is_finite() && dy > 0.0) {
            return Err(HeightMapError::BadSpacing { dx, dy });
        }
        if let Some(((iy, ix), _)) = heights.indexed_iter().find(|(_, z)| z.is_infinite()) {
            return Err(HeightMapError::Infinite { ix, iy });
        }
        Ok(Self { heights, dx, dy })
    }

    /// Heights in metres, `[[iy, ix]]`, `NaN` where missing.
    pub fn heights(&self) -> &Array2<f64> {
        &self.heights
    }

    /// Consumes the map and returns the heights.
    pub fn into_heights(self) -> Array2<f64> {
        self.heights
    }

    /// Number of points along x (columns).
    pub fn nx(&self) -> usize {
        self.heights.ncols()
    }

    /// Number of points along y (rows).
    pub fn ny(&self) -> usize {
        self.heights.nrows()
    }

    /// Pixel spacing along x in metres.
    pub fn dx(&self) -> f64 {
        self.dx
    }

    /// Pixel spacing along y in metres.
    pub fn dy(&self) -> f64 {
        self.dy
    }

    /// Physical size `(Lx, Ly) = (nx·dx, ny·dy)` in metres (periodic convention).
    pub fn size(&self) -> (f64, f64) {
        (self.nx() as f64 * self.dx, self.ny() as f64 * self.dy)
    }

    /// `f(iy, heights)` for every row `iy`, in parallel, in row order; `heights` is the whole grid
    /// row-major (row `iy` is `heights[iy·nx .. (iy + 1)·nx]`), so `f` may read neighbouring rows.
    /// A caller that folds the results in row order gets the bits of a serial loop over the rows,
    /// whatever the thread count.
    pub(crate) fn map_rows<T: Send>(&self, f: impl Fn(usize, &[f64]) -> T + Sync) -> Vec<T> {
        let z = self.heights.as_standard_layout();
        let flat = z
            .as_slice()
            .expect("an array in standard layout is contiguous");
        (0..self.ny())
            .into_par_iter()
            .map(|iy| f(iy, flat))
            .collect()
    }

    /// Number of missing (`NaN`) points.
    pub fn missing_count(&self) -> usize {
        self.heights.iter().filter(|z| z.is_nan()).count()
    }

    /// `true` where the point was measured, `false` where it is missing.
    pub fn valid_mask(&self) -> Array2<bool> {
        self.heights.mapv(|z| !z.is_nan())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_bad_input() {
        let z = Array2::<f64>::zeros((1, 5));
        assert_eq!(
            HeightMap::new(z, 1.0, 1.0),
            Err(HeightMapError::TooSmall { nx: 5, ny: 1 })
        );
        let z = Array2::<f64>::zeros((3, 3));
        assert!(matches!(
            HeightMap::new(z.clone(), 0.0, 1.0),
            Err(HeightMapError::BadSpacing { .. })
        ));
        let mut z2 = z;
        z2[[1, 2]] = f64::INFINITY;
        assert_eq!(
            HeightMap::new(z2, 1.0, 1.0),
            Err(HeightMapError::Infinite { ix: 2, iy: 1 })
        );
    }

    #[test]
    fn counts_missing_points() {
        let mut z = Array2::<f64>::zeros((3, 4));
        z[[0, 1]] = f64::NAN;
        let m = HeightMap::new(z, 1e-6, 2e-6).unwrap();
        assert_eq!(m.missing_count(), 1);
        assert!(!m.valid_mask()[[0, 1]]);
        assert_eq!((m.nx(), m.ny()), (4, 3));
        assert_eq!(m.size(), (4e-6, 6e-6));
    }
}
