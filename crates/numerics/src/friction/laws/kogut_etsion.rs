//! `kogut_etsion`: the Kogut–Etsion 2002 load and area fits with the KE 2004 static friction
//! force (equations, sources and their status: [`crate::friction::asperity_laws`]). Its one
//! parameter is the form of the KE 2004 Q_max polynomial on 1 < x ≤ 6.

use std::sync::Arc;

use super::parameters::{ParameterKind, ParameterSpec, ParameterValue, Unit};
use super::{AsperityLaws, FrictionError, FrictionLaw, LawDescriptor, LawInputs, Method};
use super::{ModelBasis, ReportedValue};
use crate::friction::asperity_laws::{
    ke_area_ratio, ke_load_ratio, ke_static_friction_ratio, StaticFrictionForm, ELASTIC_LIMIT,
    KE_BREAKPOINTS, KE_SECOND_FIT_START, KE_STATIC_FRICTION_ZERO,
};
use crate::friction::material::Material;
use crate::friction::per_spot::{interference_spot_friction, SpotFriction, SpotLoad};

/// The registry entry.
pub(super) const LAW: LawDescriptor = LawDescriptor {
    name: "kogut_etsion",
    summary: "Kogut–Etsion 2002 load/area fits with the KE 2004 static friction force",
    basis: ModelBasis::PublishedFits,
    methods: &[Method::Statistical, Method::PerSummit, Method::PerSpot],
    parameters: &[FORM],
    build,
};

const FORM: ParameterSpec = ParameterSpec {
    name: "static_friction_form",
    column: "static_friction_form",
    description: "KE 2004 Q_max polynomial on 1 < x ≤ 6: `literal` (as published, negative for \
                  4.29 < x ≤ 6) or `clipped` (max(0, ·))",
    kind: ParameterKind::Choice {
        options: &["literal", "clipped"],
        default: "literal",
    },
};

/// The Kogut–Etsion laws of one material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KogutEtsion {
    material: Material,
    form: StaticFrictionForm,
}

impl KogutEtsion {
    /// The laws of `material` with the Q_max polynomial in `form`.
    pub fn new(material: Material, form: StaticFrictionForm) -> Self {
        Self { material, form }
    }
}

fn build(inputs: &LawInputs) -> Result<Box<dyn FrictionLaw>, FrictionError> {
    let form = match inputs.parameters.choice(FORM.name)? {
        "literal" => StaticFrictionForm::Literal,
        "clipped" => StaticFrictionForm::Clipped,
        _ => {
            return Err(FrictionError::InvalidParameter {
                name: FORM.name,
                value: f64::NAN,
                expected: "`literal` or `clipped`",
            })
        }
    };
    Ok(Box::new(KogutEtsion::new(inputs.material, form)))
}

impl FrictionLaw for KogutEtsion {
    fn descriptor(&self) -> &'static LawDescriptor {
        &LAW
    }

    fn asperity_laws(self: Arc<Self>) -> Option<Arc<dyn AsperityLaws>> {
        Some(self)
    }

    fn spot_friction(&self, spot: &SpotLoad) -> Option<SpotFriction> {
        interference_spot_friction(self, &self.material, spot)
    }

    fn reported_values(&self) -> Vec<ReportedValue> {
        let form = match self.form {
            StaticFrictionForm::Literal => "literal",
            StaticFrictionForm::Clipped => "clipped",
        };
        vec![ReportedValue {
            column: FORM.column,
            value: ParameterValue::Choice(form),
            unit: Unit::Dimensionless,
        }]
    }
}

impl AsperityLaws for KogutEtsion {
    fn load_ratio(&self, x: f64) -> f64 {
        ke_load_ratio(x, self.material.hardness_factor())
    }

    fn area_ratio(&self, x: f64) -> f64 {
        ke_area_ratio(x)
    }

    fn friction_ratio(&self, x: f64) -> f64 {
        ke_static_friction_ratio(x, self.form)
    }

    fn load_breaks(&self) -> Vec<f64> {
        KE_BREAKPOINTS.to_vec()
    }

    fn friction_breaks(&self) -> Vec<f64> {
        vec![ELASTIC_LIMIT, KE_STATIC_FRICTION_ZERO]
    }

    /// KE 2004 Q_max is fitted up to x = 6 and zero beyond.
    fn friction_support(&self) -> f64 {
        KE_SECOND_FIT_START
    }

    /// Beyond x = 6 the yield-inception criterion gives no tangential load.
    fn fit_limit(&self) -> f64 {
        KE_SECOND_FIT_START
    }
}
