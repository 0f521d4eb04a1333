//! The `contact` node kind: elastic–perfectly-plastic half-space contact of one or two upstream
//! surfaces (`contact::ContactSolver`), load-stepped to the last nominal pressure (only the last
//! one is solved when the study does not write the `contacts` table). Table `contacts` (the final
//! step) and `contacts_load_curve` (one row per step); with `fields: true` the final step's
//! pressure and composite displacement `u = K p`, the composite height z₁ + z₂ the contact was
//! solved on and the upper body's heights z₂ (with an upper surface) are arrays for its
//! consumers (the per-summit and per-spot `friction` methods read them), which derive the gap,
//! deformations and plastic penetration of every step point by point
//! ([`super::contact_view::ContactView::of`]; the earlier steps' from
//! [`ContactTask::step_pressure`]).
//!
//! The cache keeps only the pressure maps (the final step's whole, the earlier steps' contact
//! points, `contact_view::contact_points`); the heights are the surfaces' and the displacements
//! follow from a step's pressure by one convolution (`contact::DisplacementOperator`, the
//! influence operator the solver used), which [`ContactTask::derive_arrays`] runs when a
//! consumer reads a cached contact: equal to the solver's to round-off (1e-12 of its largest
//! value, tested), at a few per cent of the solve's cost.

use serde::Deserialize;

use super::contact_view::{
    contact_points, step_pressure_name, COMPOSITE_HEIGHT, DISPLACEMENT, HEIGHT_UPPER, PRESSURE,
    STEP_DISPLACEMENTS,
};
use super::material_spec::MaterialSpec;
use super::surface_view::SurfaceView;
use super::validity;
use crate::contact::{
    Boundary, ContactMaterial, ContactSolver, DisplacementOperator, SolverOptions, MAX_TOLERANCE,
    MIN_TOLERANCE,
};
use crate::engine::artifact::Artifact;
use crate::engine::node::{ArrayStorage, NodeError, NodeTask, UpstreamRef};
use crate::engine::study::{Param, ResolveContext, SourceLocation, SpannedName, SpecError};
use crate::engine::value::{Field, Value};
use crate::materials::{bounds, MaterialPair};
use crate::units::{format_number, Dimension, Pressure, Quantity};
use crate::vocabulary::contact_parameters::{
    of_side, FIELDS, FLOW_PRESSURE, PERIODIC, TOLERANCE, YOUNGS_MODULUS,
};
use crate::vocabulary::metrics::{NOMINAL_PRESSURES, POISSON_RATIO};
use crate::vocabulary::{roles, tables};

mod memory;
mod results;
mod setup;
mod steps;

use memory::memory_estimate;
pub use results::final_step_metrics;
use results::load_curve_table;
use setup::StageClock;
use steps::array2;

pub(crate) use crate::vocabulary::kinds::CONTACT as KIND;
pub(crate) use crate::vocabulary::tables::CONTACTS as TABLE;

/// Implementation version of the `contact` kind; bump whenever its numerics change (27: the
/// cache keeps the pressure of every load step and derives the other maps; 28: the upper body's
/// heights are an array of the fields, the values are those of 27; 29: single-precision
/// transforms with a double-precision polish, values within the solver's tolerance of 28's; 30:
/// the same also where a kernel has round-off values below `f32`'s range, as the padded kernel
/// of a 3512² grid has, which had kept such contacts in double precision: values within the
/// solver's tolerance of 29's there, and the same elsewhere).
pub const CONTACT_KIND_VERSION: u32 = 30;

/// The maps a contact's cache entry leaves out and [`ContactTask::derive_arrays`] derives (the
/// earlier steps' displacements only for its consumers, never stored).
const DERIVED_ARRAYS: &[&str] = &[
    COMPOSITE_HEIGHT,
    HEIGHT_UPPER,
    DISPLACEMENT,
    STEP_DISPLACEMENTS,
];

