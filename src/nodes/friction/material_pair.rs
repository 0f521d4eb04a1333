//! The material pair of a friction node: the friction [`Material`] of the softer body against
//! the composite modulus, both bodies' elastic constants and the softer body's strengths.
//!
//! Material rule: the composite modulus is 1/E = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂ (a rigid counter-body
//! when `upper_material` is omitted); H and ν are those of the softer body (the lower hardness; the
//! lower body against a rigid one), which must have a hardness.

use crate::engine::study::{ResolveContext, SpecError};
use crate::friction::Material;
use crate::materials::half_space_compliance;

use super::spec_fields::spec_error;
use super::FrictionSpec;

/// Young's modulus (Pa) and Poisson's ratio of one body.
type Body = (f64, f64);

/// The resolved material pair: the friction [`Material`], both bodies' elastic constants and the
/// softer body's strengths.
pub(super) struct MaterialPair {
    pub material: Material,
    pub lower: Body,
    pub upper: Option<Body>,
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
    let mut total = half_space_compliance(lower.youngs_modulus, lower.poisson_ratio);
    let mut softer = (
        lower.hardness,
        lower.poisson_ratio,
        "lower_material",
        &lower,
    );
    if let Some(u) = &upper {
        total += half_space_compliance(u.youngs_modulus, u.poisson_ratio);
        if let Some(hu) = u.hardness {
            if lower.hardness.is_none_or(|hl| hu < hl) {
                softer = (Some(hu), u.poisson_ratio, "upper_material", u);
            }
        }
    }
    let strengths = (softer.3.yield_strength, softer.3.shear_strength);
    let Some(hardness) = softer.0 else {
        return Err(spec_error(
            spec.lower_material.location(),
            softer.2,
            "the softer body needs a hardness: use a built-in material (e.g. `s235jr`) or add `hardness` (e.g. `{youngs_modulus: 210 GPa, poisson_ratio: 0.3, hardness: 2 GPa}`)",
        ));
    };
    let material = Material::new(1.0 / total, hardness, softer.1)
        .map_err(|e| spec_error(spec.lower_material.location(), softer.2, e.to_string()))?;
    let yield_strength = strengths
        .0
        .unwrap_or_else(|| material.tabor_yield_strength());
    Ok(MaterialPair {
        material,
        lower: (lower.youngs_modulus, lower.poisson_ratio),
        upper: upper.map(|u| (u.youngs_modulus, u.poisson_ratio)),
        yield_strength,
        shear_strength: strengths.1.unwrap_or(yield_strength / 3f64.sqrt()),
    })
}
