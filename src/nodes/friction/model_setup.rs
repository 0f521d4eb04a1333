//! Resolution of the model-specific parts of a `friction` spec: which model and method, the
//! full-stick inputs (μ(P*) parameters, yield strength, Poisson ratio range), the junction-shear
//! strength τ_s = c·k, and the checks of the methods that read a contact solution
//! (`per_summit`, `per_spot`).

use crate::engine::study::{ResolveContext, SourceLocation, SpecError};
use crate::friction::contact_spots::Connectivity;
use crate::friction::full_stick::stick_factors;
use crate::friction::{AsperityModel, FullStickOptions, StickFrictionLaw};
use crate::units::format_number;

use super::material_pair::MaterialPair;
use super::spec_fields::{positive, resolve_choice, spec_error};
use super::{FrictionMethod, FrictionModel, FrictionSpec, JunctionShear};
use crate::materials::half_space_compliance;
use crate::nodes::contact::ContactTask;
use crate::nodes::validity;

/// The model and the method of the node; junction shear defaults to (and needs) `per_spot`.
pub(super) fn model_and_method(
    spec: &FrictionSpec,
    ctx: &ResolveContext<'_>,
    location: SourceLocation,
) -> Result<(FrictionModel, FrictionMethod), SpecError> {
    let model = resolve_choice(
        ctx,
        &spec.model,
        "model",
        &[
            (
                "kogut_etsion",
                FrictionModel::Asperity(AsperityModel::KogutEtsion),
            ),
            (
                "chang_etsion_bogy",
                FrictionModel::Asperity(AsperityModel::ChangEtsionBogy),
            ),
            (
                "full_stick",
                FrictionModel::Asperity(AsperityModel::FullStick),
            ),
            ("junction_shear", FrictionModel::JunctionShear),
        ],
    )?
    .unwrap_or(FrictionModel::Asperity(AsperityModel::KogutEtsion));
    let method = match (model, spec.method) {
        (FrictionModel::JunctionShear, None | Some(FrictionMethod::PerSpot)) => {
            FrictionMethod::PerSpot
        }
        (FrictionModel::JunctionShear, Some(other)) => {
            return Err(spec_error(
                spec.model.as_ref().map_or(location, |m| m.location()),
                "method",
                format!(
                    "`{}` does not apply to `model: junction_shear`, which shears the true contact area of a contact solution: use `method: per_spot` (the default for this model) with a `contact` node",
                    other.name()
                ),
            ))
        }
        (_, method) => method.unwrap_or(FrictionMethod::Statistical),
    };
    Ok((model, method))
}

/// The full-stick options (yield strength, μ(P*) parameters) and the junction-shear interface,
/// each for the model that uses it.
pub(super) fn model_inputs(
    spec: &FrictionSpec,
    ctx: &ResolveContext<'_>,
    model: FrictionModel,
    pair: &MaterialPair,
) -> Result<(FullStickOptions, Option<JunctionShear>), SpecError> {
    let location = spec.lower_material.location();
    let unused = |field: &str, used_by: &str| {
        spec_error(
            location,
            field,
            format!(
                "is used by `model: {used_by}` only, not by `model: {}`; remove it",
                model.name()
            ),
        )
    };
    let is_full_stick = model == FrictionModel::Asperity(AsperityModel::FullStick);
    if spec.stick_law.is_some() && !is_full_stick {
        return Err(unused("stick_law", "full_stick"));
    }
    if spec.interface_factor.is_some() && model != FrictionModel::JunctionShear {
        return Err(unused("interface_factor", "junction_shear"));
    }
    let mut full_stick = FullStickOptions::default();
    if is_full_stick {
        full_stick = full_stick_options(spec, ctx, pair)?;
    }
    let junction_shear = if model == FrictionModel::JunctionShear {
        let c = match &spec.interface_factor {
            Some(p) => ctx.resolve_checked(p, "interface_factor", |c: &f64| {
                validity::cross::interface_factor(*c)
            })?,
            None => 1.0,
        };
        Some(JunctionShear {
            interface_factor: c,
            shear_strength: c * pair.shear_strength,
        })
    } else {
        None
    };
    Ok((full_stick, junction_shear))
}

fn full_stick_options(
    spec: &FrictionSpec,
    ctx: &ResolveContext<'_>,
    pair: &MaterialPair,
) -> Result<FullStickOptions, SpecError> {
    let nu = pair.material.poisson_ratio;
    stick_factors(nu).map_err(|e| {
        spec_error(
            spec.lower_material.location(),
            "lower_material",
            format!(
                "`model: full_stick` needs the softer body's Poisson ratio in [0.2, 0.5); it is {}: {e}",
                format_number(nu)
            ),
        )
    })?;
    let defaults = StickFrictionLaw::default();
    let (mut a, mut b) = (defaults.a, defaults.b);
    if let Some(law) = &spec.stick_law {
        if let Some(p) = &law.a {
            a = ctx.resolve_checked(p, "stick_law.a", |v: &f64| positive(*v, ""))?;
        }
        if let Some(p) = &law.b {
            b = ctx.resolve_checked(p, "stick_law.b", |v: &f64| {
                if *v > 0.0 && *v < 1.0 {
                    Ok(())
                } else {
                    Err(String::from("is out of range: must be in (0, 1)"))
                }
            })?;
        }
    }
    let friction_law = StickFrictionLaw::new(a, b)
        .map_err(|e| spec_error(spec.lower_material.location(), "stick_law", e.to_string()))?;
    Ok(FullStickOptions {
        yield_strength: Some(pair.yield_strength),
        friction_law,
    })
}

