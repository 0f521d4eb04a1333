//! Solver options, termination reasons and residuals.

use std::fmt;

/// Smallest relative tolerance `ε` the solver accepts.
///
/// Every residual is a gap error relative to the gap scale `h` (see [`Residuals`]) or a force
/// error relative to `p̄`, so its floor is f64 rounding: the gap `g = g₀ + u − δ` sums terms of
/// several `h`, each rounded to `ε_f64 = 2.2e-16` of itself, and the displacement `u` comes out
/// of an FFT convolution whose rounding grows like `ε_f64 · log₂ N · max|u|/h`. That is a few
/// `ε_f64` on small grids and up to ~1e-13 on the largest grids near saturation (`max|u|` of
/// tens of `h`), where the approach search also converges its inner solves ten times tighter
/// than `ε` (down to [`INNER_TOLERANCE_FLOOR`]). `ε` is kept ten times above that floor, so
/// every accepted tolerance is reachable in f64 (measurements: `docs/study-format.md`,
/// contact `tolerance`).
pub const MIN_TOLERANCE: f64 = 1e-12;

/// Tightest tolerance of an inner solve of the approach search: the residual floor of f64
/// gaps on the largest grids (see [`MIN_TOLERANCE`]).
pub const INNER_TOLERANCE_FLOOR: f64 = 1e-13;

/// Tolerances are relative errors: `ε` must be below 1 (exclusive).
pub const MAX_TOLERANCE: f64 = 1.0;

/// Which fields a load step returns (each costs one `ny × nx` array per step).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FieldRequest {
    /// Contact pressure `p` in Pa.
    pub pressure: bool,
    /// Gap `g` in m after loading (negative where plastic flow removed material).
    pub gap: bool,
    /// Elastic normal deformation of each body in m (split of the composite displacement).
    pub deformation: bool,
    /// Plastic penetration `max(0, −g)` in m at saturated points.
    pub plastic_penetration: bool,
}

impl FieldRequest {
    /// No fields: only the scalar load-step results.
    pub const NONE: Self = Self {
        pressure: false,
        gap: false,
        deformation: false,
        plastic_penetration: false,
    };
    /// All fields.
    pub const ALL: Self = Self {
        pressure: true,
        gap: true,
        deformation: true,
        plastic_penetration: true,
    };

    /// `true` if any field is requested.
    pub fn any(&self) -> bool {
        self.pressure || self.gap || self.deformation || self.plastic_penetration
    }
}

/// How a load step is solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SolveStrategy {
    /// Load-controlled constrained CG first; on `Stalled` / `MaxIterations` the approach search.
    #[default]
    Auto,
    /// Load-controlled constrained conjugate gradients only (Polonsky & Keer 1999).
    ConstrainedCg,
    /// Outer search on the rigid-body approach with an inner displacement-controlled solve only.
    ApproachSearch,
}

/// Which algorithm produced a load step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SolvePath {
    /// Load-controlled constrained CG.
    ConstrainedCg,
    /// Outer search on the approach (Illinois regula falsi) with inner constrained CG.
    ApproachSearch,
}

/// Options of [`super::ContactSolver`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverOptions {
    /// Relative tolerance `ε` of every convergence condition (see [`Residuals`]).
    pub tolerance: f64,
    /// Maximum number of CG iterations per load step (summed over the approach search).
    pub max_iterations: usize,
    /// A solve that has not reduced its largest residual below 0.9 × its best value for this
    /// many iterations is `Stalled` (default 60: a load-controlled CG that stalls with almost all
    /// contact points saturated hands over to the approach search early instead of after
    /// hundreds of idle iterations; measurements in `docs/contact-solver-design.md`).
    pub stall_iterations: usize,
    /// Algorithm choice.
    pub strategy: SolveStrategy,
    /// Start a step without a warm start (the first step, or after `reset`) from the solution
    /// on coarser grids where the grid allows it (default `true`; see `multilevel.rs`);
    /// otherwise from the rigid-plastic start. On an elastic contact (no flow pressure) whose
    /// grid allows it, every step starts so, instead of from the last converged step.
    pub multilevel: bool,
    /// Build the conjugate directions of an elastic contact (no flow pressure) started from a
    /// coarser grid's solution (the multilevel start) from the residual preconditioned by the
    /// inverse of the elastic operator on the whole grid (default `true`; see
    /// `constrained_cg.rs`). Other starts and contacts with a flow pressure are never
    /// preconditioned.
    pub preconditioned: bool,
    /// Iterate with single-precision transforms until the residual reaches the tolerance or
    /// `1e-5`, then finish in double precision (default `true`; see
    /// `constrained_cg/precision.rs`): every convergence is still judged on a displacement
    /// `u = K p` computed in double precision, so the result meets the tolerance as a
    /// double-precision solve does, though not bit for bit the same. With `false`, every
    /// transform is in double precision (the results of the solver before this option).
    pub mixed_precision: bool,
    /// Fields returned with every load step.
    pub fields: FieldRequest,
}

