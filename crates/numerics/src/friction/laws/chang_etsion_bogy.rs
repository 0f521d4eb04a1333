//! `chang_etsion_bogy`: the CEB baseline — Hertz up to first yield, a volume-conserving plastic
//! cap above, and only elastic asperities carrying tangential load. No parameters.
//!
//! # Source and what was taken
//! Chang, Etsion & Bogy (1987/88): Hertz for x ≤ 1; above, a volume-conserving plastic cap
//! A = πRω(2 − ω_c/ω), P = K H A, i.e. A/A_c = 2x − 1, P/P_c = (3/2)(2x − 1). Only elastic
//! asperities (x ≤ 1) carry tangential load. CEB's own Q_max comes from a first-yield analysis
//! of the Hamilton stress field that no source available to the project restates; the baseline
//! uses the KE elastic fit 0.52 x^0.982 for x ≤ 1 and 0 above (so the baseline isolates the
//! effect of "only elastic asperities carry tangential load").

use super::asperity::{AsperityLaws, ELASTIC_LIMIT};
use super::interference::InterferenceLaw;
use super::kogut_etsion::{ke_static_friction_ratio, StaticFrictionForm};
use super::law::{FrictionLaw, LawDescriptor, LawInputs, Method, ModelBasis};
use super::parameters::ReportedValue;
use crate::friction::error::FrictionError;
use crate::friction::material::Material;

/// The registry entry.
pub(super) const LAW: LawDescriptor = LawDescriptor {
    name: "chang_etsion_bogy",
    summary: "Chang–Etsion–Bogy baseline: Hertz + volume-conserving plastic cap; only elastic \
              asperities carry tangential load",
    basis: ModelBasis::PublishedFits,
    methods: &[Method::Statistical, Method::PerSummit, Method::PerSpot],
    parameters: &[],
    mu_s_max: super::asperity::YIELD_INCEPTION_MU_S_MAX,
    validated_range: "the Chang–Etsion–Bogy tangential load ends at first yield, x = ω/ω_c = 1, \
                      beyond which an asperity carries none",
    build,
};

/// CEB P/P_c: x^1.5 (x ≤ 1), (3/2)(2x − 1) above.
pub fn ceb_load_ratio(x: f64) -> f64 {
    if x <= 0.0 {
        0.0
    } else if x <= ELASTIC_LIMIT {
        x.powf(1.5)
    } else {
        1.5 * (2.0 * x - 1.0)
    }
}

/// CEB A/A_c: x (x ≤ 1), 2x − 1 above.
pub fn ceb_area_ratio(x: f64) -> f64 {
    if x <= 0.0 {
        0.0
    } else if x <= ELASTIC_LIMIT {
        x
    } else {
        2.0 * x - 1.0
    }
}

/// CEB-baseline Q_max/P_c: the KE elastic fit 0.52 x^0.982 for x ≤ 1, 0 for plastic asperities.
pub fn ceb_static_friction_ratio(x: f64) -> f64 {
    if x <= 0.0 || x > ELASTIC_LIMIT {
        0.0
    } else {
        ke_static_friction_ratio(x, StaticFrictionForm::Literal)
    }
}

/// The CEB laws of one material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChangEtsionBogy {
    material: Material,
}

impl ChangEtsionBogy {
    /// The laws of `material`.
    pub fn new(material: Material) -> Self {
        Self { material }
    }
}

fn build(inputs: &LawInputs) -> Result<Box<dyn FrictionLaw>, FrictionError> {
    Ok(Box::new(ChangEtsionBogy::new(inputs.material)))
}

impl InterferenceLaw for ChangEtsionBogy {
    const DESCRIPTOR: &'static LawDescriptor = &LAW;

    fn material(&self) -> &Material {
        &self.material
    }

    fn parameter_values(&self) -> Vec<ReportedValue> {
        Vec::new()
    }
}

impl AsperityLaws for ChangEtsionBogy {
    fn load_ratio(&self, x: f64) -> f64 {
        ceb_load_ratio(x)
    }

    fn area_ratio(&self, x: f64) -> f64 {
        ceb_area_ratio(x)
    }

    fn friction_ratio(&self, x: f64) -> f64 {
        ceb_static_friction_ratio(x)
    }

    fn load_breaks(&self) -> Vec<f64> {
        vec![ELASTIC_LIMIT]
    }

    fn friction_breaks(&self) -> Vec<f64> {
        Vec::new()
    }

    /// Only elastic asperities (x ≤ 1) carry tangential load.
    fn friction_support(&self) -> f64 {
        ELASTIC_LIMIT
    }

    fn fit_limit(&self) -> f64 {
        ELASTIC_LIMIT
    }
}
