//! `chang_etsion_bogy`: the CEB baseline — Hertz up to first yield, a volume-conserving plastic
//! cap above, and only elastic asperities carrying tangential load (equations, sources and their
//! status: [`crate::friction::asperity_laws`]). No parameters.

use std::sync::Arc;

use super::{AsperityLaws, FrictionError, FrictionLaw, LawDescriptor, LawInputs, Method};
use super::{ModelBasis, ReportedValue};
use crate::friction::asperity_laws::{
    ceb_area_ratio, ceb_load_ratio, ceb_static_friction_ratio, ELASTIC_LIMIT,
};
use crate::friction::material::Material;
use crate::friction::per_spot::{interference_spot_friction, SpotFriction, SpotLoad};

/// The registry entry.
pub(super) const LAW: LawDescriptor = LawDescriptor {
    name: "chang_etsion_bogy",
    summary: "Chang–Etsion–Bogy baseline: Hertz + volume-conserving plastic cap; only elastic \
              asperities carry tangential load",
    basis: ModelBasis::PublishedFits,
    methods: &[Method::Statistical, Method::PerSummit, Method::PerSpot],
    parameters: &[],
    build,
};

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

impl FrictionLaw for ChangEtsionBogy {
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
