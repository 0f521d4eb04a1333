//! The key fields of a friction node, derived from the resolved task itself: the method and
//! model, the material the model sees, the model's own inputs, adhesion, and the method's
//! roughness, loads and table options, in SI. Every field of the task is named here (a new field
//! fails to compile until it is placed in the key or explicitly left out).

use crate::engine::value::Field;
use crate::friction::laws::{ParameterValue, ReportedValue, Unit};
use crate::friction::{Connectivity, FrictionLaw, Material, SummitStatistics};
use crate::units::Dimension;
use crate::vocabulary::metrics as names;

use super::per_spot::Section;
use super::{FrictionTask, Loads, MethodSetup, Roughness};

impl FrictionTask {
    /// The resolved parameters that enter the key and the `friction` table row.
    pub(super) fn key_fields(&self) -> Vec<Field> {
        let Self {
            law,
            material,
            adhesion,
            setup,
            // Derived from the upstream contact's parameters (in its key) and the hardness.
            input_flags: _,
            // Derived from which upstream nodes the spec names (in the key as roles).
            input_roles: _,
            // Derived from the grid: not a parameter.
            memory_estimate: _,
        } = self;
        // Room for the fields of every setup.
        let mut key = Vec::with_capacity(24);
        key.extend([
            Field::text(names::METHOD, setup.method().name()),
            Field::text(names::MODEL, law.descriptor().name),
        ]);
        key.extend(material_fields(material));
        key.extend(law.reported_values().iter().map(reported_field));
        key.extend([
            Field::float(
                names::ADHESION_ENERGY,
                adhesion.energy,
                Dimension::SurfaceEnergy,
            ),
            Field::float(
                names::EQUILIBRIUM_DISTANCE,
                adhesion.equilibrium_distance,
                Dimension::Length,
            ),
        ]);
        key.extend(method_fields(setup));
        key.extend(ploughing_field(law.as_ref(), setup));
        key
    }
}

/// Which body ploughs, for a per-spot law that reads the bodies' surfaces (one with a sliding
/// direction): the order of the bodies' hardness decides it and which body flows.
fn ploughing_field(law: &dyn FrictionLaw, setup: &MethodSetup) -> Option<Field> {
    let MethodSetup::PerSpot { section, .. } = setup else {
        return None;
    };
    law.sliding_direction()?;
    Some(Field::text(
        names::PLOUGHING_BODY,
        section.hardness.ploughing().name(),
    ))
}

/// A law's parameter or derived value as a key field.
fn reported_field(value: &ReportedValue) -> Field {
    let dimension = match value.unit {
        Unit::Dimensionless => Dimension::Dimensionless,
        Unit::Pressure => Dimension::Pressure,
        Unit::Angle => Dimension::Angle,
    };
    match value.value {
        ParameterValue::Number(v) => Field::float(value.column, v, dimension),
        ParameterValue::Choice(c) => Field::text(value.column, c),
    }
}

fn material_fields(material: &Material) -> [Field; 3] {
    let Material {
        composite_modulus,
        hardness,
        poisson_ratio,
    } = *material;
    [
        Field::float(
            names::COMPOSITE_MODULUS,
            composite_modulus,
            Dimension::Pressure,
        ),
        Field::float(names::HARDNESS, hardness, Dimension::Pressure),
        Field::float(
            names::POISSON_RATIO,
            poisson_ratio,
            Dimension::Dimensionless,
        ),
    ]
}

/// The nominal area (when given) and what the method reads: explicit roughness and loads, or
/// the table options of a contact-solution method. The upstream inputs' indices and whether the
/// contact was periodic come from the upstream nodes, whose keys are part of this key.
fn method_fields(setup: &MethodSetup) -> Vec<Field> {
    let nominal_area = match setup {
        MethodSetup::Statistical { nominal_area, .. }
        | MethodSetup::PerSummit { nominal_area, .. }
        | MethodSetup::PerSpot {
            section: Section { nominal_area, .. },
            ..
        } => *nominal_area,
    };
    let mut fields: Vec<Field> = nominal_area
        .map(|a| Field::float(names::NOMINAL_AREA, a, Dimension::Area))
        .into_iter()
        .collect();
    match setup {
        MethodSetup::Statistical {
            roughness,
            nominal_area: _,
            loads,
        } => {
            if let Roughness::Explicit(summits) = roughness {
                fields.extend(explicit_roughness_fields(summits));
            }
            fields.extend(load_fields(loads));
        }
        MethodSetup::PerSummit {
            contact: _,
            nominal_area: _,
            periodic: _,
            summits_table,
        } => fields.push(Field::bool(names::SUMMITS_TABLE, *summits_table)),
        MethodSetup::PerSpot {
            contact: _,
            section:
                Section {
                    nominal_area: _,
                    periodic: _,
                    connectivity,
                    spots_table,
                    // In the key of a law that reads the bodies ([`ploughing_field`]).
                    hardness: _,
                },
        } => {
            let connectivity = match connectivity {
                Connectivity::Four => 4,
                Connectivity::Eight => 8,
            };
            fields.push(Field::int(names::SPOT_CONNECTIVITY, connectivity));
            fields.push(Field::bool(names::SPOTS_TABLE, *spots_table));
        }
    }
    fields
}

/// σ, R and η as given (the other summit statistics follow from them).
fn explicit_roughness_fields(summits: &SummitStatistics) -> [Field; 3] {
    [
        Field::float(names::SIGMA, summits.sigma, Dimension::Length),
        Field::float(names::SUMMIT_RADIUS, summits.radius, Dimension::Length),
        Field::float(
            names::SUMMIT_DENSITY,
            summits.density,
            Dimension::InverseArea,
        ),
    ]
}

fn load_fields(loads: &Loads) -> Option<Field> {
    match loads {
        Loads::Pressures(p) => Some(Field::floats(
            names::NOMINAL_PRESSURES,
            p.clone(),
            Dimension::Pressure,
        )),
        Loads::Forces(f) => Some(Field::floats(names::LOADS, f.clone(), Dimension::Force)),
        Loads::FromContact(_) => None,
    }
}