/// The checks of a method that reads a contact solution (`per_summit`, `per_spot`): no
/// surfaces, roughness or loads of its own, an upstream contact node with `fields: true` and the
/// same composite modulus, and a flow pressure within a factor of 10 of the friction laws' H
/// ([`validity::cross::flow_pressure_match`]). Returns the contact's input index, whether it was
/// periodic and the flag of a flow pressure that differs by more than 1 %.
pub(super) fn contact_solution(
    spec: &FrictionSpec,
    ctx: &ResolveContext<'_>,
    location: SourceLocation,
    contact: Option<usize>,
    pair: &MaterialPair,
    method: FrictionMethod,
) -> Result<(usize, bool, Option<String>), SpecError> {
    let not_here = |field: &str, what: &str| {
        Err(spec_error(
            location,
            field,
            format!(
                "is not used by `method: {}` ({what}); remove it",
                method.name()
            ),
        ))
    };
    if spec.lower.is_some() || spec.upper.is_some() {
        return not_here(
            "lower",
            "the topography is the composite topography the contact node solved",
        );
    }
    if spec.roughness.is_some() {
        return not_here(
            "roughness",
            "the roughness is the contact node's topography",
        );
    }
    if spec.nominal_pressures.is_some() || spec.loads.is_some() {
        return not_here(
            "nominal_pressures",
            "the load is the contact node's final nominal pressure",
        );
    }
    let (Some(index), Some(name)) = (contact, &spec.contact) else {
        return Err(spec_error(
            location,
            "contact",
            format!(
                "`method: {}` needs an upstream `contact` node (run with `fields: true`)",
                method.name()
            ),
        ));
    };
    let contact_task = ctx
        .upstream(index)
        .and_then(|t| t.as_any().downcast_ref::<ContactTask>())
        .ok_or_else(|| {
            spec_error(
                name.location,
                "contact",
                format!("node '{}' is not a contact node", name.value),
            )
        })?;
    if !contact_task.keeps_fields() {
        return Err(spec_error(
            name.location,
            "contact",
            format!(
                "`method: {}` needs the contact fields of contact node '{}': add `fields: true` to it",
                method.name(),
                name.value
            ),
        ));
    }
    check_same_modulus(spec, contact_task, &name.value, pair)?;
    let flag =
        validity::cross::flow_pressure_match(contact_task.flow_pressure(), pair.material.hardness)
            .map_err(|message| spec_error(name.location, "contact", message))?;
    Ok((index, contact_task.periodic(), flag))
}

/// The contact solution was computed with the contact's materials: the friction node's must
/// give the same composite modulus.
fn check_same_modulus(
    spec: &FrictionSpec,
    contact: &ContactTask,
    name: &str,
    pair: &MaterialPair,
) -> Result<(), SpecError> {
    let compliance =
        |body: Option<(f64, f64)>| body.map_or(0.0, |(e, nu)| half_space_compliance(e, nu));
    let ours = compliance(Some(pair.lower)) + compliance(pair.upper);
    let theirs = contact.compliance();
    if (ours - theirs).abs() > 1e-9 * theirs.abs() {
        return Err(spec_error(
            spec.lower_material.location(),
            "lower_material",
            format!(
                "the composite modulus {} Pa differs from that of contact node '{name}' ({} Pa): use the contact node's materials",
                format_number(1.0 / ours),
                format_number(1.0 / theirs)
            ),
        ));
    }
    Ok(())
}

/// `spot_connectivity` (4 or 8, default 4) and `spots_table` of `method: per_spot`.
pub(super) fn spot_options(
    spec: &FrictionSpec,
    ctx: &ResolveContext<'_>,
) -> Result<(Connectivity, bool), SpecError> {
    let connectivity = match &spec.spot_connectivity {
        Some(p) => match ctx.resolve_checked(p, "spot_connectivity", |n: &i64| {
            if *n == 4 || *n == 8 {
                Ok(())
            } else {
                Err(String::from("is not one of: 4, 8"))
            }
        })? {
            8 => Connectivity::Eight,
            _ => Connectivity::Four,
        },
        None => Connectivity::Four,
    };
    let spots_table = match &spec.spots_table {
        Some(p) => ctx.resolve(p, "spots_table")?,
        None => false,
    };
    Ok((connectivity, spots_table))
}
