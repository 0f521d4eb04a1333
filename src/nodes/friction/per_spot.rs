//! `method: per_spot`: the friction law per contact spot of the solution a contact node computed
//! (`fields: true`), in one call of the numerics, [`crate::friction::per_spot_friction`], which
//! the Python binding makes too.
//!
//! * **Spots**: connected components of the points with p > 0 of the contact's `pressure`
//!   (4- or 8-neighbours, `spot_connectivity`), joined across the edges when the contact was
//!   periodic; load Σ p dA and area from the solution, radius from a paraboloid fitted to the
//!   contact's `composite_height` over the spot and its ring ([`crate::friction::contact_spots`]).
//! * **Bodies**: the lower and upper bodies' heights, deformations and hardness
//!   ([`crate::friction::bodies`]): a law with a sliding direction reads the loaded front of the
//!   harder body's deformed surface.
//! * **Adhesion** F_a: the Lennard-Jones attraction of the points out of contact across the
//!   contact's `gap` (`adhesion_from_gap`), 0 with `adhesion_energy: 0`.
//! * **Coefficient**: μ_s = Σ Q_i/(Σ P_i − F_a) of the section; forces are scaled to
//!   `nominal_area` like the per-summit method (μ_s is invariant under that scaling).
//! * **Load steps**: every step of the contact (`friction_curve`, one row each); the earlier
//!   steps' maps are read point by point from their stored pressure (in one array reused at
//!   every step) and the displacement the contact convolved once for all its consumers
//!   (`ContactTask::step_pressure`, `StepPressure::view`); the final step's are read as the
//!   contact stores them. The row and the spots table are the final step's.
//! * **Trust**: the load shares beyond the law's fit, without a radius, on merged spots under a
//!   radius-based law, on one-pixel spots, the adhesion share F_a/F_n, spot-area and local-μ
//!   quantiles over the spots (the validity rules flag the shares above their bounds).

use std::collections::BTreeMap;

use crate::engine::artifact::{Artifact, Table};
use crate::engine::node::NodeError;
use crate::engine::value::Field;
use crate::friction::contact_spots::{Connectivity, ContactSpot};
use crate::friction::per_summit::{load_weighted_quantile, quantile};
use crate::friction::{
    per_spot_friction_with_baseline, BodyHardness, BodyMaps, ContactBodies, ContactSection,
    PerSpotResult, SectionFriction, SpotFriction,
};
use crate::units::Dimension;
use crate::vocabulary::{self, metrics as names, spot_columns};

use super::deformation_part::{extend_spots_table, push_parts};
use super::steps::at_step;
use super::{
    adhesion_share_field, beyond_fit_field, coefficient_fields, share, ContactInput, FrictionTask,
};
use crate::nodes::contact_view::{step_nominal_pressures, ContactView};

/// How the section is read.
#[derive(Debug, Clone)]
pub(crate) struct Section {
    pub nominal_area: Option<f64>,
    pub periodic: bool,
    pub connectivity: Connectivity,
    pub spots_table: bool,
    /// The bodies' hardness: which body flows, which ploughs.
    pub hardness: BodyHardness,
}

/// The numerics' view of the contact node's solution.
fn contact_section<'a>(
    task: &FrictionTask,
    fields: &ContactView<'a>,
    section: &Section,
) -> Result<ContactSection<'a>, crate::friction::FrictionError> {
    let maps = BodyMaps {
        composite_height: fields.composite_height,
        upper_height: fields.upper_height,
        deformation_lower: fields.deformation_lower,
        deformation_upper: fields.deformation_upper,
        plastic_penetration: fields.plastic_penetration,
    };
    Ok(ContactSection {
        pressure: fields.pressure,
        gap: fields.gap,
        bodies: ContactBodies::new(maps, section.hardness)?,
        spacing: (fields.dx, fields.dy),
        periodic: section.periodic,
        connectivity: section.connectivity,
        adhesion: task.adhesion,
    })
}

