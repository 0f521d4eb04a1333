//! `method: per_spot`: the friction law per contact spot of the solution a contact node computed
//! (`fields: true`), [`crate::friction::per_spot_friction`].
//!
//! * **Spots**: connected components of the points with p > 0 of the contact's `pressure`
//!   (4- or 8-neighbours, `spot_connectivity`), joined across the edges when the contact was
//!   periodic; load Σ p dA and area from the solution, radius from a paraboloid fitted to the
//!   contact's `composite_height` over the spot and its ring ([`crate::friction::contact_spots`]).
//! * **Adhesion** F_a: the Lennard-Jones attraction of the points out of contact across the
//!   contact's `gap` (`adhesion_from_gap`), 0 with `adhesion_energy: 0`.
//! * **Coefficient**: μ_s = Σ Q_i/(Σ P_i − F_a) of the section; forces are scaled to
//!   `nominal_area` like the per-summit method (μ_s is invariant under that scaling).
//! * **Trust**: `load_share_beyond_fit` (spots outside the law's validated range),
//!   `load_share_one_pixel` and `one_pixel_spots` (resolution-limited spots),
//!   `load_share_without_radius` and `spots_without_radius` (no convex radius: no Q, a lower
//!   bound), spot-area and local-μ quantiles over the spots.

use std::collections::BTreeMap;

use crate::engine::artifact::{Artifact, Table};
use crate::engine::node::NodeError;
use crate::engine::value::Field;
use crate::friction::contact_spots::{
    adhesion_from_gap, label_spots, measure_spots, Connectivity, ContactSpot,
};
use crate::friction::per_summit::quantile;
use crate::friction::{
    per_spot_friction, per_spot_friction_on_slopes, spot_slopes, PerSpotResult, SpotLoad,
};
use crate::units::Dimension;
use crate::vocabulary::{self, metrics as names, spot_columns};

use super::deformation_part::{extend_spots_table, push_parts};
use super::{beyond_fit_field, coefficient_fields, FrictionTask};
use crate::nodes::contact_view::ContactView;

/// How the section is read.
#[derive(Debug, Clone)]
pub(crate) struct Section {
    pub nominal_area: Option<f64>,
    pub periodic: bool,
    pub connectivity: Connectivity,
    pub spots_table: bool,
}

pub(super) fn compute(
    task: &FrictionTask,
    contact: &Artifact,
    section: &Section,
    metrics: &mut Vec<Field>,
    tables: &mut BTreeMap<String, Table>,
) -> Result<(), NodeError> {
    let fields = ContactView::of(contact)?;
    let (pressure, gap, height) = (fields.pressure, fields.gap, fields.composite_height);
    let (dx, dy) = (fields.dx, fields.dy);
    let fail = |what: &str, e: crate::friction::FrictionError| {
        NodeError::new(format!("per-spot friction, {what}: {e}"))
    };
    let labels = label_spots(pressure, section.periodic, section.connectivity)
        .map_err(|e| fail("contact spots", e))?;
    let spots =
        measure_spots(&labels, pressure, height, dx, dy).map_err(|e| fail("contact spots", e))?;
    let adhesion =
        adhesion_from_gap(gap, pressure, dx, dy, task.adhesion).map_err(|e| fail("adhesion", e))?;
    let loads: Vec<SpotLoad> = spots.iter().map(SpotLoad::from).collect();
    let law = task.law.as_ref();
    let slopes = match law.sliding_direction() {
        Some(direction) => Some(
            spot_slopes(&labels, &spots, height, (dx, dy), direction)
                .map_err(|e| fail("spot slopes", e))?,
        ),
        None => None,
    };
    let result = match &slopes {
        Some(slopes) => per_spot_friction_on_slopes(&loads, slopes, law, adhesion),
        None => per_spot_friction(&loads, law, adhesion),
    }
    .map_err(|e| fail("law", e))?;
    let mu_s = result.mu_s.ok_or_else(|| {
        NodeError::new(format!(
            "no compressive net force on the contact spots (sum P = {} N, F_a = {} N): the section carries no friction",
            result.total_normal_force, result.adhesion_force
        ))
    })?;
    let (ny, nx) = pressure.dim();
    let section_area = nx as f64 * dx * ny as f64 * dy;
    let area = section.nominal_area.unwrap_or(section_area);
    metrics.extend(coefficient_fields(mu_s));
    metrics.push(beyond_fit_field(
        result.load_beyond_fit,
        result.total_normal_force,
    ));
    let nominal_pressure = fields.nominal_pressure;
    push_forces(
        metrics,
        &result,
        area / section_area,
        nominal_pressure * area,
    );
    push_spot_statistics(metrics, &spots, &result, section_area, area);
    if let Some(slopes) = &slopes {
        push_parts(metrics, &spots, slopes, &result);
    }
    if section.spots_table {
        let mut table = spots_table(&spots, &result, dx, dy);
        if let Some(slopes) = &slopes {
            extend_spots_table(&mut table, &spots, slopes, &result);
        }
        tables.insert(String::from(vocabulary::tables::SPOTS), table);
    }
    Ok(())
}

