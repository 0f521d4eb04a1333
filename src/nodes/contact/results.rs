//! What a contact writes: the row of its final load step, the load-curve table and the maps of
//! the final step (under the names of `contact_view`).

use super::super::contact_view::{AREA_FRACTION, DX, DY, NOMINAL_PRESSURE};
use crate::contact::{LoadCurve, LoadStep};
use crate::engine::artifact::Table;
use crate::engine::columns::STEP;
use crate::engine::value::Field;
use crate::units::Dimension;
use crate::vocabulary::contact_metrics::{
    COARSE_ITERATIONS, FREE_SET_ITERATIONS, MAX_ELASTIC_DEFORMATION, MEAN_SEPARATION,
    PLASTIC_AREA_SHARE,
};
use crate::vocabulary::metrics::{
    APPROACH, COMPOSITE_MODULUS, ITERATIONS, MEAN_CONTACT_PRESSURE, RESIDUAL, STRESS_RATIO,
};

/// The `contacts` row: the final load step, the composite modulus and the grid (also the
/// scalars of the Python package's `contact`).
pub fn final_step_metrics(
    last: &LoadStep,
    composite_modulus: f64,
    (dx, dy): (f64, f64),
) -> Vec<Field> {
    vec![
        Field::float(COMPOSITE_MODULUS, composite_modulus, Dimension::Pressure),
        Field::float(NOMINAL_PRESSURE, last.nominal_pressure, Dimension::Pressure),
        Field::float(AREA_FRACTION, last.area_fraction, Dimension::Dimensionless),
        Field::float(
            MEAN_CONTACT_PRESSURE,
            last.mean_contact_pressure,
            Dimension::Pressure,
        ),
        Field::float(STRESS_RATIO, last.stress_ratio, Dimension::Dimensionless),
        Field::float(
            PLASTIC_AREA_SHARE,
            last.plastic_area_share,
            Dimension::Dimensionless,
        ),
        Field::float(MEAN_SEPARATION, last.mean_separation, Dimension::Length),
        Field::float(
            MAX_ELASTIC_DEFORMATION,
            last.max_elastic_deformation,
            Dimension::Length,
        ),
        Field::float(APPROACH, last.approach, Dimension::Length),
        Field::float(DX, dx, Dimension::Length),
        Field::float(DY, dy, Dimension::Length),
        Field::int(ITERATIONS, last.iterations as i64),
        Field::int(COARSE_ITERATIONS, last.coarse_iterations as i64),
        Field::int(FREE_SET_ITERATIONS, last.free_set_iterations as i64),
        Field::float(RESIDUAL, last.residuals.max(), Dimension::Dimensionless),
    ]
}

/// A float column of the load curve: name, dimension and the value of a step.
type StepColumn = (&'static str, Dimension, fn(&LoadStep) -> f64);

/// The `contacts_load_curve` table: one row per load step.
pub(super) fn load_curve_table(curve: &LoadCurve) -> Table {
    let column = |f: fn(&LoadStep) -> f64| curve.steps.iter().map(f).collect();
    let steps: [StepColumn; 8] = [
        (NOMINAL_PRESSURE, Dimension::Pressure, |s| {
            s.nominal_pressure
        }),
        (AREA_FRACTION, Dimension::Dimensionless, |s| s.area_fraction),
        (MEAN_CONTACT_PRESSURE, Dimension::Pressure, |s| {
            s.mean_contact_pressure
        }),
        (STRESS_RATIO, Dimension::Dimensionless, |s| s.stress_ratio),
        (PLASTIC_AREA_SHARE, Dimension::Dimensionless, |s| {
            s.plastic_area_share
        }),
        (MEAN_SEPARATION, Dimension::Length, |s| s.mean_separation),
        (MAX_ELASTIC_DEFORMATION, Dimension::Length, |s| {
            s.max_elastic_deformation
        }),
        (APPROACH, Dimension::Length, |s| s.approach),
    ];
    let mut t = Table::default();
    t.push_int(STEP, (0..curve.steps.len() as i64).collect());
    for (name, dimension, get) in steps {
        t.push_float(name, dimension, column(get));
    }
    t.push_int(
        ITERATIONS,
        curve.steps.iter().map(|s| s.iterations as i64).collect(),
    );
    t.push_int(
        COARSE_ITERATIONS,
        curve
            .steps
            .iter()
            .map(|s| s.coarse_iterations as i64)
            .collect(),
    );
    t.push_int(
        FREE_SET_ITERATIONS,
        curve
            .steps
            .iter()
            .map(|s| s.free_set_iterations as i64)
            .collect(),
    );
    t.push_float(
        RESIDUAL,
        Dimension::Dimensionless,
        column(|s| s.residuals.max()),
    );
    t
}