/// The metrics at each load step of the contact (the earlier steps' maps derived from their
/// pressure, `StepPressure::view`; the final step's read as stored) and the spots table of
/// the final step.
pub(super) fn compute(
    task: &FrictionTask,
    contact: &ContactInput,
    artifact: &Artifact,
    section: &Section,
    tables: &mut BTreeMap<String, Table>,
) -> Result<Vec<Vec<Field>>, NodeError> {
    let n = step_nominal_pressures(artifact)?.len();
    let mut rows = Vec::with_capacity(n);
    let mut previous = None;
    // The slope baseline of the undeformed heights, the same at every step: computed once.
    let mut baseline = None;
    for step in 0..n - 1 {
        let earlier = contact
            .task
            .step_pressure(artifact, step, previous.take())
            .map_err(|e| at_step(e, step, n))?;
        let (metrics, found) = earlier
            .view(artifact)
            .and_then(|view| step_row(task, &view, section, baseline))
            .map_err(|e| at_step(e, step, n))?;
        rows.push(metrics);
        baseline = found.geometry.map(|g| g.slope_baseline);
        previous = Some(earlier);
    }
    drop(previous);
    let fields = ContactView::of(artifact, contact.task.material())?;
    let (metrics, found) = step_row(task, &fields, section, baseline)?;
    rows.push(metrics);
    if section.spots_table {
        let mut table = spots_table(&found.spots, &found.result, (fields.dx, fields.dy));
        if let Some(geometry) = &found.geometry {
            extend_spots_table(&mut table, geometry, &found.result);
        }
        tables.insert(String::from(vocabulary::tables::SPOTS), table);
    }
    Ok(rows)
}

/// The metrics of the section `fields` (one load step) and what the numerics found there, with
/// the slope baseline of an earlier step of the same contact (`None`: computed here).
fn step_row(
    task: &FrictionTask,
    fields: &ContactView<'_>,
    section: &Section,
    slope_baseline: Option<f64>,
) -> Result<(Vec<Field>, SectionFriction), NodeError> {
    let found = contact_section(task, fields, section)
        .and_then(|s| per_spot_friction_with_baseline(&s, task.law.as_ref(), slope_baseline))
        .map_err(|e| NodeError::new(format!("per-spot friction: {e}")))?;
    let SectionFriction {
        spots,
        geometry,
        result,
    } = &found;
    let mu_s = result.mu_s.ok_or_else(|| {
        NodeError::new(format!(
            "no compressive net force on the contact spots (sum P = {} N, F_a = {} N): the section carries no friction",
            result.total_normal_force, result.adhesion_force
        ))
    })?;
    let (ny, nx) = fields.pressure.dim();
    let section_area = nx as f64 * fields.dx * ny as f64 * fields.dy;
    let area = section.nominal_area.unwrap_or(section_area);
    let mut metrics = coefficient_fields(mu_s).to_vec();
    metrics.push(beyond_fit_field(
        result.load_beyond_fit,
        result.total_normal_force,
    ));
    push_forces(
        &mut metrics,
        result,
        area / section_area,
        fields.nominal_pressure,
        area,
    );
    push_spot_statistics(&mut metrics, spots, result, section_area, area);
    if let Some(geometry) = geometry {
        push_parts(&mut metrics, spots, geometry, result);
    }
    Ok((metrics, found))
}

/// The force columns, scaled from the section to the nominal area, the contact's nominal
/// pressure (Pa) and its load over the nominal area `area`, and the adhesion share.
fn push_forces(
    metrics: &mut Vec<Field>,
    result: &PerSpotResult,
    scale: f64,
    nominal_pressure: f64,
    area: f64,
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
            nominal_pressure * area,
            Dimension::Force,
        ),
        Field::float(
            names::NOMINAL_PRESSURE,
            nominal_pressure,
            Dimension::Pressure,
        ),
        adhesion_share_field(result.adhesion_force, result.total_normal_force),
    ]);
}

