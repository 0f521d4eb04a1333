//! Load steps of a contact: solved one after the other (each converged step handed to the node
//! while the solver holds it), and the maps of any step derived from its stored pressure.
//!
//! The expensive part of a step's maps, the convolution `u = K p` of its pressure, is done once
//! per contact for all its consumers: [`ContactTask::earlier_displacements`] convolves every
//! earlier step's pressure with one operator when the contact is computed or read for its
//! dependants (the artifact then holds them as [`STEP_DISPLACEMENTS`] until its last dependant is
//! done), and [`ContactTask::step_pressure`] only reads a step's pressure, into the array of the
//! step read before; its other maps are derived from the two when they are read
//! (`StepPressure::view`).
//!
//! [`STEP_DISPLACEMENTS`]: crate::nodes::contact_view::STEP_DISPLACEMENTS

use ndarray::{Array2, Array3, ArrayD, ArrayView2, Ix2};

use super::super::contact_view::{
    fill_pressure_of_contact_points, step_pressure_name, StepPressure, COMPOSITE_HEIGHT,
};
use super::ContactTask;
use crate::contact::{ContactError, ContactSolver, DisplacementOperator, LoadCurve};
use crate::engine::artifact::{Artifact, ColumnData};
use crate::engine::node::NodeError;
use crate::engine::value::Value;
use crate::vocabulary::metrics::{APPROACH, AREA_FRACTION, DX, DY, NOMINAL_PRESSURE};
use crate::vocabulary::tables;

impl ContactTask {
    /// Load step `step` (0 for the first listed pressure) before the final one of this contact,
    /// whose artifact `contact` (computed, or cached with its derived arrays, as a consumer
    /// receives it) holds the step's pressure: its pressure map (into the array of `reuse`, the
    /// step read before, instead of a new one), approach, nominal pressure and contact area
    /// share; [`StepPressure::view`] derives the other maps from it. The final step's maps are
    /// the contact's own (`ContactView::of`). An error when the contact kept no fields or has no
    /// such earlier step.
    pub fn step_pressure(
        &self,
        contact: &Artifact,
        step: usize,
        reuse: Option<StepPressure>,
    ) -> Result<StepPressure, NodeError> {
        let (approach, nominal_pressure, area_fraction, steps) = step_values(contact, step)?;
        if step + 1 >= steps {
            return Err(NodeError::new(format!(
                "load step {step} is not one before the final step {}: its maps are the \
                 contact's own",
                steps - 1
            )));
        }
        let shape = array2(contact, COMPOSITE_HEIGHT)?.dim();
        let mut pressure = match reuse {
            Some(earlier) if earlier.pressure.dim() == shape => earlier.pressure,
            _ => Array2::zeros(shape),
        };
        let name = step_pressure_name(step);
        let points = contact.arrays.get(&name).ok_or_else(|| no_fields(&name))?;
        fill_pressure_of_contact_points(points, &mut pressure)?;
        Ok(StepPressure {
            step,
            pressure,
            approach,
            nominal_pressure,
            area_fraction,
            material: self.material,
        })
    }

    /// The composite displacement `u = K p` (m) of every load step before the final one, from
    /// the steps' pressure in `contact` (this contact's artifact, with the final step's metrics
    /// and every earlier step's pressure) on its grid `shape = (ny, nx)`, by one operator for all
    /// steps: the [`STEP_DISPLACEMENTS`](crate::nodes::contact_view::STEP_DISPLACEMENTS) array,
    /// `[[step, iy, ix]]`, which every consumer of the contact reads instead of convolving the
    /// steps itself. `None` without fields or earlier steps.
    pub(super) fn earlier_displacements(
        &self,
        contact: &Artifact,
        shape: (usize, usize),
    ) -> Result<Option<ArrayD<f64>>, NodeError> {
        let earlier = self.pressures.len().saturating_sub(1);
        if !self.fields || earlier == 0 {
            return Ok(None);
        }
        let mut operator = self.displacement_operator(contact, shape)?;
        let mut displacements = Array3::zeros((earlier, shape.0, shape.1));
        let mut pressure = Array2::zeros(shape);
        for (step, mut u) in displacements.outer_iter_mut().enumerate() {
            let name = step_pressure_name(step);
            let points = contact.arrays.get(&name).ok_or_else(|| no_fields(&name))?;
            fill_pressure_of_contact_points(points, &mut pressure)?;
            let u = u
                .as_slice_mut()
                .unwrap_or_else(|| unreachable!("a step of a new array is one slice"));
            operator
                .apply(pressure.view(), u)
                .map_err(|e| NodeError::new(format!("displacement of load step {step}: {e}")))?;
        }
        Ok(Some(displacements.into_dyn()))
    }

    /// The influence operator of the contact's grid (`shape`, and the spacings among the
    /// metrics of its artifact `contact`), material and boundary, as the solver had it.
    fn displacement_operator(
        &self,
        contact: &Artifact,
        shape: (usize, usize),
    ) -> Result<DisplacementOperator, NodeError> {
        let metric = |name: &str| match contact.metric(name).map(|f| &f.value) {
            Some(Value::Float(v)) => Ok(*v),
            _ => Err(NodeError::new(format!("contact node: no {name}"))),
        };
        DisplacementOperator::new(
            shape,
            (metric(DX)?, metric(DY)?),
            &self.material,
            self.boundary(),
        )
        .map_err(|e| NodeError::new(format!("influence operator: {e}")))
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

/// The approach (m), nominal pressure (Pa) and contact area share of load step `step` from the
/// contact's load curve, and its number of steps.
fn step_values(contact: &Artifact, step: usize) -> Result<(f64, f64, f64, usize), NodeError> {
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
    Ok((
        column(APPROACH)?,
        column(NOMINAL_PRESSURE)?,
        column(AREA_FRACTION)?,
        curve.rows(),
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