/// `contact: {...}`.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// Name of the upstream surface node of the lower body.
    pub lower: SpannedName,
    /// Name of the upstream surface node of the upper body; omitted: a rigid flat.
    #[serde(default)]
    pub upper: Option<SpannedName>,
    /// Material of the lower body: a built-in name, a name with overrides or explicit constants.
    pub lower_material: MaterialSpec,
    /// Material of the upper body (required with `upper`).
    #[serde(default)]
    pub upper_material: Option<MaterialSpec>,
    /// Plastic flow pressure p_lim (pressure > 0); omitted: the lowest flow pressure of the
    /// bodies' materials (the softer body yields first; built-in materials and materials with a
    /// hardness have one), else purely elastic.
    #[serde(default)]
    pub flow_pressure: Option<Param<Quantity<Pressure>>>,
    /// Nominal pressures of the load steps, ascending; the last one is the stop criterion.
    pub nominal_pressures: Vec<Param<Quantity<Pressure>>>,
    /// Periodic surfaces (default) or isolated ones (DC-FFT, zero padding).
    #[serde(default)]
    pub periodic: Option<Param<bool>>,
    /// Relative tolerance on every complementarity residual and the force balance (default 1e-6;
    /// at least 1e-12, the solver's f64 floor, and below 1).
    #[serde(default)]
    pub tolerance: Option<Param<f64>>,
    /// Store the final step's pressure, gap, deformation and plastic-penetration maps.
    #[serde(default)]
    pub fields: Option<Param<bool>>,
}

