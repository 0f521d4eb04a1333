//! Resolution of a `friction` spec into a [`FrictionTask`]: upstream checks, materials
//! (`material_pair`), adhesion, roughness, loads.

use crate::engine::study::{Located, ResolveContext, SourceLocation, SpecError};
use crate::friction::laws::{find_law, LawInputs};
use crate::friction::{AdhesionParameters, BodyHardness, Method, SummitStatistics};

use super::contact_input;
use super::material_pair::{resolve_material, MaterialPair};
use super::model_spec::resolve_law;
use super::spec_fields::{positive, spec_error};
use crate::nodes::validity;
use crate::units::format_number;
use crate::vocabulary::roles;

use super::{
    FrictionSpec, FrictionTask, Loads, MethodSetup, Roughness, DEFAULT_ADHESION_ENERGY,
    DEFAULT_EQUILIBRIUM_DISTANCE,
};

fn resolve_loads(
    spec: &FrictionSpec,
    ctx: &ResolveContext<'_>,
    contact: Option<usize>,
    location: SourceLocation,
) -> Result<Loads, SpecError> {
    fn ascending(
        ctx: &ResolveContext<'_>,
        list: &[crate::engine::study::Param<
            crate::units::Quantity<impl crate::units::DimensionMarker>,
        >],
        field: &str,
        unit: &str,
    ) -> Result<Vec<f64>, SpecError> {
        if list.is_empty() {
            return Err(spec_error(
                SourceLocation::default(),
                field,
                "needs at least one value",
            ));
        }
        let mut values: Vec<f64> = Vec::with_capacity(list.len());
        for (i, p) in list.iter().enumerate() {
            let v = ctx.resolve(p, &format!("{field}[{i}]"))?.si();
            let previous = values.last().copied().unwrap_or(0.0);
            if !(v > previous && v.is_finite()) {
                return Err(spec_error(
                    p.location(),
                    &format!("{field}[{i}]"),
                    format!(
                        "{} {unit} is out of range: values must ascend and be > 0",
                        format_number(v)
                    ),
                ));
            }
            values.push(v);
        }
        Ok(values)
    }
    match (&spec.nominal_pressures, &spec.loads, contact) {
        (Some(_), Some(_), _) => Err(spec_error(
            location,
            "loads",
            "give either `nominal_pressures` or `loads`, not both",
        )),
        (Some(p), None, _) => {
            Ok(Loads::Pressures(ascending(ctx, p, "nominal_pressures", "Pa")?))
        }
        (None, Some(f), _) => {
            Ok(Loads::Forces(ascending(ctx, f, "loads", "N")?))
        }
        (None, None, Some(c)) => Ok(Loads::FromContact(c)),
        (None, None, None) => Err(spec_error(
            location,
            "nominal_pressures",
            "a statistical friction node needs `nominal_pressures`, `loads` or an upstream `contact` (whose final nominal pressure is used)",
        )),
    }
}

/// Checks the upstream kinds: `lower`/`upper` surfaces, `contact` a contact node.
fn check_upstream(spec: &FrictionSpec, ctx: &ResolveContext<'_>) -> Result<(), SpecError> {
    let expected = [
        (roles::LOWER, &spec.lower, crate::nodes::surface::KIND),
        (roles::UPPER, &spec.upper, crate::nodes::surface::KIND),
        (roles::CONTACT, &spec.contact, crate::nodes::contact::KIND),
    ];
    let mut index = 0;
    for (role, name, kind) in expected {
        let Some(name) = name else { continue };
        if let Some(up) = ctx.upstream(index) {
            if up.kind() != kind {
                return Err(spec_error(
                    name.location,
                    role,
                    format!(
                        "'{}' is a {} node; `{role}` needs a {kind} node",
                        name.value,
                        up.kind()
                    ),
                ));
            }
        }
        index += 1;
    }
    Ok(())
}

fn location_of(spec: &FrictionSpec) -> SourceLocation {
    spec.lower_material.location()
}

