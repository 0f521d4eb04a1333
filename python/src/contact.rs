//! `contact`: the elastic–perfectly-plastic FFT boundary-element solver of a study's `contact`
//! node on arrays. The problem is built as the node builds it (composite gap of one map
//! against a rigid flat or of two maps, the bodies' elasticity, the flow pressure, the
//! boundary) and solved through the same load steps with the same options, so equal inputs give
//! the node's numbers bit for bit.

use asperity::contact::{
    fields_from_pressure, Boundary, CompositeGap, ContactFields, ContactMaterial, ContactProblem,
    ContactSolver, FieldRequest, LoadCurve, LoadStep, SolverOptions,
};
use asperity::engine::artifact::Artifact;
use asperity::materials::{find_material, BodyMaterial, MaterialPair};
use asperity::nodes::final_step_metrics;
use asperity::nodes::validity::cross::{contact_grid, contact_slope};
use asperity::nodes::validity::{check_artifact, CONTACT};
use asperity::vocabulary::arrays;
use numpy::{IntoPyArray, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::guard::{compute, value_error};
use crate::row::set_fields;
use crate::surface::height_map;

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(contact, m)?)?;
    m.add_function(wrap_pyfunction!(material, m)?)?;
    m.add("DEFAULT_TOLERANCE", SolverOptions::default().tolerance)?;
    Ok(())
}

/// A built-in material by name or alias (case-insensitive): its constants in SI and sources.
#[pyfunction]
fn material<'py>(py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyDict>> {
    let m = find_material(name).map_err(|e| value_error("material", e))?;
    let d = PyDict::new(py);
    d.set_item("name", m.name)?;
    let body = BodyMaterial::new(m.constants).map_err(|e| value_error("material", e))?;
    d.set_item("youngs_modulus", body.youngs_modulus())?;
    d.set_item("poisson_ratio", body.poisson_ratio())?;
    d.set_item("hardness", body.hardness())?;
    d.set_item("flow_pressure", body.flow_pressure())?;
    d.set_item("source", m.source)?;
    Ok(d)
}

/// A body `(E, ν)` in Pa and 1; `field` names it in errors.
fn body((youngs_modulus, poisson_ratio): (f64, f64), field: &str) -> PyResult<BodyMaterial> {
    BodyMaterial::elastic(youngs_modulus, poisson_ratio).map_err(|e| value_error(field, e))
}

/// The contact problem: lower map (against a flat, or against the upper map), the bodies and
/// p_lim (Pa, +∞ elastic).
struct Setup {
    problem: ContactProblem,
    composite_modulus: f64,
    spacing: (f64, f64),
}

fn setup(
    lower: asperity::surface::HeightMap,
    upper: Option<(asperity::surface::HeightMap, (f64, f64))>,
    lower_body: (f64, f64),
    flow_pressure: f64,
    periodic: bool,
) -> PyResult<Setup> {
    let (gap, upper_body) = match &upper {
        Some((map, e)) => (
            CompositeGap::from_surfaces(&lower, map).map_err(|e| value_error("upper", e))?,
            Some(body(*e, "upper_body")?),
        ),
        None => (
            CompositeGap::against_flat(&lower).map_err(|e| value_error("lower", e))?,
            None,
        ),
    };
    let pair = MaterialPair::new(body(lower_body, "lower_body")?, upper_body);
    let material = ContactMaterial::with_flow_pressure(pair, flow_pressure)
        .map_err(|e| value_error("flow_pressure", e))?;
    let boundary = if periodic {
        Boundary::Periodic
    } else {
        Boundary::NonPeriodic
    };
    Ok(Setup {
        problem: ContactProblem::new(gap, material, boundary),
        composite_modulus: material.composite_modulus(),
        spacing: (lower.dx(), lower.dy()),
    })
}

