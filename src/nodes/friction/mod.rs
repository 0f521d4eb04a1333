//! The `friction` node kind: the static friction coefficient μ_s of a rough contact (stage 3).
//! Models: every law of the registry [`crate::friction::LAWS`] (`model_spec` reads `model:`
//! against it; `docs/friction-models.md`).
//!
//! * `method: statistical` — KE 2004, CEB or full stick on Greenwood–Williamson summit statistics
//!   (`friction::static_friction`): roughness from one or two upstream surface nodes (isotropic
//!   spectral moments, two surfaces combined by adding moments) or explicit
//!   `{sigma, radius, density}`; load as nominal pressures or forces, or the final nominal pressure
//!   of each load step of an upstream contact node.
//! * `method: per_summit` — the single-asperity laws applied to each summit of the composite
//!   topography an upstream contact node solved (`fields: true`), with each summit's interference
//!   from the contact's deformation there (`friction::per_summit_friction`); optional long table
//!   `friction_summits`.
//! * `method: per_spot` — the law per contact spot of that solution, on both bodies
//!   (`friction::per_spot_friction`, the one call the Python binding makes too); optional long
//!   table `friction_spots`.
//!
//! Every row says how far to trust it: `model_basis`, `load_share_beyond_fit`, the adhesion
//! share, the flags of its inputs (`trust`), a flag above the law's μ_s bound, and `mu_s` is
//! never negative (`mu_s_computed`, `mu_s_floored` keep what the model gave).
//!
//! Every method gives the friction at every load step (each load, or each step of the upstream
//! contact): long table `friction_curve` ([`steps`]), one row per step with every column of the
//! row; the row is the final step.
//!
//! Table `friction`, one row per node instance (see `docs/study-format.md`).

use serde::Deserialize;

use crate::engine::artifact::{Artifact, Table};
use crate::engine::node::{NodeError, NodeTask, UpstreamRef};
use crate::engine::study::{Param, ResolveContext, SpannedName, SpecError};
use crate::engine::value::{Field, Value};
use std::sync::Arc;

use crate::engine::study::Located;
use crate::friction::{AdhesionParameters, FrictionLaw, Material, Method, SummitStatistics};
use crate::units::{Area, Dimension, Force, Length, Pressure, Quantity, SurfaceEnergy};

use super::contact::ContactTask;
use super::contact_view::ContactView;
use super::material_spec::MaterialSpec;
use super::validity;
use model_spec::{MethodSpec, ModelSpec};
pub use models_doc::friction_models_markdown;

mod contact_input;
mod deformation_part;
mod key;
mod material_pair;
mod memory;
mod model_spec;
mod models_doc;
mod per_spot;
mod per_summit;
mod setup;
mod spec_fields;
mod statistical;
mod steps;
mod trust;

pub(crate) use crate::vocabulary::kinds::FRICTION as KIND;
use crate::vocabulary::tables::CURVE as TABLES_CURVE;
pub(crate) use crate::vocabulary::tables::FRICTION as TABLE;
use crate::vocabulary::{metrics as names, roles};

/// Implementation version of the `friction` kind; bump whenever its numerics change (4: keys
/// derived from the law registry; the values are those of version 3; 5: ploughing on the
/// harder body's deformed surface at each spot's loaded front, `tilted_junction` removed, merged
/// spots and the adhesion share reported, flags inherited from the inputs; 6: friction at
/// every load step, the `curve` table for every method with every column of the row and the
/// step's validity, per spot with `nominal_pressure`; the final step's values are those of 5;
/// 7: the local μ quantiles weighted by load and flagged above the law's μ bound, the
/// beyond-fit flag naming the row's law).
pub const FRICTION_KIND_VERSION: u32 = 7;

/// Default adhesion energy Δγ (N/m): "somewhat clean" metal surfaces, the value of the static
/// friction experiments on 17-4PH compared with the KE model (reference workflow; the range
/// quoted there is 0.01 N/m contaminated to 1 N/m very clean).
pub const DEFAULT_ADHESION_ENERGY: f64 = 0.5;

/// Default Lennard-Jones equilibrium distance ε (m): 0.158 nm, iron (KE 2003/2004).
pub const DEFAULT_EQUILIBRIUM_DISTANCE: f64 = 0.158e-9;

