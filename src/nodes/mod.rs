//! The tribology node kinds: the glue between the study engine and the numerics.
//!
//! Each kind has a spec (what a study file says, with `${param}` references), a task (resolved SI
//! parameters, a version, a compute function) and a table. This is the only module that knows
//! both the engine and the numerics.

mod contact;
pub(crate) mod contact_view;
mod friction;
mod known_columns;
mod material_spec;
mod surface;
pub(crate) mod surface_view;
pub mod validity;

use std::sync::Arc;

use serde::Deserialize;

use crate::engine::node::{NodeSpec, NodeTask, UpstreamRef};
use crate::engine::study::{ResolveContext, SpecError};

/// Peak bytes per grid point that each worker thread adds to a node that transforms or reduces a
/// grid in parallel (the contact solver and the displacements of its load steps, a measured
/// surface's preprocessing and statistics): its FFT scratch and partial sums; an upper bound
/// (figures: docs/robustness.md, "Memory").
const THREAD_BYTES_PER_POINT: u64 = 8;

/// [`THREAD_BYTES_PER_POINT`] for each thread of the current worker pool, bytes per grid point.
fn thread_scratch_bytes_per_point() -> u64 {
    THREAD_BYTES_PER_POINT.saturating_mul(rayon::current_num_threads().max(1) as u64)
}

pub use contact::{final_step_metrics, ContactSpec, ContactTask, CONTACT_KIND_VERSION};
pub use contact_view::{ContactView, StepPressure};
pub use friction::{
    beyond_fit_field, coefficient_fields, friction_models_markdown, share, FrictionSpec,
    FrictionTask, DEFAULT_ADHESION_ENERGY, DEFAULT_EQUILIBRIUM_DISTANCE, FRICTION_KIND_VERSION,
};
pub use known_columns::{is_known_column, is_prose_column, list_column, ListItems};
pub use material_spec::{MaterialMapping, MaterialSpec};
pub use surface::{
    apply_height_unit, apply_lateral_calibration, height_unit_rule, scale_checks, surface_artifact,
    AnisotropySpec, FileSpec, HeightUnitSource, LateralCalibration, SurfaceSpec, SurfaceTask,
    SyntheticSpec, SURFACE_KIND_VERSION,
};

/// A node of a study: `name: {<kind>: {...}}`.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum TribologyNode {
    /// Stage 1: a synthetic or measured rough surface.
    Surface(SurfaceSpec),
    /// Stage 2: elastic–perfectly-plastic contact of one or two surfaces.
    Contact(ContactSpec),
    /// Stage 3: static friction coefficient (Kogut–Etsion, CEB, full stick or junction shear;
    /// statistical, per summit or per contact spot).
    Friction(FrictionSpec),
}

impl NodeSpec for TribologyNode {
    fn all_tables() -> &'static [&'static str] {
        &[surface::TABLE, contact::TABLE, friction::TABLE]
    }

    fn kind(&self) -> &'static str {
        match self {
            TribologyNode::Surface(_) => surface::KIND,
            TribologyNode::Contact(_) => contact::KIND,
            TribologyNode::Friction(_) => friction::KIND,
        }
    }

    fn table(&self) -> &'static str {
        match self {
            TribologyNode::Surface(_) => surface::TABLE,
            TribologyNode::Contact(_) => contact::TABLE,
            TribologyNode::Friction(_) => friction::TABLE,
        }
    }

    fn upstream(&self) -> Vec<UpstreamRef<'_>> {
        match self {
            TribologyNode::Surface(_) => Vec::new(),
            TribologyNode::Contact(c) => c.upstream(),
            TribologyNode::Friction(f) => f.upstream(),
        }
    }

    fn instantiate(&self, ctx: &ResolveContext<'_>) -> Result<Arc<dyn NodeTask>, SpecError> {
        match self {
            TribologyNode::Surface(spec) => Ok(Arc::new(spec.instantiate(ctx)?)),
            TribologyNode::Contact(spec) => Ok(Arc::new(spec.instantiate(ctx)?)),
            TribologyNode::Friction(spec) => Ok(Arc::new(spec.instantiate(ctx)?)),
        }
    }
}

/// The JSON Schema of study files, pretty-printed (committed as `schemas/study.schema.json`).
pub fn study_schema_json() -> String {
    let schema = schemars::schema_for!(crate::engine::study::StudyFile<TribologyNode>);
    let mut text = serde_json::to_string_pretty(&schema).unwrap_or_default();
    text.push('\n');
    text
}