/// The force columns, scaled from the section to the nominal area.
fn push_forces(
    metrics: &mut Vec<Field>,
    result: &PerSpotResult,
    scale: f64,
    contact_normal_load: f64,
) {
    let force = |name: &'static str, v: f64| Field::float(name, scale * v, Dimension::Force);
    metrics.extend([
        force(
            names::EXTERNAL_LOAD,
            result.total_normal_force - result.adhesion_force,
        ),
        force(names::NORMAL_LOAD, result.total_normal_force),
        force(names::ADHESION_FORCE, result.adhesion_force),
        force(names::FRICTION_FORCE, result.total_friction_force.max(0.0)),
        Field::float(
            names::CONTACT_NORMAL_LOAD,
            contact_normal_load,
            Dimension::Force,
        ),
    ]);
}

/// Area, spot counts, the resolution and radius shares and the quantiles over the spots.
fn push_spot_statistics(
    metrics: &mut Vec<Field>,
    spots: &[ContactSpot],
    result: &PerSpotResult,
    section_area: f64,
    area: f64,
) {
    let n = |name: &'static str, v: f64| Field::float(name, v, Dimension::Dimensionless);
    let share = |load: f64| {
        if result.total_normal_force > 0.0 {
            load / result.total_normal_force
        } else {
            0.0
        }
    };
    let area_fraction = result.total_area / section_area;
    metrics.extend([
        Field::float(names::REAL_AREA, area_fraction * area, Dimension::Area),
        n(names::AREA_FRACTION, area_fraction),
        Field::float(names::APPARENT_AREA, area, Dimension::Area),
        Field::float(names::SECTION_AREA, section_area, Dimension::Area),
        Field::int(names::SPOT_COUNT, spots.len() as i64),
        Field::int(names::ONE_PIXEL_SPOTS, result.one_pixel_spots as i64),
        n(names::LOAD_SHARE_ONE_PIXEL, share(result.load_one_pixel)),
        Field::int(
            names::SPOTS_WITHOUT_RADIUS,
            result.spots_without_radius as i64,
        ),
        n(
            names::LOAD_SHARE_WITHOUT_RADIUS,
            share(result.load_without_radius),
        ),
    ]);
    let mut areas: Vec<f64> = spots.iter().map(|s| s.area).collect();
    areas.sort_by(f64::total_cmp);
    let mut local: Vec<f64> = spots
        .iter()
        .zip(&result.spots)
        .filter(|(s, _)| s.load > 0.0)
        .map(|(s, f)| (f.friction_force / s.load).max(0.0))
        .collect();
    local.sort_by(f64::total_cmp);
    if !areas.is_empty() {
        let area_quantiles = [
            (names::SPOT_AREA_P10, 0.1),
            (names::SPOT_AREA_MEDIAN, 0.5),
            (names::SPOT_AREA_P90, 0.9),
        ];
        for (name, q) in area_quantiles {
            metrics.push(Field::float(name, quantile(&areas, q), Dimension::Area));
        }
    }
    if !local.is_empty() {
        let mu_quantiles = [
            (names::LOCAL_MU_P10, 0.1),
            (names::LOCAL_MU_MEDIAN, 0.5),
            (names::LOCAL_MU_P90, 0.9),
        ];
        for (name, q) in mu_quantiles {
            metrics.push(Field::float(
                name,
                quantile(&local, q),
                Dimension::Dimensionless,
            ));
        }
    }
}