/// A solver option the solver cannot work with (see [`SolverOptions::check`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("solver option {name} = {value} is invalid: {reason}")]
pub struct BadOption {
    pub name: &'static str,
    pub value: f64,
    pub reason: String,
}

impl SolverOptions {
    /// Checks the options the solver cannot work with: a tolerance outside
    /// [`MIN_TOLERANCE`]`..`[`MAX_TOLERANCE`] (or not a number), no iterations.
    pub fn check(&self) -> Result<(), BadOption> {
        if !(MIN_TOLERANCE..MAX_TOLERANCE).contains(&self.tolerance) {
            return Err(BadOption {
                name: "tolerance",
                value: self.tolerance,
                reason: format!(
                    "must be at least {MIN_TOLERANCE:e} (the smallest residual the solver \
                     resolves in f64) and below {MAX_TOLERANCE}"
                ),
            });
        }
        if self.max_iterations == 0 {
            return Err(BadOption {
                name: "max_iterations",
                value: 0.0,
                reason: String::from("must be > 0"),
            });
        }
        Ok(())
    }
}

impl Default for SolverOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-6,
            max_iterations: 10_000,
            stall_iterations: 60,
            strategy: SolveStrategy::Auto,
            multilevel: true,
            preconditioned: true,
            mixed_precision: true,
            fields: FieldRequest::NONE,
        }
    }
}

/// Why an iterative solve stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Termination {
    /// Every residual is at most the tolerance.
    Converged,
    /// The iteration limit was reached first.
    MaxIterations,
    /// No progress within `stall_iterations`.
    Stalled,
    /// The approach search could not bracket or reach the target load.
    ApproachSearchFailed,
    /// A residual became NaN or infinite: the problem's numbers overflow or underflow (heights,
    /// moduli or pressures far outside physical ranges), so the iteration stops at once.
    NonFinite,
}

impl fmt::Display for Termination {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Termination::Converged => "converged",
            Termination::MaxIterations => "iteration limit reached",
            Termination::Stalled => "stalled",
            Termination::ApproachSearchFailed => "approach search failed",
            Termination::NonFinite => "a residual became NaN or infinite (numbers overflow)",
        })
    }
}

/// Convergence residuals of a solve, all dimensionless.
///
/// With `h` the gap scale (the composite rms roughness `S_q`, at least the elastic pixel
/// displacement `p̄ √(dx dy) / E*`), `g` the gap, `p` the pressure, `p̄` the nominal pressure:
/// * `separation = max over p = 0 of max(0, −g) / h` (no interpenetration outside contact);
/// * `contact = max over 0 < p < p_lim of |g| / h` (closed gap where the contact is elastic);
/// * `plastic = max over p = p_lim of max(0, g) / h` (no open gap at a saturated point);
/// * `force = |mean(p) − p̄| / p̄` (force balance).
///
/// A solve is converged when all four are at most the tolerance.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Residuals {
    pub separation: f64,
    pub contact: f64,
    pub plastic: f64,
    pub force: f64,
}

impl Residuals {
    /// The largest of the four residuals.
    pub fn max(&self) -> f64 {
        self.separation
            .max(self.contact)
            .max(self.plastic)
            .max(self.force)
    }
}