/// Solves the load steps `nominal_pressures` (Pa, ascending); see `asperity.contact`. `slopes`
/// are the rms slopes Sdq of the given surfaces (from their statistics) for the node's flag of
/// a composite slope beyond the half-space theory. Returns the result and the sentences that
/// would flag the node's row.
#[pyfunction]
#[pyo3(signature = (lower, dx, dy, lower_body, nominal_pressures, flow_pressure, upper=None, upper_body=None, periodic=true, tolerance=None, slopes=Vec::new(), all_steps=false))]
#[allow(clippy::too_many_arguments)]
fn contact<'py>(
    py: Python<'py>,
    lower: PyReadonlyArray2<'py, f64>,
    dx: f64,
    dy: f64,
    lower_body: (f64, f64),
    nominal_pressures: Vec<f64>,
    flow_pressure: f64,
    upper: Option<PyReadonlyArray2<'py, f64>>,
    upper_body: Option<(f64, f64)>,
    periodic: bool,
    tolerance: Option<f64>,
    slopes: Vec<f64>,
    all_steps: bool,
) -> PyResult<(Bound<'py, PyDict>, Vec<String>)> {
    let lower = height_map("lower", &lower, dx, dy)?;
    let upper = match (upper, upper_body) {
        (Some(h), Some(e)) => Some((height_map("upper", &h, dx, dy)?, e)),
        (None, None) => None,
        _ => {
            return Err(value_error(
                "upper_material",
                "an upper surface needs its material, and a material needs the upper surface",
            ))
        }
    };
    check_pressures(&nominal_pressures, flow_pressure)?;
    let options = SolverOptions {
        tolerance: tolerance.unwrap_or(SolverOptions::default().tolerance),
        // Every step's pressure, for the maps of the earlier steps (`all_steps`).
        fields: FieldRequest {
            pressure: all_steps,
            ..FieldRequest::NONE
        },
        ..SolverOptions::default()
    };
    let grid_flag = contact_grid(lower.nx(), lower.ny());
    let (artifact, curve, fields, earlier) = compute(py, || {
        let s = setup(lower, upper, lower_body, flow_pressure, periodic)?;
        check_strain(&nominal_pressures, s.composite_modulus)?;
        let problem = all_steps.then(|| s.problem.clone());
        let mut solver =
            ContactSolver::new(s.problem, options).map_err(|e| value_error("tolerance", e))?;
        let curve = solver
            .solve_load_steps(&nominal_pressures)
            .map_err(|e| value_error("nominal_pressures", e))?;
        let last = curve
            .steps
            .last()
            .ok_or_else(|| value_error("nominal_pressures", "needs at least one pressure (Pa)"))?;
        let mut artifact = Artifact {
            metrics: final_step_metrics(last, s.composite_modulus, s.spacing),
            flags: grid_flag
                .into_iter()
                .chain(contact_slope(&slopes))
                .collect(),
            ..Artifact::default()
        };
        check_artifact(CONTACT, &mut artifact).map_err(|e| value_error("contact", e.message))?;
        let fields = solver.into_last_fields(FieldRequest::ALL);
        let earlier = match &problem {
            Some(problem) => earlier_step_fields(problem, &curve)?,
            None => Vec::new(),
        };
        Ok((artifact, curve, fields, earlier))
    })?;
    let d = PyDict::new(py);
    set_fields(&d, artifact.metrics)?;
    let steps = curve.steps.iter().map(step_dict).collect::<Vec<_>>();
    d.set_item("load_curve", steps.into_pyobject(py)?)?;
    if all_steps {
        let maps = earlier.into_iter().map(Some).chain([fields.clone()]);
        d.set_item("steps", step_dicts(py, &curve, maps)?)?;
    }
    if let Some(f) = fields {
        set_maps(&d, f)?;
    }
    Ok((d, artifact.flags))
}

/// One dict per load step: its nominal pressure, contact area share and `maps`.
fn step_dicts<'py>(
    py: Python<'py>,
    curve: &LoadCurve,
    maps: impl Iterator<Item = Option<ContactFields>>,
) -> PyResult<Bound<'py, PyList>> {
    let steps = PyList::empty(py);
    for (step, f) in curve.steps.iter().zip(maps) {
        let s = PyDict::new(py);
        s.set_item("nominal_pressure_Pa", step.nominal_pressure)?;
        s.set_item("area_fraction", step.area_fraction)?;
        if let Some(f) = f {
            set_maps(&s, f)?;
        }
        steps.append(s)?;
    }
    Ok(steps)
}

