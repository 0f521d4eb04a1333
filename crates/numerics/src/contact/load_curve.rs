//! Results of a load-stepped contact solve: one row per load step, fields on demand.

use ndarray::Array2;

use super::options::{Residuals, SolvePath};
use super::work::Work;

/// Fields of one load step, each `[[iy, ix]]` on the contact grid; `None` unless requested
/// through [`super::FieldRequest`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ContactFields {
    /// Contact pressure `p` in Pa (`0 ≤ p ≤ p_lim`).
    pub pressure: Option<Array2<f64>>,
    /// Gap `g = g₀ + u − δ` in m after loading (`≤ 0` only at saturated points).
    pub gap: Option<Array2<f64>>,
    /// Elastic normal deformation of the first body in m: `u · c₁/(c₁ + c₂)`.
    pub deformation_first: Option<Array2<f64>>,
    /// Elastic normal deformation of the second body in m: `u · c₂/(c₁ + c₂)`.
    pub deformation_second: Option<Array2<f64>>,
    /// Plastic penetration `max(0, −g)` in m where `p = p_lim`, 0 elsewhere.
    pub plastic_penetration: Option<Array2<f64>>,
}

/// Results of one converged load step (SI units).
///
/// Elastic displacements `u` are absolute for [`super::Boundary::NonPeriodic`] and measured from
/// the mean displaced plane for [`super::Boundary::Periodic`] (where the mean of `u` is zero); the
/// approach `δ` follows the same convention and is zero at first contact for non-periodic grids.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadStep {
    /// Nominal (apparent) pressure `p̄` in Pa.
    pub nominal_pressure: f64,
    /// True contact area share `A_true / A_nominal` (points with `p > 0`).
    pub area_fraction: f64,
    /// Mean pressure on the true contact area `p̄ / (A_true/A_nominal)` in Pa.
    pub mean_contact_pressure: f64,
    /// Stress ratio `θ = mean contact pressure / p_lim` (0 for a purely elastic material).
    pub stress_ratio: f64,
    /// Share of the true contact area at the flow pressure (`p = p_lim`).
    pub plastic_area_share: f64,
    /// Mean separation `mean(max(g, 0))` over the nominal area in m.
    pub mean_separation: f64,
    /// Largest composite elastic deformation `max u` in m.
    pub max_elastic_deformation: f64,
    /// Rigid-body approach `δ` in m.
    pub approach: f64,
    /// CG iterations of this step on its own grid.
    pub iterations: usize,
    /// CG iterations of the multilevel start on the coarser grids (each with a quarter of the
    /// points of the next finer one), summed over them; 0 after a warm start (which elastic
    /// contacts on grids that can be coarsened do not take: `SolverOptions::multilevel`).
    pub coarse_iterations: usize,
    /// CG iterations of this step on its moving points alone (free points, points entering or
    /// leaving saturation; each a product with the operator restricted to them instead of an FFT
    /// pair; see `free_set.rs`), not counted in `iterations`.
    pub free_set_iterations: usize,
    /// Real 2-D FFTs (forward or inverse; a full convolution is two) of this step on its own
    /// grid, including the exact recomputations of the displacement and the start.
    pub fft_transforms: usize,
    /// Final residuals (all `≤` the tolerance).
    pub residuals: Residuals,
    /// Algorithm that produced the step.
    pub path: SolvePath,
    /// Fields, if requested.
    pub fields: Option<ContactFields>,
}

/// A load curve: one [`LoadStep`] per nominal pressure, in ascending order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LoadCurve {
    pub steps: Vec<LoadStep>,
}

impl LoadStep {
    /// The work of this step on its own grid (the coarse grids' iterations are
    /// `coarse_iterations`).
    pub fn work(&self) -> Work {
        Work {
            iterations: self.iterations,
            free_set_iterations: self.free_set_iterations,
            fft_transforms: self.fft_transforms,
        }
    }
}

impl LoadCurve {
    /// The work of every step on its own grid, added up.
    pub fn work(&self) -> Work {
        self.steps
            .iter()
            .map(LoadStep::work)
            .fold(Work::default(), |a, b| a + b)
    }
}
