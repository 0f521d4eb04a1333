//! The grid and solver settings of the separation solve (`static_friction`), which the
//! net-load grid (`net_load_grid`) shares.

use super::error::FrictionError;

/// Grid and solver settings of the separation solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolveSettings {
    /// Lowest d* of the initial grid (σ units).
    pub d_star_min: f64,
    /// Highest d* of the grid in units of s = σ_s/σ.
    pub d_star_max_in_summit_std: f64,
    /// Grid step in d*.
    pub grid_step: f64,
    /// Lowest d* the grid may be extended to for heavy loads.
    pub d_star_floor: f64,
    /// Brent absolute tolerance on d*.
    pub d_star_tolerance: f64,
}

impl Default for SolveSettings {
    fn default() -> Self {
        Self {
            d_star_min: -3.0,
            d_star_max_in_summit_std: 12.0,
            grid_step: 0.5,
            d_star_floor: -30.0,
            d_star_tolerance: 1e-11,
        }
    }
}

impl SolveSettings {
    /// Check the settings: finite values with d_star_floor ≤ d_star_min,
    /// d_star_max_in_summit_std > max(d_star_min, 0), a grid step ≥ 1e-3 (bounding the table
    /// size) and a positive tolerance.
    pub fn validated(&self) -> Result<Self, FrictionError> {
        let invalid = |name: &'static str, value: f64, expected: &'static str| {
            Err(FrictionError::InvalidParameter {
                name,
                value,
                expected,
            })
        };
        if !(self.grid_step.is_finite() && self.grid_step >= 1e-3) {
            return invalid("grid_step", self.grid_step, "a grid step >= 1e-3");
        }
        if !(self.d_star_min.is_finite()
            && self.d_star_floor.is_finite()
            && self.d_star_floor <= self.d_star_min)
        {
            return invalid(
                "d_star_floor",
                self.d_star_floor,
                "finite d_star_floor <= d_star_min",
            );
        }
        if !(self.d_star_max_in_summit_std.is_finite()
            && self.d_star_max_in_summit_std > self.d_star_min.max(0.0))
        {
            return invalid(
                "d_star_max_in_summit_std",
                self.d_star_max_in_summit_std,
                "a finite value above max(d_star_min, 0)",
            );
        }
        if !(self.d_star_tolerance.is_finite() && self.d_star_tolerance > 0.0) {
            return invalid(
                "d_star_tolerance",
                self.d_star_tolerance,
                "a finite tolerance > 0",
            );
        }
        Ok(*self)
    }
}