/// The maps of a step under the names of a study's contact fields.
fn set_maps(d: &Bound<'_, PyDict>, f: ContactFields) -> PyResult<()> {
    let py = d.py();
    let named = [
        (arrays::PRESSURE, f.pressure),
        (arrays::GAP, f.gap),
        (arrays::DEFORMATION_LOWER, f.deformation_first),
        (arrays::DEFORMATION_UPPER, f.deformation_second),
        (arrays::PLASTIC_PENETRATION, f.plastic_penetration),
    ];
    for (name, array) in named {
        if let Some(a) = array {
            d.set_item(name, a.into_pyarray(py))?;
        }
    }
    Ok(())
}

/// The maps of every step before the final one, as a study's contact node derives them for
/// its consumers (`ContactTask::step_pressure`): the step's pressure as solved, the other maps from
/// it and the step's approach by the solver's influence operator
/// ([`fields_from_pressure`]).
fn earlier_step_fields(
    problem: &ContactProblem,
    curve: &LoadCurve,
) -> PyResult<Vec<ContactFields>> {
    let derived = FieldRequest {
        pressure: false,
        ..FieldRequest::ALL
    };
    let earlier = curve.steps.len().saturating_sub(1);
    curve.steps[..earlier]
        .iter()
        .enumerate()
        .map(|(i, step)| {
            let pressure = step
                .fields
                .as_ref()
                .and_then(|f| f.pressure.clone())
                .ok_or_else(|| value_error("fields", format!("load step {i} kept no pressure")))?;
            let mut f = fields_from_pressure(problem, pressure.view(), step.approach, derived)
                .map_err(|e| value_error("fields", format!("maps of load step {i}: {e}")))?;
            f.pressure = Some(pressure);
            Ok(f)
        })
        .collect()
}

/// Largest nominal pressure as a share of the composite modulus E*: a mean elastic strain p̄/E*
/// of 1 (a pressure of the modulus' size) is far outside the small strains of linear elasticity
/// — metals carry nominal pressures of 1e-4 E* and less — and is how a modulus in GPa or a
/// pressure in MPa given as a plain number in Pa shows (A/A₀ = 1 without a word otherwise).
const MAX_STRAIN: f64 = 1.0;

/// Every nominal pressure (Pa) below [`MAX_STRAIN`] × E*.
fn check_strain(pressures: &[f64], composite_modulus: f64) -> PyResult<()> {
    for (i, &p) in pressures.iter().enumerate() {
        if p >= MAX_STRAIN * composite_modulus {
            return Err(value_error(
                &format!("nominal_pressures[{i}]"),
                format!(
                    "{p:e} Pa is not below the composite modulus E* = {composite_modulus:e} Pa: \
                     a mean strain p/E* of 1 or more is outside linear elasticity; was the \
                     modulus given in GPa or MPa (E is in Pa, or a string such as '210 GPa') or \
                     the pressure in other units than Pa?"
                ),
            ));
        }
    }
    Ok(())
}

/// Pressures must be finite, > 0, ascending and below the flow pressure (as in a study).
fn check_pressures(pressures: &[f64], flow_pressure: f64) -> PyResult<()> {
    if pressures.is_empty() {
        return Err(value_error(
            "nominal_pressures",
            "needs at least one pressure (Pa)",
        ));
    }
    let mut previous = 0.0;
    for (i, &p) in pressures.iter().enumerate() {
        if !(p > previous && p < flow_pressure) {
            return Err(value_error(
                &format!("nominal_pressures[{i}]"),
                format!("{p:e} Pa is out of range: pressures must ascend, be > 0 Pa and stay below the flow pressure ({flow_pressure:e} Pa)"),
            ));
        }
        previous = p;
    }
    Ok(())
}

/// One load step's results (SI; column names as in `contacts_load_curve`).
fn step_dict(s: &LoadStep) -> std::collections::BTreeMap<&'static str, f64> {
    [
        ("nominal_pressure_Pa", s.nominal_pressure),
        ("area_fraction", s.area_fraction),
        ("mean_contact_pressure_Pa", s.mean_contact_pressure),
        ("stress_ratio", s.stress_ratio),
        ("plastic_area_share", s.plastic_area_share),
        ("mean_separation_m", s.mean_separation),
        ("max_elastic_deformation_m", s.max_elastic_deformation),
        ("approach_m", s.approach),
        ("iterations", s.iterations as f64),
        ("residual", s.residuals.max()),
    ]
    .into_iter()
    .collect()
}