/// One row per spot: peak position, size, load, radius (0 with `radius_status` `not_convex`),
/// load measure (P* for full stick, x for KE/CEB, 0 where the law has none), friction and
/// whether the spot is inside the law's validated range (section values).
fn spots_table(spots: &[ContactSpot], result: &PerSpotResult, dx: f64, dy: f64) -> Table {
    let pairs: Vec<_> = spots.iter().zip(&result.spots).collect();
    let float = |f: &dyn Fn(&ContactSpot, &crate::friction::SpotFriction) -> f64| {
        pairs.iter().map(|(s, r)| f(s, r)).collect::<Vec<f64>>()
    };
    let mut t = Table::default();
    t.push_int(spot_columns::SPOT, (0..spots.len() as i64).collect());
    t.push_int(
        spot_columns::PEAK_IX,
        spots.iter().map(|s| s.peak.1 as i64).collect(),
    );
    t.push_int(
        spot_columns::PEAK_IY,
        spots.iter().map(|s| s.peak.0 as i64).collect(),
    );
    t.push_float(
        spot_columns::PEAK_X,
        Dimension::Length,
        float(&|s, _| s.peak.1 as f64 * dx),
    );
    t.push_float(
        spot_columns::PEAK_Y,
        Dimension::Length,
        float(&|s, _| s.peak.0 as f64 * dy),
    );
    t.push_int(
        spot_columns::PIXELS,
        spots.iter().map(|s| s.pixels as i64).collect(),
    );
    t.push_float(spot_columns::AREA, Dimension::Area, float(&|s, _| s.area));
    t.push_float(
        spot_columns::NORMAL_FORCE,
        Dimension::Force,
        float(&|s, _| s.load),
    );
    t.push_float(
        spot_columns::MAX_PRESSURE,
        Dimension::Pressure,
        float(&|s, _| s.max_pressure),
    );
    t.push_float(
        spot_columns::RADIUS,
        Dimension::Length,
        float(&|s, _| s.radius.unwrap_or(0.0)),
    );
    t.push_text(
        spot_columns::RADIUS_STATUS,
        spots
            .iter()
            .map(|s| {
                String::from(if s.radius.is_some() {
                    "convex"
                } else {
                    "not_convex"
                })
            })
            .collect(),
    );
    t.push_float(
        spot_columns::LOAD_MEASURE,
        Dimension::Dimensionless,
        float(&|_, r| r.load_measure.unwrap_or(0.0)),
    );
    t.push_float(
        spot_columns::FRICTION_FORCE,
        Dimension::Force,
        float(&|_, r| r.friction_force.max(0.0)),
    );
    t.push_float(
        spot_columns::LOCAL_MU,
        Dimension::Dimensionless,
        float(&|s, r| {
            if s.load > 0.0 {
                (r.friction_force / s.load).max(0.0)
            } else {
                0.0
            }
        }),
    );
    t.push_text(
        spot_columns::FIT,
        pairs
            .iter()
            .map(|(_, r)| String::from(if r.beyond_fit { "beyond" } else { "inside" }))
            .collect(),
    );
    t
}
