//! Filling of missing points for stages that need a full grid (spectra, FFT contact).
//!
//! Method: **harmonic (Laplace) inpainting**. The filled heights `u` at the missing points solve the
//! discrete Laplace equation `(u_{x+1} + u_{x−1} − 2u)/dx² + (u_{y+1} + u_{y−1} − 2u)/dy² = 0` at every
//! missing point, with the valid heights as Dirichlet data and a zero-flux (Neumann) condition at the
//! grid edge (a neighbour outside the grid is dropped from the stencil). The result is the smoothest
//! (minimum Dirichlet energy) surface through the measured points; it adds no roughness inside holes,
//! so statistics of a filled surface are biased towards smoothness where holes are large — report the
//! number filled alongside any such statistic.
//!
//! Solver: conjugate gradients with a Jacobi (diagonal) preconditioner on the symmetric positive
//! definite system over the missing points (it is positive definite because every 4-connected hole
//! touches a valid point once at least one point is valid). Convergence criterion:
//! `‖b − A u‖₂ ≤ tolerance · ‖b‖₂`, with `b` the Dirichlet data term; the iteration count and the
//! achieved relative residual are reported. Initial guess: zero. All sums are
//! sequential, so the result is deterministic.

use super::{HeightMap, HeightMapError};

/// Options of [`fill_missing`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FillOptions {
    /// Relative residual `‖b − A u‖₂ / ‖b‖₂` at which the iteration stops.
    pub tolerance: f64,
    /// Maximum number of conjugate-gradient iterations.
    pub max_iterations: usize,
    /// Smallest share of valid points filled from: below it the "surface" would be invented
    /// from almost nothing (a map with one valid point becomes a constant plane).
    pub min_valid_fraction: f64,
}

impl Default for FillOptions {
    /// `tolerance = 1e-10`, `max_iterations = 100 000`, `min_valid_fraction = 0.01`.
    fn default() -> Self {
        Self {
            tolerance: 1e-10,
            max_iterations: 100_000,
            min_valid_fraction: 0.01,
        }
    }
}

/// A height map without missing points and how it was obtained.
#[derive(Debug, Clone, PartialEq)]
pub struct FilledSurface {
    /// The full height map (m): measured points unchanged, missing points filled.
    pub surface: HeightMap,
    /// Number of points that were missing and have been filled.
    pub filled_count: usize,
    /// Conjugate-gradient iterations performed (0 if nothing was missing).
    pub iterations: usize,
    /// Final relative residual `‖b − A u‖₂ / ‖b‖₂` (0 if nothing was missing or `b = 0`).
    pub relative_residual: f64,
}

/// Why missing points could not be filled.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FillError {
    #[error("the height map has no valid point to fill from")]
    NoValidPoints,
    #[error(
        "only {valid} of {total} points are valid (less than {:.0} %): filling would invent the \
         surface; crop to the measured region", 100.0 * min_fraction
    )]
    TooFewValidPoints {
        valid: usize,
        total: usize,
        min_fraction: f64,
    },
    #[error("tolerance must be finite and > 0, got {tolerance}")]
    BadTolerance { tolerance: f64 },
    #[error("harmonic fill did not converge: relative residual {relative_residual:e} after {iterations} iterations")]
    NotConverged {
        iterations: usize,
        relative_residual: f64,
    },
    #[error("filled heights do not form a valid height map: {0}")]
    HeightMap(#[from] HeightMapError),
}

/// Fills the missing points of `map` by harmonic inpainting (see the module documentation).
pub fn fill_missing(map: &HeightMap, options: FillOptions) -> Result<FilledSurface, FillError> {
    if !(options.tolerance.is_finite() && options.tolerance > 0.0) {
        return Err(FillError::BadTolerance {
            tolerance: options.tolerance,
        });
    }
    let nx = map.nx();
    let z: Vec<f64> = map.heights().iter().copied().collect();
    let missing: Vec<usize> = (0..z.len()).filter(|&p| z[p].is_nan()).collect();
    if missing.is_empty() {
        return Ok(FilledSurface {
            surface: map.clone(),
            filled_count: 0,
            iterations: 0,
            relative_residual: 0.0,
        });
    }
    if missing.len() == z.len() {
        return Err(FillError::NoValidPoints);
    }
    let valid = z.len() - missing.len();
    if (valid as f64) < options.min_valid_fraction * z.len() as f64 {
        return Err(FillError::TooFewValidPoints {
            valid,
            total: z.len(),
            min_fraction: options.min_valid_fraction,
        });
    }
    let system = LaplaceSystem::new(map, &z, &missing);
    let (x, iterations, residual) = system.solve(&options)?;
    let m = missing.len();
    let mut filled = map.heights().clone();
    for (&p, &value) in missing.iter().zip(&x) {
        filled[[p / nx, p % nx]] = value;
    }
    Ok(FilledSurface {
        surface: HeightMap::new(filled, map.dx(), map.dy())?,
        filled_count: m,
        iterations,
        relative_residual: residual,
    })
}

