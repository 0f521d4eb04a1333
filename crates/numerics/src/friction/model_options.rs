//! Options of the friction models beyond the physical inputs, shared by the statistical and
//! per-summit methods and the model dispatch (`model_laws`).

use super::asperity_laws::{AdhesionBeyondFits, StaticFrictionForm};
use super::error::FrictionError;
use super::full_stick::{FullStickLaw, StickFrictionLaw};
use super::material::Material;

/// Model options beyond the physical inputs.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ModelOptions {
    /// Form of the KE Q_max polynomial (literal by default).
    pub static_friction_form: StaticFrictionForm,
    /// Contacting adhesion beyond x = 110 (hold the x = 110 value by default).
    pub adhesion_beyond_fits: AdhesionBeyondFits,
    /// Inputs of the full-stick model (ignored by the others).
    pub full_stick: FullStickOptions,
}

/// Inputs of the full-stick model beyond the [`Material`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FullStickOptions {
    /// Yield strength Y of the softer body (Pa); `None`: Tabor's Y = H/2.8
    /// ([`Material::tabor_yield_strength`]).
    pub yield_strength: Option<f64>,
    /// μ(P*) of a sticking asperity.
    pub friction_law: StickFrictionLaw,
}

impl FullStickOptions {
    /// The full-stick laws for `material` with these options.
    pub fn law(&self, material: &Material) -> Result<FullStickLaw, FrictionError> {
        FullStickLaw::new(
            self.yield_strength
                .unwrap_or_else(|| material.tabor_yield_strength()),
            material.composite_modulus,
            material.poisson_ratio,
            self.friction_law,
        )
    }
}
