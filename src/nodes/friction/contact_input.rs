//! The inputs of the methods that read a contact solution (`per_summit`, `per_spot`): the
//! upstream contact node and its checks, and the spot options.

use crate::engine::study::{ResolveContext, SourceLocation, SpecError};
use crate::friction::contact_spots::Connectivity;
use crate::friction::Method;
use crate::units::format_number;

use super::material_pair::MaterialPair;
use super::spec_fields::spec_error;
use super::{ContactInput, FrictionSpec};
use crate::nodes::contact::ContactTask;
use crate::nodes::validity;

/// The checks of a method that reads a contact solution (`per_summit`, `per_spot`): no
/// surfaces, roughness or loads of its own, an upstream contact node with `fields: true` and the
/// same composite modulus, and a flow pressure within a factor of 10 of the friction laws' H
/// ([`validity::cross::flow_pressure_match`]). Returns the contact (its input index and task)
/// and the flag of a flow pressure that differs by more than 1 %.
pub(super) fn contact_solution(
    spec: &FrictionSpec,
    ctx: &ResolveContext<'_>,
    location: SourceLocation,
    contact: Option<usize>,
    pair: &MaterialPair,
    method: Method,
) -> Result<(ContactInput, Option<String>), SpecError> {
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
    let flag = validity::cross::flow_pressure_match(
        contact_task.material().flow_pressure(),
        pair.material.hardness,
    )
    .map_err(|message| spec_error(name.location, "contact", message))?;
    let contact = ContactInput {
        index,
        task: std::sync::Arc::new(contact_task.clone()),
    };
    Ok((contact, flag))
}

/// The contact solution was computed with the contact's materials: the friction node's must
/// give the same composite modulus.
fn check_same_modulus(
    spec: &FrictionSpec,
    contact: &ContactTask,
    name: &str,
    pair: &MaterialPair,
) -> Result<(), SpecError> {
    let ours = pair.bodies.composite().compliance;
    let theirs = contact.material().pair().composite().compliance;
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