/// `friction: {...}`.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FrictionSpec {
    /// `statistical` (GW summit statistics), `per_summit` (summits of a contact node's
    /// composite topography with the contact's deformation) or `per_spot` (each contact spot of a
    /// contact node's solution with its exact load and area). Default: the model's first method
    /// (`statistical`; `per_spot` for `junction_shear`, its only method).
    #[serde(default)]
    pub method: Option<MethodSpec>,
    /// The friction law: a name (`kogut_etsion`, the default; `chang_etsion_bogy`, `full_stick`,
    /// `junction_shear`) or the name with its parameters, `{full_stick: {a: 0.3, b: 0.35}}`.
    #[serde(default)]
    pub model: Option<ModelSpec>,
    /// Statistical: upstream surface node of the lower body (roughness from its spectral moments).
    #[serde(default)]
    pub lower: Option<SpannedName>,
    /// Statistical: upstream surface node of the upper body (moments added to the lower's).
    #[serde(default)]
    pub upper: Option<SpannedName>,
    /// Upstream contact node: required by `per_summit`; for `statistical` its final nominal
    /// pressure is the default load.
    #[serde(default)]
    pub contact: Option<SpannedName>,
    /// Statistical: explicit summit statistics instead of upstream surfaces.
    #[serde(default)]
    pub roughness: Option<Box<RoughnessSpec>>,
    /// Material of the lower body (a built-in name, a name with overrides or explicit constants).
    pub lower_material: MaterialSpec,
    /// Material of the upper body; omitted: a rigid counter-body.
    #[serde(default)]
    pub upper_material: Option<Box<MaterialSpec>>,
    /// Adhesion energy Δγ (surface energy ≥ 0, e.g. `0.5 N/m`, the default; 0 switches adhesion off).
    #[serde(default)]
    pub adhesion_energy: Option<Param<Quantity<SurfaceEnergy>>>,
    /// Lennard-Jones equilibrium distance ε (length > 0; default 0.158 nm, iron).
    #[serde(default)]
    pub equilibrium_distance: Option<Param<Quantity<Length>>>,
    /// Nominal area A_n (area > 0). Statistical: default the upstream surface's area (required
    /// with explicit roughness). Per summit: forces are scaled from the section to this area.
    #[serde(default)]
    pub nominal_area: Option<Param<Quantity<Area>>>,
    /// Statistical: nominal pressures (ascending, > 0); F = p · A_n. Several: a μ(F) curve.
    #[serde(default)]
    pub nominal_pressures: Option<Vec<Param<Quantity<Pressure>>>>,
    /// Statistical: external normal loads (ascending, > 0), instead of `nominal_pressures`.
    #[serde(default)]
    pub loads: Option<Vec<Param<Quantity<Force>>>>,
    /// Per summit: also write the long table `friction_summits` (one row per summit).
    #[serde(default)]
    pub summits_table: Option<Param<bool>>,
    /// Per spot: grid neighbours that join contact points into one spot, 4 (edges, default) or
    /// 8 (edges and corners).
    #[serde(default)]
    pub spot_connectivity: Option<Param<i64>>,
    /// Per spot: also write the long table `friction_spots` (one row per contact spot).
    #[serde(default)]
    pub spots_table: Option<Param<bool>>,
    /// Moved into `model: {kogut_etsion: {static_friction_form: ...}}` (refused here).
    #[serde(default)]
    #[schemars(skip)]
    pub static_friction_form: Option<Located<serde::de::IgnoredAny>>,
    /// Moved into `model: {full_stick: {a: ..., b: ...}}` (refused here).
    #[serde(default)]
    #[schemars(skip)]
    pub stick_law: Option<Located<serde::de::IgnoredAny>>,
    /// Moved into `model: {junction_shear: {interface_factor: ...}}` (refused here).
    #[serde(default)]
    #[schemars(skip)]
    pub interface_factor: Option<Located<serde::de::IgnoredAny>>,
}

/// Explicit summit statistics of the equivalent rough surface.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RoughnessSpec {
    /// Standard deviation of surface heights σ (length > 0).
    pub sigma: Param<Quantity<Length>>,
    /// Mean summit radius of curvature R (length > 0).
    pub radius: Param<Quantity<Length>>,
    /// Summit areal density η in summits per square metre (> 0; e.g. 1e10 = 1e4 per mm²).
    pub density: Param<f64>,
}

impl FrictionSpec {
    pub(crate) fn upstream(&self) -> Vec<UpstreamRef<'_>> {
        let mut refs = Vec::new();
        for (role, node) in [
            (roles::LOWER, &self.lower),
            (roles::UPPER, &self.upper),
            (roles::CONTACT, &self.contact),
        ] {
            if let Some(node) = node {
                refs.push(UpstreamRef { role, node });
            }
        }
        refs
    }
}

/// Where the statistical roughness comes from.
#[derive(Debug, Clone)]
pub(crate) enum Roughness {
    /// Spectral moments of the upstream surface(s) at these input indices.
    Surfaces { lower: usize, upper: Option<usize> },
    /// Explicit summit statistics.
    Explicit(SummitStatistics),
}