pub(super) fn instantiate(
    spec: &FrictionSpec,
    ctx: &ResolveContext<'_>,
) -> Result<FrictionTask, SpecError> {
    check_upstream(spec, ctx)?;
    refuse_moved_fields(spec)?;
    let location = location_of(spec);
    let pair = resolve_material(spec, ctx)?;
    let inputs = LawInputs {
        material: pair.material,
        yield_strength: pair.yield_strength,
        shear_strength: pair.shear_strength,
        parameters: crate::friction::laws::default_law().default_parameters(),
    };
    let (law, method) = resolve_law(
        spec.model.as_ref(),
        spec.method.as_ref(),
        ctx,
        inputs,
        location,
    )?;
    check_method_fields(spec, method, location)?;
    let adhesion = adhesion(spec, ctx, location)?;
    let nominal_area = match &spec.nominal_area {
        Some(p) => Some(
            ctx.resolve_checked(p, "nominal_area", |q| positive(q.si(), "m^2"))?
                .si(),
        ),
        None => None,
    };
    let (setup, input_flag) = method_setup(spec, ctx, method, &pair, nominal_area)?;
    Ok(FrictionTask {
        law,
        material: pair.material,
        input_flags: input_flag.into_iter().collect(),
        input_roles: spec.upstream().iter().map(|r| r.role).collect(),
        adhesion,
        memory_estimate: super::memory::estimate(
            &setup,
            crate::nodes::thread_scratch_bytes_per_point(),
        ),
        setup,
    })
}

/// Fields that moved into a law's parameter block, and the law whose block now holds them.
const MOVED_FIELDS: [(&str, &str); 3] = [
    ("static_friction_form", "kogut_etsion"),
    ("stick_law", "full_stick"),
    ("interface_factor", "junction_shear"),
];

/// A moved field is refused with its new place, written out from the registry's defaults
/// (`model: {full_stick: {a: 0.27, b: 0.35}}`).
fn refuse_moved_fields(spec: &FrictionSpec) -> Result<(), SpecError> {
    let given = [
        &spec.static_friction_form,
        &spec.stick_law,
        &spec.interface_factor,
    ];
    for ((field, law), value) in MOVED_FIELDS.iter().zip(given) {
        let Some(Located { location, .. }) = value else {
            continue;
        };
        let block = find_law(law).map_or_else(String::new, |law| {
            law.parameters
                .iter()
                .map(|p| format!("{}: {}", p.name, super::model_spec::default_text(p)))
                .collect::<Vec<_>>()
                .join(", ")
        });
        return Err(spec_error(
            *location,
            field,
            format!(
                "has moved into the model's parameter block: write `model: {{{law}: {{{block}}}}}` (the defaults shown) and remove `{field}`"
            ),
        ));
    }
    Ok(())
}

/// The adhesion energy Δγ and equilibrium distance ε (defaults: see the constants).
fn adhesion(
    spec: &FrictionSpec,
    ctx: &ResolveContext<'_>,
    location: SourceLocation,
) -> Result<AdhesionParameters, SpecError> {
    let energy = match &spec.adhesion_energy {
        Some(p) => ctx
            .resolve_checked(p, "adhesion_energy", |q| {
                if q.si() >= 0.0 {
                    Ok(())
                } else {
                    Err(String::from("is out of range: must be >= 0 N/m"))
                }
            })?
            .si(),
        None => DEFAULT_ADHESION_ENERGY,
    };
    let epsilon = match &spec.equilibrium_distance {
        Some(p) => ctx
            .resolve_checked(p, "equilibrium_distance", |q| positive(q.si(), "m"))?
            .si(),
        None => DEFAULT_EQUILIBRIUM_DISTANCE,
    };
    AdhesionParameters::new(energy, epsilon)
        .map_err(|e| spec_error(location, "adhesion_energy", e.to_string()))
}

/// What the method needs: roughness and loads (statistical), or the contact solution and its
/// options (per summit, per spot), with the flag of a contact whose flow pressure differs from
/// the friction laws' H.
fn method_setup(
    spec: &FrictionSpec,
    ctx: &ResolveContext<'_>,
    method: Method,
    pair: &MaterialPair,
    nominal_area: Option<f64>,
) -> Result<(MethodSetup, Option<String>), SpecError> {
    let location = location_of(spec);
    let surfaces = usize::from(spec.lower.is_some()) + usize::from(spec.upper.is_some());
    let contact = spec.contact.as_ref().map(|_| surfaces);
    let mut flag = None;
    let setup = match method {
        Method::Statistical => {
            let roughness = roughness(spec, ctx, nominal_area, location)?;
            let loads = resolve_loads(spec, ctx, contact, location)?;
            check_pressures_within_flow(spec, &loads, pair)?;
            MethodSetup::Statistical {
                roughness,
                nominal_area,
                loads,
            }
        }
        Method::PerSummit => {
            let (contact, mismatch) =
                contact_input::contact_solution(spec, ctx, location, contact, pair, method)?;
            let periodic = contact.task.periodic();
            let summits_table = match &spec.summits_table {
                Some(p) => ctx.resolve(p, "summits_table")?,
                None => false,
            };
            flag = mismatch;
            MethodSetup::PerSummit {
                contact,
                nominal_area,
                periodic,
                summits_table,
            }
        }
        Method::PerSpot => {
            let (contact, mismatch) =
                contact_input::contact_solution(spec, ctx, location, contact, pair, method)?;
            let periodic = contact.task.periodic();
            let (connectivity, spots_table) = contact_input::spot_options(spec, ctx)?;
            flag = mismatch;
            MethodSetup::PerSpot {
                contact,
                section: super::per_spot::Section {
                    nominal_area,
                    periodic,
                    connectivity,
                    spots_table,
                    hardness: BodyHardness::of(&pair.bodies),
                },
            }
        }
    };
    Ok((setup, flag))
}

