//! `junction_shear`: Bowden–Tabor junction shear, Q_i = τ_s A_i per contact spot with
//! τ_s = c·k, k the softer body's shear strength and c the interface factor (1: a clean metal
//! junction; smaller for contaminated or lubricated ones; a junction stronger than the body would
//! shear inside the body, hence c ≤ 1). It needs the true contact area of a contact solution,
//! so its only method is `per_spot`; no radius, no fitted range.

use std::sync::Arc;

use super::asperity::AsperityLaws;
use super::law::{FrictionLaw, LawDescriptor, LawInputs, Method, ModelBasis};
use super::parameters::{
    NumberRange, ParameterKind, ParameterSpec, ParameterValue, ReportedValue, Unit,
};
use super::spot::{SpotFriction, SpotGeometry, SpotLoad};
use crate::friction::error::{require_non_negative, FrictionError};

/// The registry entry.
pub(super) const LAW: LawDescriptor = LawDescriptor {
    name: "junction_shear",
    summary: "Bowden–Tabor junction shear τ_s·A_true on a contact solution, τ_s = c·k",
    basis: ModelBasis::TextbookLaw,
    methods: &[Method::PerSpot],
    parameters: &[INTERFACE_FACTOR],
    mu_s_max: super::law::DRY_METAL_MU_S_MAX,
    validated_range: "junction shear has no fitted range: every spot is inside it",
    build,
};

pub(super) const INTERFACE_FACTOR: ParameterSpec = ParameterSpec {
    name: "interface_factor",
    column: "interface_factor",
    description: "c in [0, 1] of τ_s = c·k (default 1, a clean metal junction; a junction \
                  stronger than the softer body would shear inside the body)",
    kind: ParameterKind::Number {
        default: 1.0,
        range: INTERFACE_FACTOR_RANGE,
        unit: Unit::Dimensionless,
    },
};

/// c ∈ [0, 1].
const INTERFACE_FACTOR_RANGE: NumberRange = NumberRange {
    min: 0.0,
    min_inclusive: true,
    max: 1.0,
    max_inclusive: true,
};

/// Junction shear with interface factor c and strength τ_s = c·k.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JunctionShear {
    interface_factor: f64,
    shear_strength: f64,
}

impl JunctionShear {
    /// τ_s = c·k for interface factor c ∈ [0, 1] and shear strength k ≥ 0 (Pa).
    pub fn new(interface_factor: f64, shear_strength: f64) -> Result<Self, FrictionError> {
        if !INTERFACE_FACTOR_RANGE.contains(interface_factor) {
            return Err(FrictionError::InvalidParameter {
                name: INTERFACE_FACTOR.name,
                value: interface_factor,
                expected: "an interface factor in [0, 1]",
            });
        }
        let k = require_non_negative("shear_strength", shear_strength)?;
        Ok(Self {
            interface_factor,
            shear_strength: interface_factor * k,
        })
    }

    /// τ_s (Pa).
    pub fn shear_strength(&self) -> f64 {
        self.shear_strength
    }
}

fn build(inputs: &LawInputs) -> Result<Box<dyn FrictionLaw>, FrictionError> {
    let c = inputs.parameters.number(INTERFACE_FACTOR.name)?;
    Ok(Box::new(JunctionShear::new(c, inputs.shear_strength)?))
}

impl FrictionLaw for JunctionShear {
    fn descriptor(&self) -> &'static LawDescriptor {
        &LAW
    }

    fn asperity_laws(self: Arc<Self>) -> Option<Arc<dyn AsperityLaws>> {
        None
    }

    fn spot_friction(&self, spot: &SpotLoad, _: Option<&SpotGeometry>) -> Option<SpotFriction> {
        Some(SpotFriction {
            friction_force: self.shear_strength * spot.area,
            ..SpotFriction::default()
        })
    }

    fn reported_values(&self) -> Vec<ReportedValue> {
        vec![
            ReportedValue {
                column: INTERFACE_FACTOR.column,
                value: ParameterValue::Number(self.interface_factor),
                unit: Unit::Dimensionless,
            },
            ReportedValue {
                column: "shear_strength",
                value: ParameterValue::Number(self.shear_strength),
                unit: Unit::Pressure,
            },
        ]
    }
}