/// The loads of a statistical node.
#[derive(Debug, Clone)]
pub(crate) enum Loads {
    /// Nominal pressures (Pa).
    Pressures(Vec<f64>),
    /// External loads (N).
    Forces(Vec<f64>),
    /// The final nominal pressure of the contact at this input index.
    FromContact(usize),
}

/// Method-specific resolved inputs.
#[derive(Debug, Clone)]
pub(crate) enum MethodSetup {
    Statistical {
        roughness: Roughness,
        nominal_area: Option<f64>,
        loads: Loads,
    },
    PerSummit {
        contact: ContactInput,
        nominal_area: Option<f64>,
        periodic: bool,
        summits_table: bool,
    },
    PerSpot {
        contact: ContactInput,
        section: per_spot::Section,
    },
}

/// The upstream contact a per-summit or per-spot node reads: its input index and its task,
/// which reads the contact's earlier load steps (`ContactTask::step_pressure`).
#[derive(Debug, Clone)]
pub(crate) struct ContactInput {
    pub index: usize,
    pub task: Arc<ContactTask>,
}

/// A resolved friction node.
#[derive(Debug, Clone)]
pub struct FrictionTask {
    /// The law, built for the material with its parameters.
    law: Arc<dyn FrictionLaw>,
    material: Material,
    /// Flags found when the node was resolved (a contact flow pressure that differs from H).
    input_flags: Vec<String>,
    /// The role of each input, in input order (their flags carry over to the row).
    input_roles: Vec<&'static str>,
    adhesion: AdhesionParameters,
    setup: MethodSetup,
    /// Peak memory in bytes, from the method and the contact's grid ([`memory::estimate`]).
    memory_estimate: u64,
}

/// `input` at `index`, or an error naming the role.
pub(crate) fn input<'a>(
    inputs: &[&'a Artifact],
    index: usize,
    role: &str,
) -> Result<&'a Artifact, NodeError> {
    inputs
        .get(index)
        .copied()
        .ok_or_else(|| NodeError::new(format!("no {role} input")))
}

impl FrictionSpec {
    pub(crate) fn instantiate(&self, ctx: &ResolveContext<'_>) -> Result<FrictionTask, SpecError> {
        setup::instantiate(self, ctx)
    }
}

impl NodeTask for FrictionTask {
    fn as_any(&self) -> &dyn std::any::Any {
        self
    }

    fn kind(&self) -> &'static str {
        KIND
    }

    fn version(&self) -> u32 {
        FRICTION_KIND_VERSION
    }

    fn table(&self) -> &'static str {
        TABLE
    }

    /// `curve` (`friction_curve`): one row per load step, every method ([`steps`]).
    fn step_table(&self) -> Option<&'static str> {
        Some(TABLES_CURVE)
    }

    fn params(&self) -> Vec<Field> {
        self.key_fields()
    }

    fn memory_estimate(&self) -> u64 {
        self.memory_estimate
    }

    /// Every load step's row (`steps`), then the `friction` row: the final step's, with the
    /// method's long tables of the final step and the `curve` table of every step.
    fn compute(&self, inputs: &[&Artifact]) -> Result<Artifact, NodeError> {
        let law = self.law.descriptor();
        let head = [
            Field::text(names::METHOD, self.setup.method().name()),
            Field::text(names::MODEL, law.name),
            Field::text(names::MODEL_BASIS, law.basis.name()),
        ];
        let mut tables = std::collections::BTreeMap::<String, Table>::new();
        let rows = self.compute_method(inputs, &mut tables)?;
        let n = rows.len();
        let mut checked = Vec::with_capacity(n);
        for (i, row) in rows.into_iter().enumerate() {
            let metrics = head.iter().cloned().chain(row).collect();
            let artifact = if i + 1 == n {
                self.checked(inputs, metrics, std::mem::take(&mut tables))?
            } else {
                self.checked(inputs, metrics, Default::default())
                    .map_err(|e| steps::at_step(e, i, n))?
            };
            checked.push(artifact);
        }
        let curve = steps::step_table(
            &checked
                .iter()
                .map(|a| (a.metrics.clone(), a.flags.clone()))
                .collect::<Vec<_>>(),
        )?;
        let mut artifact = checked
            .pop()
            .ok_or_else(|| NodeError::new("no load step was computed"))?;
        artifact.tables.insert(String::from(TABLES_CURVE), curve);
        Ok(artifact)
    }
}