/// Statistical `nominal_pressures`: each at most the flow pressure H of the softer body
/// ([`validity::cross::pressure_within_flow`]), an error at the value.
fn check_pressures_within_flow(
    spec: &FrictionSpec,
    loads: &Loads,
    pair: &MaterialPair,
) -> Result<(), SpecError> {
    let (Loads::Pressures(values), Some(list)) = (loads, &spec.nominal_pressures) else {
        return Ok(());
    };
    for (i, (&p, param)) in values.iter().zip(list).enumerate() {
        validity::cross::pressure_within_flow(p, pair.material.hardness).map_err(|message| {
            spec_error(
                param.location(),
                &format!("nominal_pressures[{i}]"),
                message,
            )
        })?;
    }
    Ok(())
}

/// The roughness of the statistical method: explicit `{sigma, radius, density}` (which needs a
/// nominal area) or the upstream surfaces, never both.
fn roughness(
    spec: &FrictionSpec,
    ctx: &ResolveContext<'_>,
    nominal_area: Option<f64>,
    location: SourceLocation,
) -> Result<Roughness, SpecError> {
    match (&spec.roughness, &spec.lower, &spec.upper) {
        (Some(_), Some(n), _) | (Some(_), None, Some(n)) => Err(spec_error(
            n.location,
            "roughness",
            "give either explicit `roughness` or upstream surfaces (`lower`, `upper`), not both",
        )),
        (Some(r), None, None) => {
            let sigma = ctx
                .resolve_checked(&r.sigma, "roughness.sigma", |q| positive(q.si(), "m"))?
                .si();
            let radius = ctx
                .resolve_checked(&r.radius, "roughness.radius", |q| positive(q.si(), "m"))?
                .si();
            let density = ctx.resolve_checked(&r.density, "roughness.density", |v| {
                positive(*v, "per m^2")
            })?;
            let summits = SummitStatistics::from_explicit(sigma, radius, density)
                .map_err(|e| spec_error(r.sigma.location(), "roughness", e.to_string()))?;
            if nominal_area.is_none() {
                return Err(spec_error(
                    r.sigma.location(),
                    "nominal_area",
                    "is required with explicit `roughness` (there is no upstream surface to take it from)",
                ));
            }
            Ok(Roughness::Explicit(summits))
        }
        (None, Some(_), upper) => Ok(Roughness::Surfaces {
            lower: 0,
            upper: upper.as_ref().map(|_| 1),
        }),
        (None, None, Some(n)) => Err(spec_error(
            n.location,
            "upper",
            "is given without `lower` (one surface goes in `lower`)",
        )),
        (None, None, None) => Err(spec_error(
            location,
            "roughness",
            "a statistical friction node needs upstream surfaces (`lower`, optional `upper`) or explicit `roughness: {sigma, radius, density}`",
        )),
    }
}

/// Fields that only one method uses are refused with the others.
fn check_method_fields(
    spec: &FrictionSpec,
    method: Method,
    location: SourceLocation,
) -> Result<(), SpecError> {
    let only = [
        (
            "summits_table",
            spec.summits_table.is_some(),
            Method::PerSummit,
        ),
        ("spots_table", spec.spots_table.is_some(), Method::PerSpot),
        (
            "spot_connectivity",
            spec.spot_connectivity.is_some(),
            Method::PerSpot,
        ),
    ];
    for (field, given, owner) in only {
        if given && method != owner {
            return Err(spec_error(
                location,
                field,
                format!("is only available with `method: {}`", owner.name()),
            ));
        }
    }
    Ok(())
}
