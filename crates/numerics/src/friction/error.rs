//! Typed errors of the friction models.

use thiserror::Error;

/// Every failure of the friction library: bad input, an invalid roughness regime, or a load that
/// the statistical model cannot carry. No function of this module panics or returns NaN instead.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum FrictionError {
    /// An input parameter is outside its physical range.
    #[error("invalid parameter `{name}` = {value}: expected {expected}")]
    InvalidParameter {
        /// Parameter name as in the documentation.
        name: &'static str,
        /// The offending value (SI units).
        value: f64,
        /// Human-readable expected range.
        expected: &'static str,
    },
    /// Nayak's bandwidth parameter α = m0 m4 / m2² is at or below the McCool validity bound
    /// 0.8968 (β ≤ 0.01928), where the summit-height variance σ_s² = (1 − 0.8968/α) m0 is not positive.
    #[error("bandwidth parameter alpha = {alpha} (beta = {beta}) is at or below the McCool bound 0.8968 (beta 0.01928)")]
    BandwidthBelowMcCoolBound {
        /// Nayak's α.
        alpha: f64,
        /// β = η R σ = √(α / 768π).
        beta: f64,
    },
    /// The tensile external load is below the pull-off load: no equilibrium separation exists.
    #[error(
        "external load {load} N is below the pull-off load {pull_off} N (the surfaces separate)"
    )]
    LoadBelowPullOff {
        /// Requested external load (N, compressive positive).
        load: f64,
        /// Most tensile load the interface can carry (N, negative).
        pull_off: f64,
    },
    /// The compressive load needs a separation below the lowest one searched.
    #[error("external load {load} N exceeds the load {max_load} N carried at the lowest searched separation d* = {d_star_min}")]
    LoadAboveSearchRange {
        /// Requested external load (N).
        load: f64,
        /// Net load at the lowest separation searched (N).
        max_load: f64,
        /// Lowest dimensionless separation searched.
        d_star_min: f64,
    },
    /// Two arrays that describe the same grid have different shapes.
    #[error("array `{name}` has shape {found:?}, expected {expected:?} (ny, nx)")]
    ShapeMismatch {
        /// Name of the offending array.
        name: &'static str,
        /// Shape of the reference array (ny, nx).
        expected: (usize, usize),
        /// Shape found (ny, nx).
        found: (usize, usize),
    },
    /// An adaptive quadrature did not reach its relative tolerance within its interval budget.
    #[error("quadrature of {what} did not converge: estimated error {error} on value {value}")]
    QuadratureNotConverged {
        /// Which integral.
        what: &'static str,
        /// Integral value reached.
        value: f64,
        /// Estimated absolute error.
        error: f64,
    },
}

/// Check that `value` is finite and strictly positive.
pub(crate) fn require_positive(name: &'static str, value: f64) -> Result<f64, FrictionError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(FrictionError::InvalidParameter {
            name,
            value,
            expected: "a finite value > 0",
        })
    }
}

/// Check that `value` is finite and not negative.
pub(crate) fn require_non_negative(name: &'static str, value: f64) -> Result<f64, FrictionError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(FrictionError::InvalidParameter {
            name,
            value,
            expected: "a finite value >= 0",
        })
    }
}
