//! Hybrid parameters of ISO 25178-2: root-mean-square gradient `Sdq` and developed interfacial area
//! ratio `Sdr`, from finite differences of the height map.
//!
//! Continuous definitions (ISO 25178-2:2012, §4.3.1 and §4.3.2), over the definition area `A`:
//!
//! * `Sdq = sqrt( (1/A) ∬ [ (∂z/∂x)² + (∂z/∂y)² ] dx dy )`
//! * `Sdr = (1/A) ∬ [ sqrt(1 + (∂z/∂x)² + (∂z/∂y)²) − 1 ] dx dy`, reported here in **percent**.
//!
//! Discretisations offered ([`DifferenceScheme`]):
//!
//! * [`DifferenceScheme::Central`] (the ISO-style choice): at point `(ix, iy)`
//!   `∂z/∂x ≈ (z[ix+1] − z[ix−1]) / (2 dx)`, `∂z/∂y ≈ (z[iy+1] − z[iy−1]) / (2 dy)`. With
//!   [`Boundary::Open`] only interior points (all four axial neighbours inside the grid) contribute;
//!   with [`Boundary::Periodic`] neighbours wrap around.
//! * [`DifferenceScheme::Forward`] (SurfaceTopography's `rms_gradient`):
//!   `∂z/∂x ≈ (z[ix+1] − z[ix]) / dx`, `∂z/∂y ≈ (z[iy+1] − z[iy]) / dy`, both evaluated at the
//!   same point `(ix, iy)`. With [`Boundary::Open`] this is the cropped `(nx−1)×(ny−1)` grid
//!   `ix < nx−1, iy < ny−1`, which reproduces the reference values in the project's
//!   `topography/SOURCES.md`; with [`Boundary::Periodic`] the differences wrap around.
//!
//! Missing points: a point contributes only if it is valid **and** every neighbour its differences use
//! is valid; the mean is taken over the contributing points (`point_count`). `Sdr` uses the same
//! per-point gradients, i.e. the local surface element `sqrt(1 + |∇z|²) dx dy`.

use super::HeightMap;

/// How neighbours beyond the edge of the grid are treated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Boundary {
    /// The grid ends at its edge: a stencil that needs a point outside the grid is not evaluated.
    #[default]
    Open,
    /// The surface repeats with period `(nx·dx, ny·dy)`: neighbours wrap around.
    Periodic,
}

/// Finite-difference scheme for the slopes (see the module documentation for the formulas).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DifferenceScheme {
    /// Central differences, second-order accurate (ISO-style).
    Central,
    /// Forward differences, first-order accurate (SurfaceTopography `rms_gradient`).
    Forward,
}

impl DifferenceScheme {
    /// The scheme's name in messages.
    pub fn name(self) -> &'static str {
        match self {
            DifferenceScheme::Central => "central",
            DifferenceScheme::Forward => "forward",
        }
    }
}

/// `Sdq` and `Sdr` of one height map for one scheme and boundary treatment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GradientStatistics {
    /// Difference scheme used.
    pub scheme: DifferenceScheme,
    /// Boundary treatment used.
    pub boundary: Boundary,
    /// Root-mean-square gradient `Sdq` (dimensionless, m/m).
    pub sdq: f64,
    /// Developed interfacial area ratio `Sdr` in percent.
    pub sdr_percent: f64,
    /// Number of grid points whose gradient entered the means.
    pub point_count: usize,
}

/// Why gradient statistics could not be computed.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum GradientError {
    #[error(
        "no grid point has all the valid neighbours the {} difference scheme needs",
        scheme.name()
    )]
    NoGradientPoints { scheme: DifferenceScheme },
}

/// Index of the neighbour `i + offset` on an axis of `n` points, or `None` outside an open grid.
pub(crate) fn neighbour_index(
    i: usize,
    offset: isize,
    n: usize,
    boundary: Boundary,
) -> Option<usize> {
    let j = i as isize + offset;
    if (0..n as isize).contains(&j) {
        Some(j as usize)
    } else {
        match boundary {
            Boundary::Open => None,
            Boundary::Periodic => Some(j.rem_euclid(n as isize) as usize),
        }
    }
}

/// `Sdq` and `Sdr` (percent) of `map` with the given scheme and boundary treatment.
///
/// Sums are accumulated per row (rows in parallel) and then over rows in row order (two-level
/// summation, the same bits for any thread count).
/// `sqrt(1 + g²) − 1` is evaluated as `g² / (sqrt(1 + g²) + 1)` to avoid cancellation at small slopes.
pub fn gradient_statistics(
    map: &HeightMap,
    scheme: DifferenceScheme,
    boundary: Boundary,
) -> Result<GradientStatistics, GradientError> {
    let (sum_g2, sum_area, count) = gradient_sums::<true>(map, scheme, boundary);
    if count == 0 {
        return Err(GradientError::NoGradientPoints { scheme });
    }
    let n = count as f64;
    Ok(GradientStatistics {
        scheme,
        boundary,
        sdq: (sum_g2 / n).sqrt(),
        sdr_percent: 100.0 * sum_area / n,
        point_count: count,
    })
}

