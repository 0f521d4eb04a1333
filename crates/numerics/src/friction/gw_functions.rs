//! Greenwood–Williamson functions F_n(t) and the Gaussian helpers of the statistical models.
//!
//! F_n(t) = ∫_t^∞ (s − t)^n φ(s) ds with φ the standard normal density (Greenwood & Williamson,
//! Proc. R. Soc. A 295 (1966) 300). F_0 is the upper tail probability, F_1(0) = 1/√(2π).

use super::error::{require_non_negative, FrictionError};
use super::quadrature::{breakpoints, integrate, pieces_graded_at_start, QuadratureOutcome};

/// 1/√(2π).
pub(crate) const INV_SQRT_2PI: f64 = 0.398_942_280_401_432_7;

/// Number of standard deviations beyond which the Gaussian is negligible (φ < 1e-300 at 40:
/// exp(−800) underflows; docs/friction-models.md, "Numerics of the statistical models").
pub(crate) const GAUSSIAN_CUT: f64 = 40.0;

/// Standard deviations of the Gaussian at which integrals get breakpoints (peak and flanks).
pub(crate) const GAUSSIAN_FEATURES: [f64; 9] = [-8.0, -4.0, -2.0, -1.0, 0.0, 1.0, 2.0, 4.0, 8.0];

/// Relative tolerance of every statistical integral (docs/friction-models.md, "Numerics").
pub const INTEGRAL_REL_TOL: f64 = 1e-10;

/// Normal density with zero mean and standard deviation `std` at `z`.
pub(crate) fn normal_pdf(z: f64, std: f64) -> f64 {
    let u = z / std;
    INV_SQRT_2PI / std * (-0.5 * u * u).exp()
}

/// Upper tail probability ∫_t^∞ φ(s) ds of the standard normal (= F_0(t)), via `libm::erfc`.
pub fn upper_tail_probability(t: f64) -> f64 {
    0.5 * libm::erfc(t / std::f64::consts::SQRT_2)
}

/// GW function F_n(t) = ∫_t^∞ (s − t)^n φ(s) ds for n ≥ 0, to relative tolerance
/// [`INTEGRAL_REL_TOL`] (adaptive Gauss–Kronrod, graded at s = t, split at the Gaussian peak and
/// flanks, cut at s = max(t, 0) + 40).
///
/// Reference values (GW 1966 tables): F_1(0) = 0.39894, F_{3/2}(0) = 0.43002,
/// F_{3/2}(1) = 0.075668, F_{3/2}(2) = 0.0066482, F_{3/2}(3) = 2.6397e-4.
pub fn gw_function(n: f64, t: f64) -> Result<QuadratureOutcome, FrictionError> {
    require_non_negative("n", n)?;
    if !t.is_finite() {
        return Err(FrictionError::InvalidParameter {
            name: "t",
            value: t,
            expected: "a finite value",
        });
    }
    if n == 0.0 {
        return Ok(QuadratureOutcome {
            value: upper_tail_probability(t),
            error: 0.0,
            evaluations: 0,
            converged: true,
        });
    }
    let integrand = |u: f64| u.powf(n) * normal_pdf(u + t, 1.0);
    let u_max = t.max(0.0) + GAUSSIAN_CUT - t;
    let features: Vec<f64> = GAUSSIAN_FEATURES.iter().map(|g| g - t).collect();
    let points = breakpoints(0.0, u_max, &features);
    let pieces = pieces_graded_at_start(&points, &integrand);
    let outcome = integrate(&pieces, INTEGRAL_REL_TOL, 0.0);
    if outcome.converged {
        Ok(outcome)
    } else {
        Err(FrictionError::QuadratureNotConverged {
            what: "GW function F_n(t)",
            value: outcome.value,
            error: outcome.error,
        })
    }
}