impl FrictionTask {
    /// The row of `metrics` (with the long `tables` of its step) and its validity: the input
    /// flags, the nominal pressure against the flow pressure, the law's μ_s bound and the
    /// column rules ([`validity::check_artifact`]).
    fn checked(
        &self,
        inputs: &[&Artifact],
        metrics: Vec<Field>,
        tables: std::collections::BTreeMap<String, Table>,
    ) -> Result<Artifact, NodeError> {
        let mut artifact = Artifact {
            metrics,
            arrays: Default::default(),
            tables,
            flags: self.input_flags.clone(),
        };
        if let Some(Value::Float(p)) = artifact.metric(names::NOMINAL_PRESSURE).map(|f| &f.value) {
            validity::cross::pressure_within_flow(*p, self.material.hardness)
                .map_err(NodeError::new)?;
        }
        trust::inherit_flags(&self.input_roles, inputs, &mut artifact.flags);
        trust::flag_mu_beyond_law(self.law.descriptor(), &mut artifact);
        trust::flag_load_beyond_fit(self.law.descriptor(), &mut artifact);
        validity::check_artifact(KIND, &mut artifact)?;
        Ok(artifact)
    }

    /// The method's metrics at each load step (the last the final step) and its long tables
    /// of the final step.
    fn compute_method(
        &self,
        inputs: &[&Artifact],
        tables: &mut std::collections::BTreeMap<String, Table>,
    ) -> Result<Vec<Vec<Field>>, NodeError> {
        if let MethodSetup::PerSummit { contact, .. } | MethodSetup::PerSpot { contact, .. } =
            &self.setup
        {
            let artifact = input(inputs, contact.index, roles::CONTACT)?;
            let (ny, nx) = ContactView::of(artifact, contact.task.material())?
                .pressure
                .dim();
            validity::cross::friction_grid(nx, ny).map_err(NodeError::new)?;
        }
        match &self.setup {
            MethodSetup::Statistical {
                roughness,
                nominal_area,
                loads,
            } => statistical::compute(self, inputs, roughness, *nominal_area, loads),
            MethodSetup::PerSummit {
                contact,
                nominal_area,
                periodic,
                summits_table,
            } => per_summit::compute(
                self,
                contact,
                input(inputs, contact.index, roles::CONTACT)?,
                *nominal_area,
                *periodic,
                *summits_table,
                tables,
            ),
            MethodSetup::PerSpot { contact, section } => per_spot::compute(
                self,
                contact,
                input(inputs, contact.index, roles::CONTACT)?,
                section,
                tables,
            ),
        }
    }
}

impl MethodSetup {
    /// The method this setup is for.
    pub(crate) fn method(&self) -> Method {
        match self {
            Self::Statistical { .. } => Method::Statistical,
            Self::PerSummit { .. } => Method::PerSummit,
            Self::PerSpot { .. } => Method::PerSpot,
        }
    }
}

impl FrictionTask {
    /// The single-asperity laws of the law (the statistical and per-summit methods); the setup
    /// checked that the law has them ([`model_spec`]).
    fn asperity_laws(&self) -> Result<Arc<dyn crate::friction::AsperityLaws>, NodeError> {
        Arc::clone(&self.law).asperity_laws().ok_or_else(|| {
            NodeError::new(format!(
                "`model: {}` has no single-asperity laws: use `method: per_spot`",
                self.law.descriptor().name
            ))
        })
    }
}

/// The coefficient columns of a row: `mu_s` (never negative), `mu_s_computed` (the model's value
/// as computed) and `mu_s_floored` (true when a negative computed value is reported as 0: a
/// negative total Q_max, e.g. the literal KE 2004 polynomial at high plasticity index).
pub fn coefficient_fields(mu_computed: f64) -> [Field; 3] {
    let floored = mu_computed < 0.0;
    [
        Field::float(names::MU_S, mu_computed.max(0.0), Dimension::Dimensionless),
        Field::float(names::MU_S_COMPUTED, mu_computed, Dimension::Dimensionless),
        Field::bool(names::MU_S_FLOORED, floored),
    ]
}

/// `load_share_beyond_fit`: the share of the normal load carried outside the validated range of
/// the law used (0 when there is no load).
pub fn beyond_fit_field(load_beyond_fit: f64, normal_load: f64) -> Field {
    let share = share(load_beyond_fit, normal_load).clamp(0.0, 1.0);
    Field::float(
        names::LOAD_SHARE_BEYOND_FIT,
        share,
        Dimension::Dimensionless,
    )
}

/// `adhesion_share`: the adhesion force over the contact load, F_a/F_n (0 without load); above
/// the validity rule's bound μ_s = Q/(F_n − F_a) is governed by a small difference.
pub(crate) fn adhesion_share_field(adhesion_force: f64, normal_load: f64) -> Field {
    Field::float(
        names::ADHESION_SHARE,
        share(adhesion_force, normal_load),
        Dimension::Dimensionless,
    )
}

/// `part / whole`, 0 when `whole` is not positive.
pub fn share(part: f64, whole: f64) -> f64 {
    if whole > 0.0 {
        part / whole
    } else {
        0.0
    }
}
