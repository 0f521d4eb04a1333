//! `ploughing`: Bowden–Tabor friction of a contact spot in two parts, the adhesion part of
//! junction shear Q_a,i = τ_s A_i (τ_s = c·k, as `junction_shear`) and a deformation part from
//! the spot's geometry along the sliding direction ([`deformation`]): the
//! groove of the spot's own cap (default), a cone of its attack slope or a sphere of its radius,
//! each added (Bowden–Tabor's split), or the junction tilted by its plane, composed. Per spot
//! only; textbook laws without fitted constants (docs/friction-models.md, "Deformation part").
//!
//! A spot without the geometry its deformation law needs, or outside that law's range (a > R,
//! a locked junction), keeps its adhesion part and is counted beyond the law's range.

use std::f64::consts::TAU;
use std::sync::Arc;

pub mod closed_forms;
pub mod deformation;
pub mod spot_slope;

use super::asperity::AsperityLaws;
use super::junction_shear::{JunctionShear, INTERFACE_FACTOR};
use super::law::{FrictionLaw, LawDescriptor, LawInputs, Method, ModelBasis};
use super::parameters::{
    NumberRange, ParameterKind, ParameterSpec, ParameterValue, ReportedValue, Unit,
};
use super::spot::{SlidingDirection, SpotFriction, SpotLoad, SpotSlope};
use crate::friction::error::FrictionError;
use deformation::{DeformationLaw, DeformationSpot};

/// The registry entry.
pub(super) const LAW: LawDescriptor = LawDescriptor {
    name: "ploughing",
    summary: "Bowden–Tabor: junction shear τ_s·A_i plus the deformation (ploughing) part of \
              each contact spot along the sliding direction",
    basis: ModelBasis::TextbookLaw,
    methods: &[Method::PerSpot],
    parameters: &[DEFORMATION, INTERFACE_FACTOR, SLIDING_DIRECTION],
    build,
};

const DEFORMATION: ParameterSpec = ParameterSpec {
    name: "deformation",
    column: "deformation_law",
    description: "the deformation part: `groove` (the cross-section of the spot's own cap along \
                  the sliding direction over half its area), `cone` ((2/π) tan α of its attack \
                  slope), `sphere` (the sphere at a/R), each added to the adhesion part, or \
                  `tilted_junction` (tan(φ + θ) of its plane's tilt θ, μ_a = tan φ)",
    kind: ParameterKind::Choice {
        options: &["groove", "cone", "sphere", "tilted_junction"],
        default: "groove",
    },
};

/// The sliding direction: the angle ψ in the surface plane from +x towards +y, the parameter of
/// every direction-dependent law.
pub const SLIDING_DIRECTION: ParameterSpec = ParameterSpec {
    name: "sliding_direction",
    column: "sliding_direction",
    description: "angle ψ of the sliding direction from +x towards +y (default 0: along +x; \
                  write it with its unit, e.g. `90 deg`)",
    kind: ParameterKind::Number {
        default: 0.0,
        range: DIRECTION_RANGE,
        unit: Unit::Angle,
    },
};

/// ψ ∈ [−2π, 2π].
const DIRECTION_RANGE: NumberRange = NumberRange {
    min: -TAU,
    min_inclusive: true,
    max: TAU,
    max_inclusive: true,
};

/// Junction shear and a deformation law along one sliding direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ploughing {
    adhesion: JunctionShear,
    deformation: DeformationLaw,
    deformation_name: &'static str,
    direction: SlidingDirection,
}

fn build(inputs: &LawInputs) -> Result<Box<dyn FrictionLaw>, FrictionError> {
    let c = inputs.parameters.number(INTERFACE_FACTOR.name)?;
    let name = inputs.parameters.choice(DEFORMATION.name)?;
    let deformation = DeformationLaw::named(name).ok_or(FrictionError::InvalidParameter {
        name: DEFORMATION.name,
        value: f64::NAN,
        expected: "groove, cone, sphere or tilted_junction",
    })?;
    let angle = inputs.parameters.number(SLIDING_DIRECTION.name)?;
    if !DIRECTION_RANGE.contains(angle) {
        return Err(FrictionError::InvalidParameter {
            name: SLIDING_DIRECTION.name,
            value: angle,
            expected: "an angle in [-2π, 2π] rad",
        });
    }
    Ok(Box::new(Ploughing {
        adhesion: JunctionShear::new(c, inputs.shear_strength)?,
        deformation,
        deformation_name: name,
        direction: SlidingDirection::new(angle)?,
    }))
}

impl FrictionLaw for Ploughing {
    fn descriptor(&self) -> &'static LawDescriptor {
        &LAW
    }

    fn asperity_laws(self: Arc<Self>) -> Option<Arc<dyn AsperityLaws>> {
        None
    }

    /// Without the spot's geometry: the adhesion part alone, beyond the law's range.
    fn spot_friction(&self, spot: &SpotLoad) -> Option<SpotFriction> {
        self.adhesion.spot_friction(spot).map(|a| SpotFriction {
            beyond_fit: true,
            ..a
        })
    }

    fn reported_values(&self) -> Vec<ReportedValue> {
        let mut values = vec![ReportedValue {
            column: DEFORMATION.column,
            value: ParameterValue::Choice(self.deformation_name),
            unit: Unit::Dimensionless,
        }];
        values.extend(self.adhesion.reported_values());
        values.push(ReportedValue {
            column: SLIDING_DIRECTION.column,
            value: ParameterValue::Number(self.direction.angle()),
            unit: Unit::Angle,
        });
        values
    }

    fn sliding_direction(&self) -> Option<SlidingDirection> {
        Some(self.direction)
    }

    fn sloped_spot_friction(
        &self,
        spot: &SpotLoad,
        geometry: &SpotSlope,
    ) -> Option<(SpotFriction, f64)> {
        let adhesion = self.adhesion.spot_friction(spot)?;
        let input = DeformationSpot {
            load: spot.load,
            area: spot.area,
            radius: spot.radius,
            tilt: geometry.tilt,
            attack_slope: geometry.attack_slope,
            groove_ratio: geometry.groove_ratio,
            adhesion_friction: adhesion.friction_force,
        };
        Some(match self.deformation.spot_deformation(&input) {
            Ok(q) => (
                SpotFriction {
                    friction_force: adhesion.friction_force + q,
                    ..adhesion
                },
                q,
            ),
            Err(_) => (self.spot_friction(spot)?, 0.0),
        })
    }
}