/// Area, spot counts, the trust shares and the quantiles over the spots.
fn push_spot_statistics(
    metrics: &mut Vec<Field>,
    spots: &[ContactSpot],
    result: &PerSpotResult,
    section_area: f64,
    area: f64,
) {
    let n = |name: &'static str, v: f64| Field::float(name, v, Dimension::Dimensionless);
    let share = |load: f64| share(load, result.total_normal_force);
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
        Field::int(names::MERGED_SPOTS, result.merged_spots as i64),
        n(names::LOAD_SHARE_MERGED, share(result.load_merged)),
    ]);
    push_quantiles(metrics, spots, &result.spots);
}

/// Quantiles of the spot areas (over the spots) and load-weighted quantiles of the local
/// μ_i = Q_i/P_i (a negative one counts as 0): the μ_i below which a share q of Σ P_i sits
/// ([`load_weighted_quantile`]).
fn push_quantiles(metrics: &mut Vec<Field>, spots: &[ContactSpot], friction: &[SpotFriction]) {
    let mut areas: Vec<f64> = spots.iter().map(|s| s.area).collect();
    areas.sort_by(f64::total_cmp);
    let local: Vec<(f64, f64)> = spots
        .iter()
        .zip(friction)
        .filter(|(s, _)| s.load > 0.0)
        .map(|(s, f)| ((f.friction_force / s.load).max(0.0), s.load))
        .collect();
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
    push_local_mu_quantiles(metrics, &local);
}

/// `local_mu_p10`, `local_mu_median`, `local_mu_p90`: load-weighted quantiles of the
/// `(μ_i, load_i)` pairs of the summits or spots (absent when none carries load).
pub(super) fn push_local_mu_quantiles(metrics: &mut Vec<Field>, local: &[(f64, f64)]) {
    let mu_quantiles = [
        (names::LOCAL_MU_P10, 0.1),
        (names::LOCAL_MU_MEDIAN, 0.5),
        (names::LOCAL_MU_P90, 0.9),
    ];
    for (name, q) in mu_quantiles {
        if let Some(mu) = load_weighted_quantile(local, q) {
            metrics.push(Field::float(name, mu, Dimension::Dimensionless));
        }
    }
}

/// One row per spot: peak position, size, load, radius (0 with `radius_status` `not_convex`),
/// summits, load measure (P* for full stick, x for KE/CEB, 0 where the law has none), friction
/// and whether the spot is inside the law's validated range (section values).
fn spots_table(spots: &[ContactSpot], result: &PerSpotResult, (dx, dy): (f64, f64)) -> Table {
    let pairs: Vec<_> = spots.iter().zip(&result.spots).collect();
    let float = |f: &dyn Fn(&ContactSpot, &SpotFriction) -> f64| {
        pairs.iter().map(|(s, r)| f(s, r)).collect::<Vec<f64>>()
    };
    let text = |f: &dyn Fn(&ContactSpot, &SpotFriction) -> &'static str| {
        pairs
            .iter()
            .map(|(s, r)| String::from(f(s, r)))
            .collect::<Vec<_>>()
    };
    let int = |f: &dyn Fn(&ContactSpot) -> usize| spots.iter().map(|s| f(s) as i64).collect();
    let mut t = Table::default();
    t.push_int(spot_columns::SPOT, (0..spots.len() as i64).collect());
    t.push_int(spot_columns::PEAK_IX, int(&|s| s.peak.1));
    t.push_int(spot_columns::PEAK_IY, int(&|s| s.peak.0));
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
    t.push_int(spot_columns::PIXELS, int(&|s| s.pixels));
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
        text(&|s, _| match s.radius {
            Some(_) => "convex",
            None => "not_convex",
        }),
    );
    t.push_int(spot_columns::SUMMITS, int(&|s| s.summits));
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
        float(&|s, r| share(r.friction_force.max(0.0), s.load)),
    );
    t.push_text(
        spot_columns::FIT,
        text(&|_, r| if r.beyond_fit { "beyond" } else { "inside" }),
    );
    t
}
