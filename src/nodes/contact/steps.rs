//! Load steps of a contact: solved one after the other (each converged step handed to the node
//! while the solver holds it), and the maps of any step derived from its stored pressure.

use ndarray::{ArrayView2, Ix2};

use super::super::contact_view::{
    pressure_of_contact_points, step_pressure_name, StepMaps, COMPOSITE_HEIGHT, PRESSURE,
};
use super::{ContactTask, DERIVED_FIELDS};
use crate::contact::{
    fields_from_pressure, CompositeGap, ContactError, ContactProblem, ContactSolver, LoadCurve,
};
use crate::engine::artifact::{Artifact, ColumnData};
use crate::engine::node::NodeError;
use crate::engine::value::Value;
use crate::vocabulary::metrics::{APPROACH, AREA_FRACTION, DX, DY, NOMINAL_PRESSURE};
use crate::vocabulary::tables;

impl ContactTask {
    /// The maps of load step `step` (0 for the first listed pressure) of this contact, whose
    /// artifact `contact` (computed, or cached with its derived arrays, as a consumer receives
    /// it) holds the step's pressure: the other maps from it, the step's approach and the
    /// composite height by one convolution ([`fields_from_pressure`]). An error when the contact
    /// kept no fields or has no such step.
    pub fn step_maps(&self, contact: &Artifact, step: usize) -> Result<StepMaps, NodeError> {
        let curve = contact
            .tables
            .get(tables::LOAD_CURVE)
            .ok_or_else(|| NodeError::new("the contact has no load curve"))?;
        let column = |name: &str| match curve.columns.iter().find(|c| c.name == name) {
            Some(c) => match &c.data {
                ColumnData::Float(v) => v.get(step).copied().ok_or_else(|| {
                    NodeError::new(format!(
                        "the contact has {} load steps, not a step {step}",
                        v.len()
                    ))
                }),
                _ => Err(NodeError::new(format!(
                    "load curve column {name} is not a float"
                ))),
            },
            None => Err(NodeError::new(format!(
                "the load curve has no column {name}"
            ))),
        };
        let (approach, nominal_pressure, area_fraction) = (
            column(APPROACH)?,
            column(NOMINAL_PRESSURE)?,
            column(AREA_FRACTION)?,
        );
        let composite = array2(contact, COMPOSITE_HEIGHT)?;
        let problem = self.problem_of_composite(composite, contact)?;
        let pressure = if step + 1 == curve.rows() {
            array2(contact, PRESSURE)?.to_owned()
        } else {
            let name = step_pressure_name(step);
            let points = contact.arrays.get(&name).ok_or_else(|| no_fields(&name))?;
            pressure_of_contact_points(points, composite.dim())?
        };
        let f = fields_from_pressure(&problem, pressure.view(), approach, DERIVED_FIELDS)
            .map_err(|e| NodeError::new(format!("maps of load step {step}: {e}")))?;
        let missing = || NodeError::new(format!("maps of load step {step}: a field is missing"));
        Ok(StepMaps {
            gap: f.gap.ok_or_else(missing)?,
            deformation_lower: f.deformation_first.ok_or_else(missing)?,
            deformation_upper: f.deformation_second,
            plastic_penetration: f.plastic_penetration.ok_or_else(missing)?,
            pressure,
            nominal_pressure,
            area_fraction,
        })
    }

    /// The contact problem on the composite height `z` the contact was solved on, with the grid
    /// spacings of its metrics: the gap `g₀ = max z − z` as the solver had it.
    fn problem_of_composite(
        &self,
        z: ArrayView2<f64>,
        contact: &Artifact,
    ) -> Result<ContactProblem, NodeError> {
        let metric = |name: &str| match contact.metric(name).map(|f| &f.value) {
            Some(Value::Float(v)) => Ok(*v),
            _ => Err(NodeError::new(format!("contact node: no {name}"))),
        };
        let gap = CompositeGap::from_gap_array(z.mapv(|h| -h).view(), metric(DX)?, metric(DY)?)
            .map_err(|e| NodeError::new(format!("gap: {e}")))?;
        Ok(ContactProblem::new(gap, self.material, self.boundary()))
    }

    /// Solves the load steps in order, each warm-started from the previous one (as
    /// [`ContactSolver::solve_load_steps`] does), with `each` called on every converged step
    /// while the solver holds it.
    pub(super) fn solve_steps(
        &self,
        solver: &mut ContactSolver,
        mut each: impl FnMut(usize, &ContactSolver),
    ) -> Result<LoadCurve, NodeError> {
        let mut curve = LoadCurve::default();
        for (i, &pressure) in self.pressures.iter().enumerate() {
            let step = solver
                .solve(pressure)
                .map_err(|e| NodeError::new(format!("contact solve: {}", at_step(e, i))))?;
            curve.steps.push(step);
            each(i, solver);
        }
        Ok(curve)
    }
}

/// A solver error of a single-step solve, with the step index of the load curve.
fn at_step(error: ContactError, step: usize) -> ContactError {
    match error {
        ContactError::NotConverged {
            pressure,
            termination,
            iterations,
            residuals,
            ..
        } => ContactError::NotConverged {
            step,
            pressure,
            termination,
            iterations,
            residuals,
        },
        ContactError::BadNominalPressure { pressure, .. } => {
            ContactError::BadNominalPressure { step, pressure }
        }
        ContactError::AboveFlowPressure {
            pressure,
            flow_pressure,
            ..
        } => ContactError::AboveFlowPressure {
            step,
            pressure,
            flow_pressure,
        },
        other => other,
    }
}

pub(super) fn no_fields(name: &str) -> NodeError {
    NodeError::new(format!(
        "the contact node holds no '{name}' array: run it with `fields: true`"
    ))
}

/// The map called `name` of `artifact`.
pub(super) fn array2<'a>(
    artifact: &'a Artifact,
    name: &str,
) -> Result<ArrayView2<'a, f64>, NodeError> {
    artifact
        .arrays
        .get(name)
        .ok_or_else(|| no_fields(name))?
        .view()
        .into_dimensionality::<Ix2>()
        .map_err(|e| NodeError::new(format!("contact array {name}: {e}")))
}