/// The discrete Laplace equation on the missing points (5-point stencil, weights scaled by dx²:
/// 1 along x, (dx/dy)² along y), the known neighbours moved to the right-hand side.
struct LaplaceSystem {
    /// Per unknown: its unknown neighbours and their weights.
    stencil: Vec<Vec<(usize, f64)>>,
    diag: Vec<f64>,
    b: Vec<f64>,
}

impl LaplaceSystem {
    fn new(map: &HeightMap, z: &[f64], missing: &[usize]) -> Self {
        let (nx, ny) = (map.nx(), map.ny());
        let wy = (map.dx() / map.dy()).powi(2);
        let mut unknown = vec![usize::MAX; z.len()];
        for (k, &p) in missing.iter().enumerate() {
            unknown[p] = k;
        }
        let m = missing.len();
        let mut stencil: Vec<Vec<(usize, f64)>> = Vec::with_capacity(m);
        let mut diag = vec![0.0; m];
        let mut b = vec![0.0; m];
        for (k, &p) in missing.iter().enumerate() {
            let (ix, iy) = (p % nx, p / nx);
            let mut links = Vec::with_capacity(4);
            let neighbours = [
                (ix > 0).then(|| (p - 1, 1.0)),
                (ix + 1 < nx).then(|| (p + 1, 1.0)),
                (iy > 0).then(|| (p - nx, wy)),
                (iy + 1 < ny).then(|| (p + nx, wy)),
            ];
            for (q, w) in neighbours.into_iter().flatten() {
                diag[k] += w;
                if z[q].is_nan() {
                    links.push((unknown[q], w));
                } else {
                    b[k] += w * z[q];
                }
            }
            stencil.push(links);
        }
        Self { stencil, diag, b }
    }

    /// `out = A x`.
    fn apply(&self, x: &[f64], out: &mut [f64]) {
        for (k, o) in out.iter_mut().enumerate() {
            *o = self.diag[k] * x[k] - self.stencil[k].iter().map(|&(j, w)| w * x[j]).sum::<f64>();
        }
    }

    /// Jacobi-preconditioned conjugate gradients from `x = 0` to the relative residual
    /// `|r|/|b| ≤ tolerance`: the solution, the iterations and the final relative residual.
    fn solve(&self, options: &FillOptions) -> Result<(Vec<f64>, usize, f64), FillError> {
        let (diag, b) = (&self.diag, &self.b);
        let m = b.len();
        let dot = |a: &[f64], c: &[f64]| a.iter().zip(c).map(|(x, y)| x * y).sum::<f64>();
        // Initial guess u = 0, so the initial residual is b; if b = 0 then u = 0 is the exact
        // solution.
        let mut x = vec![0.0; m];
        let mut r = b.clone();
        let b_norm = dot(b, b).sqrt();
        let reference = if b_norm > 0.0 { b_norm } else { 1.0 };
        let mut s: Vec<f64> = (0..m).map(|k| r[k] / diag[k]).collect();
        let mut d = s.clone();
        let mut rs = dot(&r, &s);
        let mut ad = vec![0.0; m];
        let mut iterations = 0;
        let mut residual = dot(&r, &r).sqrt() / reference;
        while residual > options.tolerance {
            if iterations == options.max_iterations {
                return Err(FillError::NotConverged {
                    iterations,
                    relative_residual: residual,
                });
            }
            self.apply(&d, &mut ad);
            let alpha = rs / dot(&d, &ad);
            for k in 0..m {
                x[k] += alpha * d[k];
                r[k] -= alpha * ad[k];
                s[k] = r[k] / diag[k];
            }
            let rs_new = dot(&r, &s);
            let beta = rs_new / rs;
            rs = rs_new;
            for k in 0..m {
                d[k] = s[k] + beta * d[k];
            }
            iterations += 1;
            residual = dot(&r, &r).sqrt() / reference;
        }
        Ok((x, iterations, residual))
    }
}