impl ContactSpec {
    pub(crate) fn upstream(&self) -> Vec<UpstreamRef<'_>> {
        let mut refs = vec![UpstreamRef {
            role: roles::LOWER,
            node: &self.lower,
        }];
        if let Some(upper) = &self.upper {
            refs.push(UpstreamRef {
                role: roles::UPPER,
                node: upper,
            });
        }
        refs
    }

    pub(crate) fn instantiate(&self, ctx: &ResolveContext<'_>) -> Result<ContactTask, SpecError> {
        self.check_upstream_kinds(ctx)?;
        let material = self.material(ctx)?;
        let pressures = self.pressures(ctx, material.flow_pressure())?;
        let periodic = match &self.periodic {
            Some(p) => ctx.resolve(p, "periodic")?,
            None => true,
        };
        let tolerance = match &self.tolerance {
            Some(p) => ctx.resolve_checked(p, "tolerance", |t| {
                if (MIN_TOLERANCE..MAX_TOLERANCE).contains(t) {
                    Ok(())
                } else {
                    Err(format!(
                        "is out of range: must be at least {MIN_TOLERANCE:e} and below \
                         {MAX_TOLERANCE} (the solver's residuals cannot fall below ~1e-13 in \
                         f64 arithmetic); write e.g. 1e-6"
                    ))
                }
            })?,
            None => SolverOptions::default().tolerance,
        };
        let fields = match &self.fields {
            Some(p) => ctx.resolve(p, "fields")?,
            None => false,
        };
        let points = ctx
            .upstream(0)
            .and_then(|t| t.as_any().downcast_ref::<super::surface::SurfaceTask>())
            .map_or(1 << 24, super::surface::SurfaceTask::points);
        let memory_estimate = memory_estimate(
            points,
            periodic,
            fields,
            pressures.len(),
            super::thread_scratch_bytes_per_point(),
        );
        Ok(ContactTask {
            material,
            pressures,
            periodic,
            tolerance,
            fields,
            points,
            memory_estimate,
        })
    }

    /// `lower` and `upper` must name surface nodes.
    fn check_upstream_kinds(&self, ctx: &ResolveContext<'_>) -> Result<(), SpecError> {
        for (i, name) in std::iter::once(&self.lower).chain(&self.upper).enumerate() {
            if let Some(up) = ctx.upstream(i) {
                if up.kind() != super::surface::KIND {
                    return Err(spec_error(
                        name.location,
                        if i == 0 { "lower" } else { "upper" },
                        format!(
                            "'{}' is a {} node; contact needs surface nodes",
                            name.value,
                            up.kind()
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// The material pair (the upper body rigid without `upper`) and its flow pressure: the
    /// explicit field, else the pair's ([`MaterialPair::flow_pressure`]), else +∞ (purely
    /// elastic).
    fn material(&self, ctx: &ResolveContext<'_>) -> Result<ContactMaterial, SpecError> {
        let lower = self.lower_material.resolve(ctx, "lower_material")?;
        let upper = match (&self.upper, &self.upper_material) {
            (Some(_), Some(m)) => Some(m.resolve(ctx, "upper_material")?),
            (Some(u), None) => {
                return Err(spec_error(
                    u.location,
                    "upper_material",
                    String::from(
                        "an upper surface needs `upper_material` (a name such as `s235jr` or `{youngs_modulus, poisson_ratio}`)",
                    ),
                ))
            }
            (None, Some(_)) => {
                return Err(spec_error(
                    self.lower.location,
                    "upper_material",
                    String::from(
                        "is given but there is no `upper` surface (the counter-body is a rigid flat)",
                    ),
                ))
            }
            (None, None) => None,
        };
        let pair = MaterialPair::new(lower, upper);
        let Some(p) = &self.flow_pressure else {
            return Ok(ContactMaterial::new(pair));
        };
        let flow_pressure = ctx
            .resolve_checked(p, "flow_pressure", |q| {
                bounds::contact_flow_pressure(q.si())
                    .map(|_| ())
                    .map_err(|e| e.range_message())
            })?
            .si();
        ContactMaterial::with_flow_pressure(pair, flow_pressure)
            .map_err(|e| spec_error(p.location(), "flow_pressure", e.range_message()))
    }

    /// The load steps to solve (Pa): the listed nominal pressures, at least one, ascending, > 0
    /// and below the flow pressure. When the study does not write the `contacts` table (whose
    /// `contacts_load_curve` shows every step), only the last one is kept and solved from the
    /// multilevel start: the others would only warm-start it (what that saves, and where it
    /// does not: `docs/study-format.md`). The instance is then the one of a study that lists
    /// the last pressure alone, key included.
    fn pressures(
        &self,
        ctx: &ResolveContext<'_>,
        flow_pressure: f64,
    ) -> Result<Vec<f64>, SpecError> {
        if self.nominal_pressures.is_empty() {
            return Err(spec_error(
                self.lower.location,
                "nominal_pressures",
                String::from("needs at least one pressure"),
            ));
        }
        let mut pressures = Vec::with_capacity(self.nominal_pressures.len());
        for (i, p) in self.nominal_pressures.iter().enumerate() {
            let v = ctx.resolve(p, &format!("nominal_pressures[{i}]"))?.si();
            let previous = pressures.last().copied().unwrap_or(0.0);
            if !(v > previous && v < flow_pressure) {
                return Err(spec_error(
                    p.location(),
                    &format!("nominal_pressures[{i}]"),
                    format!(
                        "{} Pa is out of range: pressures must ascend, be > 0 and stay below the flow pressure",
                        format_number(v)
                    ),
                ));
            }
            pressures.push(v);
        }
        if !ctx.writes_table(TABLE) {
            pressures.drain(..pressures.len() - 1);
        }
        Ok(pressures)
    }
}

fn spec_error(location: SourceLocation, field: &str, message: String) -> SpecError {
    SpecError {
        location,
        field: field.to_string(),
        message,
    }
}

/// A resolved contact node.
#[derive(Debug, Clone)]
pub struct ContactTask {
    /// The material pair (the upper body rigid: a flat) and p_lim (Pa; +∞: purely elastic).
    material: ContactMaterial,
    /// The load steps solved (Pa): every listed one, or only the last when no written table
    /// shows the others (`ContactSpec::pressures`).
    pressures: Vec<f64>,
    periodic: bool,
    tolerance: f64,
    fields: bool,
    /// The points of the lower surface's grid (the contact's maps have as many).
    points: u64,
    /// Peak memory in bytes, from the grid ([`memory_estimate`]).
    memory_estimate: u64,
}

impl ContactTask {
    /// The key fields: both bodies' elastic constants, the flow pressure (when finite), the
    /// load steps and the solver settings, in SI. The memory estimate is not part of it.
    fn key_fields(&self) -> Vec<Field> {
        let Self {
            material,
            pressures,
            periodic,
            tolerance,
            fields,
            points: _,
            memory_estimate: _,
        } = self;
        let pair = material.pair();
        let mut key = Vec::with_capacity(9);
        for (side, body) in [("lower", Some(pair.lower())), ("upper", pair.upper())] {
            if let Some(body) = body {
                key.extend([
                    Field::float(
                        of_side(side, YOUNGS_MODULUS),
                        body.youngs_modulus(),
                        Dimension::Pressure,
                    ),
                    Field::float(
                        of_side(side, POISSON_RATIO),
                        body.poisson_ratio(),
                        Dimension::Dimensionless,
                    ),
                ]);
            }
        }
        if material.flow_pressure().is_finite() {
            key.push(Field::float(
                FLOW_PRESSURE,
                material.flow_pressure(),
                Dimension::Pressure,
            ));
        }
        key.extend([
            Field::floats(NOMINAL_PRESSURES, pressures.to_vec(), Dimension::Pressure),
            Field::bool(PERIODIC, *periodic),
            Field::float(TOLERANCE, *tolerance, Dimension::Dimensionless),
            Field::bool(FIELDS, *fields),
        ]);
        key
    }

    /// The points of the contact's grid (its maps have as many).
    pub(crate) fn points(&self) -> u64 {
        self.points
    }

    /// The load steps the contact solves.
    pub(crate) fn step_count(&self) -> usize {
        self.pressures.len()
    }

    /// Whether the final step's fields are kept for consumers (`fields: true`).
    pub(crate) fn keeps_fields(&self) -> bool {
        self.fields
    }

    /// Whether the surfaces are periodic (the contact spots wrap around the section).
    pub(crate) fn periodic(&self) -> bool {
        self.periodic
    }

    /// The material pair and flow pressure the contact was solved with.
    pub fn material(&self) -> &ContactMaterial {
        &self.material
    }

    fn boundary(&self) -> Boundary {
        if self.periodic {
            Boundary::Periodic
        } else {
            Boundary::NonPeriodic
        }
    }
}

impl NodeTask for ContactTask {
    fn as_any(&self) -> &dyn std::any::Any {
        self
    }

    fn kind(&self) -> &'static str {
        KIND
    }

    fn version(&self) -> u32 {
        CONTACT_KIND_VERSION
    }

    fn table(&self) -> &'static str {
        TABLE
    }

    fn params(&self) -> Vec<Field> {
        self.key_fields()
    }

    fn memory_estimate(&self) -> u64 {
        self.memory_estimate
    }

    /// With fields, the maps other than the pressures are derived ([`Self::derive_arrays`]);
    /// without, there are no arrays.
    fn array_storage(&self) -> ArrayStorage {
        if self.fields {
            ArrayStorage::Derive(DERIVED_ARRAYS)
        } else {
            ArrayStorage::Store
        }
    }

    /// The composite height from the surfaces and the final step's other maps from its pressure
    /// and approach, by the solver's influence operator: `compute`'s maps to round-off.
    fn derive_arrays(
        &self,
        inputs: &[&Artifact],
        artifact: &mut Artifact,
    ) -> Result<(), NodeError> {
        let shape = array2(artifact, PRESSURE)?.dim();
        if let Some(u) = self.earlier_displacements(artifact, shape)? {
            artifact.arrays.insert(String::from(STEP_DISPLACEMENTS), u);
        }
        let setup = self.problem(inputs)?;
        let pressure = array2(artifact, PRESSURE)?;
        let mut displacement = ndarray::Array2::zeros(shape);
        let slice = displacement
            .as_slice_mut()
            .ok_or_else(|| NodeError::new("the displacement is not one slice"))?;
        DisplacementOperator::of_problem(&setup.problem)
            .and_then(|mut operator| operator.apply(pressure, slice))
            .map_err(|e| NodeError::new(format!("displacement of the final load step: {e}")))?;
        drop(setup);
        artifact
            .arrays
            .insert(String::from(DISPLACEMENT), displacement.into_dyn());
        self.store_heights(inputs, artifact)
    }

    /// Solves the load steps; with fields, the final step's maps come from the consumed solver
    /// and the earlier steps' displacements are convolved before those maps are assembled, so
    /// the node never holds the solver beside the maps (the stages' times are debug events).
    fn compute(&self, inputs: &[&Artifact]) -> Result<Artifact, NodeError> {
        let fail = |what: &str, e: &dyn std::fmt::Display| NodeError::new(format!("{what}: {e}"));
        let mut clock = StageClock::start();
        let setup = self.problem(inputs)?;
        clock.stage("gap");
        let (composite_modulus, spacing) = (setup.composite_modulus, setup.spacing);
        let options = SolverOptions {
            tolerance: self.tolerance,
            ..SolverOptions::default()
        };
        let mut solver =
            ContactSolver::new(setup.problem, options).map_err(|e| fail("solver", &e))?;
        clock.stage("influence operator and plans");
        let steps = self.pressures.len();
        let mut earlier = Vec::new();
        let curve = self.solve_steps(&mut solver, |i, solver| {
            clock.stage(&format!("load step {i}"));
            if self.fields && i + 1 < steps {
                if let Some(p) = solver.last_pressure() {
                    earlier.push((step_pressure_name(i), contact_points(p)));
                }
            }
        })?;
        let last = curve
            .steps
            .last()
            .ok_or_else(|| NodeError::new("no load step was solved"))?;
        let mut artifact = Artifact {
            metrics: final_step_metrics(last, composite_modulus, spacing),
            ..Artifact::default()
        };
        artifact
            .tables
            .insert(String::from(tables::LOAD_CURVE), load_curve_table(&curve));
        if self.fields {
            let solution = solver
                .into_last_solution()
                .ok_or_else(|| NodeError::new("the final load step left no fields"))?;
            artifact.arrays.extend(earlier);
            if let Some(u) = self.earlier_displacements(&artifact, solution.shape())? {
                artifact.arrays.insert(String::from(STEP_DISPLACEMENTS), u);
            }
            clock.stage("earlier steps' displacements");
            let (pressure, displacement) = solution.into_pressure_and_displacement();
            let arrays = [(PRESSURE, pressure), (DISPLACEMENT, displacement)];
            for (name, array) in arrays {
                artifact.arrays.insert(String::from(name), array.into_dyn());
            }
            self.store_heights(inputs, &mut artifact)?;
            clock.stage("final step's maps and heights");
        }
        artifact.flags = input_flags(inputs)?;
        validity::check_artifact(KIND, &mut artifact)?;
        clock.stage("checks");
        Ok(artifact)
    }
}

/// The flags the upstream surfaces give a contact: a grid too coarse to resolve a contact spot,
/// a composite slope beyond the half-space theory's small-slope assumption.
fn input_flags(inputs: &[&Artifact]) -> Result<Vec<String>, NodeError> {
    let lower = SurfaceView::of(
        inputs
            .first()
            .ok_or_else(|| NodeError::new("no lower surface"))?,
        "lower",
    )?;
    let sdq: Vec<f64> = inputs
        .iter()
        .filter_map(|input| match input.metric("sdq").map(|f| &f.value) {
            Some(Value::Float(s)) => Some(*s),
            _ => None,
        })
        .collect();
    Ok([
        validity::cross::contact_grid(lower.nx, lower.ny),
        validity::cross::contact_slope(&sdq),
    ]
    .into_iter()
    .flatten()
    .collect())
}
