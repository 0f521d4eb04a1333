//! The interference-driven laws by name for the tests (the node layer reaches them through the
//! registry; here they are built directly so a test can say which it means).

use std::sync::Arc;

use asperity_numerics::friction::{
    AdhesionBeyondFits, AdhesionParameters, AsperityLaws, ChangEtsionBogy, FrictionError,
    FullStick, FullStickOptions, KogutEtsion, Material, StaticFrictionForm, StatisticalModel,
    SummitStatistics,
};

/// An interference-driven law.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Model {
    KogutEtsion,
    ChangEtsionBogy,
    FullStick,
}

/// The choices a test varies beyond the physical inputs.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Options {
    pub static_friction_form: StaticFrictionForm,
    pub adhesion_beyond_fits: AdhesionBeyondFits,
}

/// The laws of `model` for `material` (full stick with Tabor's yield strength and the default
/// μ(P*)).
pub fn laws(
    model: Model,
    material: &Material,
    form: StaticFrictionForm,
) -> Result<Arc<dyn AsperityLaws>, FrictionError> {
    Ok(match model {
        Model::KogutEtsion => Arc::new(KogutEtsion::new(*material, form)),
        Model::ChangEtsionBogy => Arc::new(ChangEtsionBogy::new(*material)),
        Model::FullStick => Arc::new(FullStick::new(material, FullStickOptions::default())?),
    })
}

/// A statistical model of `model` with `options`.
pub fn statistical(
    model: Model,
    summits: SummitStatistics,
    material: Material,
    adhesion: AdhesionParameters,
    nominal_area: f64,
    options: Options,
) -> Result<StatisticalModel, FrictionError> {
    StatisticalModel::new(
        laws(model, &material, options.static_friction_form)?,
        summits,
        material,
        adhesion,
        nominal_area,
        options.adhesion_beyond_fits,
    )
}
