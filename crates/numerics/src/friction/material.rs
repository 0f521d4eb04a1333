//! Material of a contact pair and the critical (first-yield) values of a spherical asperity.
//!
//! Composite modulus E of the pair ([`MaterialPair::composite`]); hardness H and Poisson ratio ν
//! of the softer body ([`MaterialPair::softer`]); hardness factor K = 0.454 + 0.41 ν (Chang,
//! Etsion & Bogy, J. Tribol. 109 (1987) 257: the peak Hertz pressure at first yield is K·H).
//! Critical values of a sphere of radius R on a flat (Kogut & Etsion, J. Appl. Mech. 69 (2002)
//! 657):
//!
//! ```text
//! ω_c = (π K H / (2E))² R      P_c = (2/3) π K H R ω_c      A_c = π R ω_c
//! ```
//!
//! Plasticity index (KE form): ψ = (2E/(π K H)) √(σ_s/R), evaluated with the **summit-height**
//! standard deviation σ_s (as KE 2003/2004 do), so that ω_c/σ_s = 1/ψ².

use super::error::{require_positive, FrictionError};
pub use crate::materials::TABOR_FACTOR;
use crate::materials::{bounds, MaterialPair};

/// Elastic and plastic properties of a contact pair (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Composite modulus E (Pa).
    pub composite_modulus: f64,
    /// Hardness H of the softer body (Pa).
    pub hardness: f64,
    /// Poisson ratio ν of the softer body.
    pub poisson_ratio: f64,
}

/// First-yield values of one spherical asperity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CriticalValues {
    /// Critical interference ω_c (m).
    pub interference: f64,
    /// Critical load P_c (N).
    pub load: f64,
    /// Critical contact area A_c (m²).
    pub area: f64,
}

impl Material {
    /// Material from the composite modulus E (Pa), the softer body's hardness H (Pa) and Poisson
    /// ratio ν. Requires E > 0, 0 < H < E and ν within the material bounds, [0, 0.5]
    /// ([`crate::materials::bounds`]).
    pub fn new(
        composite_modulus: f64,
        hardness: f64,
        poisson_ratio: f64,
    ) -> Result<Self, FrictionError> {
        let composite_modulus = require_positive("composite_modulus", composite_modulus)?;
        let hardness = require_positive("hardness", hardness)?;
        if hardness >= composite_modulus {
            return Err(FrictionError::InvalidParameter {
                name: "hardness",
                value: hardness,
                expected: "a hardness below the composite modulus",
            });
        }
        let poisson_ratio =
            bounds::poisson_ratio(poisson_ratio).map_err(|_| FrictionError::InvalidParameter {
                name: "poisson_ratio",
                value: poisson_ratio,
                expected: "a Poisson ratio in [0, 0.5] (the material bounds)",
            })?;
        Ok(Self {
            composite_modulus,
            hardness,
            poisson_ratio,
        })
    }

    /// Material of a pair: its composite modulus ([`MaterialPair::composite`]) and the softer
    /// body's ([`MaterialPair::softer`]) hardness and Poisson ratio; the softer body must have a
    /// hardness.
    pub fn from_pair(pair: &MaterialPair) -> Result<Self, FrictionError> {
        let (_, softer) = pair.softer();
        let hardness = softer.hardness().ok_or(FrictionError::InvalidParameter {
            name: "hardness",
            value: f64::NAN,
            expected: "the hardness of the softer body (none given)",
        })?;
        Self::new(pair.composite().modulus, hardness, softer.poisson_ratio())
    }

    /// Yield strength by Tabor's rule, Y = H/2.8 ([`TABOR_FACTOR`]).
    pub fn tabor_yield_strength(&self) -> f64 {
        self.hardness / TABOR_FACTOR
    }

    /// Hardness factor K = 0.454 + 0.41 ν.
    pub fn hardness_factor(&self) -> f64 {
        0.454 + 0.41 * self.poisson_ratio
    }

    /// Critical values ω_c, P_c, A_c of a sphere of radius `radius` (m).
    pub fn critical_values(&self, radius: f64) -> CriticalValues {
        let k = self.hardness_factor();
        let ratio = std::f64::consts::PI * k * self.hardness / (2.0 * self.composite_modulus);
        let interference = ratio * ratio * radius;
        CriticalValues {
            interference,
            load: 2.0 / 3.0 * std::f64::consts::PI * k * self.hardness * radius * interference,
            area: std::f64::consts::PI * radius * interference,
        }
    }

    /// Plasticity index ψ = (2E/(π K H)) √(σ_s/R), with σ_s the summit-height std (m) and R the
    /// mean summit radius (m).
    pub fn plasticity_index(&self, sigma_s: f64, radius: f64) -> f64 {
        let k = self.hardness_factor();
        2.0 * self.composite_modulus / (std::f64::consts::PI * k * self.hardness)
            * (sigma_s / radius).sqrt()
    }
}

/// Adhesion parameters: adhesion energy Δγ (N/m, ≥ 0) and Lennard-Jones equilibrium distance ε (m, > 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdhesionParameters {
    /// Adhesion energy Δγ (N/m); 0 switches adhesion off.
    pub energy: f64,
    /// Lennard-Jones equilibrium distance ε (m), e.g. 0.158e-9 for iron.
    pub equilibrium_distance: f64,
}

impl AdhesionParameters {
    /// Validated adhesion parameters (Δγ ≥ 0, ε > 0).
    pub fn new(energy: f64, equilibrium_distance: f64) -> Result<Self, FrictionError> {
        Ok(Self {
            energy: super::error::require_non_negative("adhesion_energy", energy)?,
            equilibrium_distance: require_positive("equilibrium_distance", equilibrium_distance)?,
        })
    }
}
