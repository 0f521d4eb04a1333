//! Jackson–Green (2005) single asperity: an elastic–perfectly-plastic hemisphere pressed by a
//! rigid flat, from first yield to fully plastic flow with a hardness that falls as the contact
//! grows (Jackson & Green, J. Tribol. 127 (2005) 343; status \[C2\] in the project reference
//! `docs/friction-models.md`).
//!
//! With E' the composite modulus, Y the yield strength and ν the Poisson ratio of the softer body
//! and R the sphere radius:
//!
//! ```text
//! C = 1.295 exp(0.736 ν)
//! ω_c = (π C Y / (2E'))² R        P_c = (4/3) (R/E')² (C π Y / 2)³        A_c = π R ω_c
//! ω* = ω/ω_c
//! ω* ≤ 1.9 (Hertz):  P/P_c = ω*^{3/2},   A/A_c = ω*,   a/R = √(ω/R)
//! ω* > 1.9:          P/P_c = exp(−¼ ω*^{5/12}) ω*^{3/2}
//!                           + (4 H_G/(C Y)) [1 − exp(−ω*^{5/9}/25)] ω*
//!                    A/A_c = ω* (ω*/1.9)^B,   B = 0.14 exp(23 Y/E')
//!                    a/R = √(ω/R) (ω*/1.9)^{B/2}
//!                    H_G/Y = 2.84 [1 − exp(−0.82 (a/R)^{−0.7})]
//! ```
//!
//! The laws are dimensionless given Y/E' and ν (ω/R = ω* (π C Y/(2E'))²), so [`JacksonGreenLaw`]
//! holds those two and every value is a ratio to the critical values of the radius at hand.
//! The area is continuous at ω* = 1.9; the load is not quite: the elastic–plastic branch starts
//! about 0.5 % above Hertz at ν = 0.3, Y/E' ≈ 0.006, and up to 2.6 % at ν = 0.2 (tested). The fits were made for a/R ≤ 1; at very
//! large ω* (≈ 3000 at Y/E' = 0.005) a/R passes 1 — [`JacksonGreenLaw::contact_radius_ratio`]
//! lets callers report it.

use crate::friction::error::{require_positive, FrictionError};

/// The Jackson–Green break between the Hertz and the elastic–plastic branch, ω* = 1.9.
pub const JG_ELASTIC_LIMIT: f64 = 1.9;

/// Jackson–Green critical factor C = 1.295 exp(0.736 ν).
pub fn jg_critical_factor(poisson_ratio: f64) -> f64 {
    1.295 * (0.736 * poisson_ratio).exp()
}

/// The Jackson–Green laws for one material pair, as ratios to the critical values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JacksonGreenLaw {
    /// Y/E' (yield strength over composite modulus).
    pub yield_over_modulus: f64,
    /// C = 1.295 exp(0.736 ν).
    pub critical_factor: f64,
    /// Area exponent B = 0.14 exp(23 Y/E').
    pub area_exponent: f64,
    /// ω_c/R = (π C Y/(2E'))².
    pub critical_interference_over_radius: f64,
}

impl JacksonGreenLaw {
    /// The law for yield strength Y (Pa), composite modulus E' (Pa) and the softer body's ν.
    /// Requires 0 < Y < E' and −1 < ν < 0.5.
    pub fn new(
        yield_strength: f64,
        composite_modulus: f64,
        poisson_ratio: f64,
    ) -> Result<Self, FrictionError> {
        let y = require_positive("yield_strength", yield_strength)?;
        let e = require_positive("composite_modulus", composite_modulus)?;
        if y >= e {
            return Err(FrictionError::InvalidParameter {
                name: "yield_strength",
                value: y,
                expected: "a yield strength below the composite modulus",
            });
        }
        if !(poisson_ratio.is_finite() && poisson_ratio > -1.0 && poisson_ratio < 0.5) {
            return Err(FrictionError::InvalidParameter {
                name: "poisson_ratio",
                value: poisson_ratio,
                expected: "a Poisson ratio in (-1, 0.5)",
            });
        }
        let c = jg_critical_factor(poisson_ratio);
        let ratio = std::f64::consts::PI * c * y / (2.0 * e);
        Ok(Self {
            yield_over_modulus: y / e,
            critical_factor: c,
            area_exponent: 0.14 * (23.0 * y / e).exp(),
            critical_interference_over_radius: ratio * ratio,
        })
    }

    /// a/R at ω* (0 for ω* ≤ 0).
    pub fn contact_radius_ratio(&self, w: f64) -> f64 {
        if w <= 0.0 {
            return 0.0;
        }
        let hertz = (w * self.critical_interference_over_radius).sqrt();
        if w <= JG_ELASTIC_LIMIT {
            hertz
        } else {
            hertz * (w / JG_ELASTIC_LIMIT).powf(0.5 * self.area_exponent)
        }
    }

    /// Geometric hardness over yield strength, H_G/Y = 2.84 [1 − exp(−0.82 (a/R)^{−0.7})], at ω*.
    pub fn hardness_ratio(&self, w: f64) -> f64 {
        let a_over_r = self.contact_radius_ratio(w);
        if a_over_r <= 0.0 {
            return 2.84;
        }
        2.84 * (1.0 - (-0.82 * a_over_r.powf(-0.7)).exp())
    }

    /// P/P_c at ω* (0 for ω* ≤ 0).
    pub fn load_ratio(&self, w: f64) -> f64 {
        if w <= 0.0 {
            0.0
        } else if w <= JG_ELASTIC_LIMIT {
            w.powf(1.5)
        } else {
            let elastic = (-0.25 * w.powf(5.0 / 12.0)).exp() * w.powf(1.5);
            let plastic = 4.0 * self.hardness_ratio(w) / self.critical_factor
                * (1.0 - (-w.powf(5.0 / 9.0) / 25.0).exp())
                * w;
            elastic + plastic
        }
    }

    /// A/A_c at ω* (0 for ω* ≤ 0).
    pub fn area_ratio(&self, w: f64) -> f64 {
        if w <= 0.0 {
            0.0
        } else if w <= JG_ELASTIC_LIMIT {
            w
        } else {
            w * (w / JG_ELASTIC_LIMIT).powf(self.area_exponent)
        }
    }

    /// Critical interference ω_c (m) of a sphere of radius R (m).
    pub fn critical_interference(&self, radius: f64) -> f64 {
        self.critical_interference_over_radius * radius
    }

    /// Critical load P_c (N) of a sphere of radius R (m) with composite modulus E' (Pa):
    /// P_c = (4/3)(R/E')² (CπY/2)³ = (4/3) E' R² (ω_c/R)^{3/2}.
    pub fn critical_load(&self, radius: f64, composite_modulus: f64) -> f64 {
        4.0 / 3.0
            * composite_modulus
            * radius
            * radius
            * self.critical_interference_over_radius.powf(1.5)
    }
}
