//! The material pair of a friction node: the [`MaterialPair`] of `lower_material` against
//! `upper_material` (a rigid counter-body when it is omitted), the friction [`Material`] built
//! from it ([`Material::from_pair`]: the pair's composite modulus, H and ν of the softer body,
//! which must have a hardness) and the softer body's strengths (given, or by the default rules
//! of [`crate::materials::BodyMaterial`]).

use crate::engine::study::{ResolveContext, SpecError};
use crate::friction::Material;
use crate::materials;

use super::spec_fields::spec_error;
use super::FrictionSpec;

/// The resolved materials of a friction node.
pub(super) struct MaterialPair {
    /// What the asperity laws see: E*, and H and ν of the softer body.
    pub material: Material,
    /// Both bodies.
    pub bodies: materials::MaterialPair,
    /// Yield strength Y of the softer body (Pa): given, or Tabor's H/2.8.
    pub yield_strength: f64,
    /// Shear strength k of the softer body (Pa): given, or von Mises Y/√3.
    pub shear_strength: f64,
}

/// Resolves the spec's `lower_material` and `upper_material` into the pair.
pub(super) fn resolve_material(
    spec: &FrictionSpec,
    ctx: &ResolveContext<'_>,
) -> Result<MaterialPair, SpecError> {
    let lower = spec.lower_material.resolve(ctx, "lower_material")?;
    let upper = match &spec.upper_material {
        Some(m) => Some(m.resolve(ctx, "upper_material")?),
        None => None,
    };
    let bodies = materials::MaterialPair::new(lower, upper);
    let (side, softer) = bodies.softer();
    let error = |message: String| {
        spec_error(
            spec.lower_material.location(),
            side.material_field(),
            message,
        )
    };
    let strengths = (softer.hardness())
        .and(softer.yield_strength())
        .zip(softer.shear_strength());
    let Some((yield_strength, shear_strength)) = strengths else {
        return Err(error(String::from(
            "the softer body needs a hardness: use a built-in material (e.g. `s235jr`) or add `hardness` (e.g. `{youngs_modulus: 210 GPa, poisson_ratio: 0.3, hardness: 2 GPa}`)",
        )));
    };
    let material = Material::from_pair(&bodies).map_err(|e| error(e.to_string()))?;
    Ok(MaterialPair {
        material,
        bodies,
        yield_strength,
        shear_strength,
    })
}
