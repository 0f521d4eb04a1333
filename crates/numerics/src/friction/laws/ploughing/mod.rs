//! `ploughing`: Bowden–Tabor friction of a contact spot in two parts, the adhesion part of
//! junction shear Q_a,i = τ_s A_i (τ_s = c·k, as `junction_shear`) and the deformation part
//! Q_d,i = μ_d P_i of the harder body's asperity ploughing the softer body on the loaded front
//! of the spot ([`front`], [`deformation`]; the bodies' convention in
//! [`crate::friction::bodies`]): the groove of the front's own cap (default), a cone of its attack
//! slope or a sphere of its radius along the motion, added to the adhesion part (Bowden–Tabor's
//! split). At equal hardness both bodies plough, each with half of the deformation part. Per spot
//! only; textbook laws without fitted constants (docs/friction-models.md, "Deformation part").
//!
//! **Regime.** The additive laws describe the ploughing mode only; past a degree of penetration
//! D_p (groove depth over contact radius) the wear-mode maps of Hokkirigawa & Kato (1988) show
//! wedge forming and cutting instead. The bound is a parameter (`penetration_limit`, default
//! 0.1, recalled, not confirmed from an accessible source); a spot beyond it keeps its
//! deformation part and is counted outside the regime.
//!
//! A spot without the geometry its deformation law needs (no ring ahead of the tip: a spot
//! covering a periodic grid) keeps its adhesion part and is counted beyond the law's range.

pub mod baseline;
pub mod closed_forms;
pub mod deformation;
pub mod front;

use std::f64::consts::TAU;
use std::sync::Arc;

use super::asperity::AsperityLaws;
use super::junction_shear::{JunctionShear, INTERFACE_FACTOR};
use super::law::{FrictionLaw, LawDescriptor, LawInputs, Method, ModelBasis, DRY_METAL_MU_S_MAX};
use super::parameters::{
    NumberRange, ParameterKind, ParameterSpec, ParameterValue, ReportedValue, Unit,
};
use super::spot::{SlidingDirection, SpotFriction, SpotGeometry, SpotLoad};
use crate::friction::error::FrictionError;
use deformation::DeformationLaw;

/// The registry entry.
pub(super) const LAW: LawDescriptor = LawDescriptor {
    name: "ploughing",
    summary: "Bowden–Tabor: junction shear τ_s·A_i plus the deformation part of the harder \
              body's asperity ploughing on the loaded front of each contact spot",
    basis: ModelBasis::TextbookLaw,
    methods: &[Method::PerSpot],
    parameters: &[
        DEFORMATION,
        INTERFACE_FACTOR,
        SLIDING_DIRECTION,
        PENETRATION_LIMIT,
    ],
    mu_s_max: DRY_METAL_MU_S_MAX,
    validated_range: "the ploughing law needs each spot's loaded front on the ploughing body, \
                      without which a spot gets its junction shear alone",
    build,
};

const DEFORMATION: ParameterSpec = ParameterSpec {
    name: "deformation",
    column: "deformation_law",
    description: "the deformation part: `groove` (the silhouette of the ploughing asperity's cap \
                  along its motion over the loaded front's area), `cone` ((2/π) tan α of the \
                  front's attack slope) or `sphere` (the sphere through the front's tip and \
                  boundary at a_f/R_f), each added to the adhesion part",
    kind: ParameterKind::Choice {
        options: &["groove", "cone", "sphere"],
        default: "groove",
    },
};

/// The sliding direction: the angle ψ in the surface plane from +x towards +y along which the
/// upper body slides over the lower, the parameter of every direction-dependent law.
pub const SLIDING_DIRECTION: ParameterSpec = ParameterSpec {
    name: "sliding_direction",
    column: "sliding_direction",
    description: "angle ψ along which the upper body slides over the lower, from +x towards +y \
                  (default 0: along +x; write it with its unit, e.g. `90 deg`)",
    kind: ParameterKind::Number {
        default: 0.0,
        range: DIRECTION_RANGE,
        unit: Unit::Angle,
    },
};