/// The root-mean-square gradient ([`GradientStatistics::sdq`]) and the point count of
/// [`gradient_statistics`], without the area term of `Sdr`: the same bits, one square root and
/// one division per point less.
pub(crate) fn rms_gradient(
    map: &HeightMap,
    scheme: DifferenceScheme,
    boundary: Boundary,
) -> Result<(f64, usize), GradientError> {
    let (sum_g2, _, count) = gradient_sums::<false>(map, scheme, boundary);
    if count == 0 {
        return Err(GradientError::NoGradientPoints { scheme });
    }
    Ok(((sum_g2 / count as f64).sqrt(), count))
}

/// `(Σ g², Σ area excess, points)` of [`gradient_statistics`]; the area excess is summed only
/// with `AREA` (0 otherwise).
fn gradient_sums<const AREA: bool>(
    map: &HeightMap,
    scheme: DifferenceScheme,
    boundary: Boundary,
) -> (f64, f64, usize) {
    let (nx, ny) = (map.nx(), map.ny());
    // Offsets (back, ahead) of the two points each difference uses, and its denominator factor.
    let (back, ahead, factor) = match scheme {
        DifferenceScheme::Central => (-1, 1, 2.0),
        DifferenceScheme::Forward => (0, 1, 1.0),
    };
    let (sx, sy) = (factor * map.dx(), factor * map.dy());
    let columns: Vec<Option<(usize, usize)>> = (0..nx)
        .map(|ix| {
            Some((
                neighbour_index(ix, back, nx, boundary)?,
                neighbour_index(ix, ahead, nx, boundary)?,
            ))
        })
        .collect();
    // Per row `(Σ g², Σ area excess, points)`, in parallel; the rows are added in row order.
    let rows = map.map_rows(|iy, flat| {
        let (Some(ya), Some(yb)) = (
            neighbour_index(iy, back, ny, boundary),
            neighbour_index(iy, ahead, ny, boundary),
        ) else {
            return (0.0, 0.0, 0);
        };
        let row = |iy: usize| &flat[iy * nx..(iy + 1) * nx];
        let (centre, row_a, row_b) = (row(iy), row(ya), row(yb));
        let mut row_g2 = 0.0;
        let mut row_area = 0.0;
        let mut row_count = 0usize;
        for (ix, cols) in columns.iter().enumerate() {
            let Some((xa, xb)) = *cols else {
                continue;
            };
            let gx = (centre[xb] - centre[xa]) / sx;
            let gy = (row_b[ix] - row_a[ix]) / sy;
            let g2 = gx * gx + gy * gy;
            // NaN in any point used (or in the centre itself) excludes the point.
            if centre[ix].is_nan() || g2.is_nan() {
                continue;
            }
            row_g2 += g2;
            if AREA {
                row_area += g2 / ((1.0 + g2).sqrt() + 1.0);
            }
            row_count += 1;
        }
        (row_g2, row_area, row_count)
    });
    rows.into_iter()
        .fold((0.0, 0.0, 0usize), |(g2, area, count), row| {
            (g2 + row.0, area + row.1, count + row.2)
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use ndarray::Array2;

    /// [`rms_gradient`] has the bits and the count of [`gradient_statistics`]' `Sdq` for both
    /// schemes and boundaries, with missing points, and its error where no point qualifies.
    #[test]
    fn rms_gradient_equals_the_sdq_of_the_full_statistics() {
        let heights = Array2::from_shape_fn((23, 31), |(j, i)| {
            if (j * 31 + i) % 41 == 5 {
                f64::NAN
            } else {
                1e-6 * ((0.3 * i as f64).sin() + (0.17 * (i * j) as f64).cos())
            }
        });
        let map = HeightMap::new(heights, 1e-6, 2e-6).unwrap();
        for scheme in [DifferenceScheme::Central, DifferenceScheme::Forward] {
            for boundary in [Boundary::Open, Boundary::Periodic] {
                let full = gradient_statistics(&map, scheme, boundary).unwrap();
                let (sdq, count) = rms_gradient(&map, scheme, boundary).unwrap();
                assert_eq!(sdq.to_bits(), full.sdq.to_bits(), "{scheme:?} {boundary:?}");
                assert_eq!(count, full.point_count);
            }
        }
        let missing = HeightMap::new(Array2::from_elem((4, 4), f64::NAN), 1.0, 1.0).unwrap();
        assert_eq!(
            rms_gradient(&missing, DifferenceScheme::Forward, Boundary::Open),
            Err(GradientError::NoGradientPoints {
                scheme: DifferenceScheme::Forward
            })
        );
    }
}