/// The largest degree of penetration D_p of the ploughing regime.
const PENETRATION_LIMIT: ParameterSpec = ParameterSpec {
    name: "penetration_limit",
    column: "penetration_limit",
    description: "largest degree of penetration D_p (groove depth over contact radius) of the \
                  ploughing mode; beyond it Hokkirigawa & Kato's wear-mode maps show wedge \
                  forming and cutting, where the additive laws do not hold (default 0.1, \
                  recalled from that work, not confirmed: parameterised)",
    kind: ParameterKind::Number {
        default: 0.1,
        range: NumberRange::POSITIVE,
        unit: Unit::Dimensionless,
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
    penetration_limit: f64,
}

fn build(inputs: &LawInputs) -> Result<Box<dyn FrictionLaw>, FrictionError> {
    let c = inputs.parameters.number(INTERFACE_FACTOR.name)?;
    let name = inputs.parameters.choice(DEFORMATION.name)?;
    let deformation = DeformationLaw::named(name).ok_or(FrictionError::InvalidParameter {
        name: DEFORMATION.name,
        value: f64::NAN,
        expected: "groove, cone or sphere",
    })?;
    let angle = inputs.parameters.number(SLIDING_DIRECTION.name)?;
    if !DIRECTION_RANGE.contains(angle) {
        return Err(FrictionError::InvalidParameter {
            name: SLIDING_DIRECTION.name,
            value: angle,
            expected: "an angle in [-2π, 2π] rad",
        });
    }
    let penetration_limit = inputs.parameters.number(PENETRATION_LIMIT.name)?;
    if !(penetration_limit.is_finite() && penetration_limit > 0.0) {
        return Err(FrictionError::InvalidParameter {
            name: PENETRATION_LIMIT.name,
            value: penetration_limit,
            expected: "a degree of penetration > 0",
        });
    }
    Ok(Box::new(Ploughing {
        adhesion: JunctionShear::new(c, inputs.shear_strength)?,
        deformation,
        deformation_name: name,
        direction: SlidingDirection::new(angle)?,
        penetration_limit,
    }))
}

impl Ploughing {
    /// μ_d of the spot from its ploughing bodies' fronts, the largest D_p among them, and
    /// whether every front had what the law needs.
    fn deformation_coefficient(&self, geometry: &SpotGeometry) -> (f64, f64, bool) {
        let (mut mu, mut penetration, mut complete) = (0.0, 0.0f64, true);
        for (share, front) in geometry.ploughers() {
            let Some(front) = front else {
                complete = false;
                continue;
            };
            penetration = penetration.max(front.penetration);
            match self.deformation.coefficient(front) {
                Some(m) => mu += share * m,
                None => complete = false,
            }
        }
        (mu, penetration, complete)
    }
}

impl FrictionLaw for Ploughing {
    fn descriptor(&self) -> &'static LawDescriptor {
        &LAW
    }

    fn asperity_laws(self: Arc<Self>) -> Option<Arc<dyn AsperityLaws>> {
        None
    }

    /// The adhesion part plus the deformation part of the spot's ploughing bodies; without
    /// `geometry` the adhesion part alone, beyond the law's range.
    fn spot_friction(
        &self,
        spot: &SpotLoad,
        geometry: Option<&SpotGeometry>,
    ) -> Option<SpotFriction> {
        let adhesion = self.adhesion.spot_friction(spot, None)?;
        let Some(geometry) = geometry else {
            return Some(SpotFriction {
                beyond_fit: true,
                ..adhesion
            });
        };
        let (mu, penetration, complete) = self.deformation_coefficient(geometry);
        let deformation_force = mu * spot.load;
        Some(SpotFriction {
            friction_force: adhesion.friction_force + deformation_force,
            deformation_force,
            beyond_fit: !complete,
            radius_based: self.deformation.radius_based(),
            penetration: Some(penetration),
            outside_regime: penetration > self.penetration_limit,
            ..adhesion
        })
    }

    fn reported_values(&self) -> Vec<ReportedValue> {
        let mut values = vec![ReportedValue {
            column: DEFORMATION.column,
            value: ParameterValue::Choice(self.deformation_name),
            unit: Unit::Dimensionless,
        }];
        values.extend(self.adhesion.reported_values());
        values.extend([
            ReportedValue {
                column: SLIDING_DIRECTION.column,
                value: ParameterValue::Number(self.direction.angle()),
                unit: Unit::Angle,
            },
            ReportedValue {
                column: PENETRATION_LIMIT.column,
                value: ParameterValue::Number(self.penetration_limit),
                unit: Unit::Dimensionless,
            },
        ]);
        values
    }

    fn sliding_direction(&self) -> Option<SlidingDirection> {
        Some(self.direction)
    }
}
