//! `method: per_summit`: the single-asperity laws per summit of the topography a contact node
//! solved (docs/friction-models.md, "Per summit").
//!
//! * **Summits**: 8-neighbour maxima of the contact's composite height z₁ + z₂ (array
//!   `composite_height`, stored with `fields: true`), periodic neighbourhoods when the contact was
//!   periodic; radius R = −2/∇²z (`surface::find_summits`).
//! * **Interference** of a summit at grid point i: where the contact pressure is positive,
//!   ω = u₁ + u₂ + u_pl, the elastic deformation of both bodies plus the plastic penetration there
//!   (equal to the rigid overlap δ − g₀ at a contact point). This BEM deformation includes the
//!   long-range deformation caused by the neighbouring contacts, unlike the isolated-asperity
//!   assumption of the KE fits (each asperity deformed only by its own load). On periodic grids u is
//!   measured from the mean displaced plane; a contacting summit whose ω comes out ≤ 0 counts as
//!   touching without interference (ω = 0). Where the pressure is zero, ω = −max(g, 0) with g
//!   the gap after loading (the Lennard-Jones adhesion sees that gap).
//! * **Forces**: `friction::per_summit_friction` (F_n, F_a, F_f = Q_max per summit), force-weighted
//!   μ_s = ΣF_f / Σ(F_n − F_a); distribution of local μ = F_f/(F_n − F_a) over summits with
//!   F_n > F_a (median, p10, p90).
//! * **Homogenization**: the section is a representative sample, so forces scale with area: the
//!   force columns are the section sums times A_n/A_section (`nominal_area`, default the section);
//!   μ_s is invariant under that scaling and is the whole-surface estimate.
//! * **Area**: `real_area`/`area_fraction` are the contact node's (points with p > 0), scaled to A_n.
//! * **Load steps**: every step of the contact (`friction_curve`, one row each) on the same
//!   summits; the earlier steps' maps are read point by point from their stored pressure (in
//!   one array reused at every step) and the displacement the contact convolved once for all
//!   its consumers (`StepPressure::view`); the final step's are read as the contact stores them.
//!   The row and the summits table are the final step's.
//! * **ψ**: the plasticity index of the identified summits, (2E/(πKH))·√(σ_s/R̄) with σ_s the std
//!   of their heights and R̄ their mean radius.

use std::collections::BTreeMap;

use crate::contact::PointMap;

use crate::engine::artifact::{Artifact, Table};
use crate::engine::node::NodeError;
use crate::engine::value::Field;
use crate::friction::per_summit::PerSummitResult;
use crate::friction::{
    per_summit_friction, summit_interference, AdhesionBeyondFits, DeformationState, SummitContact,
    SummitFriction,
};
use crate::surface::{find_summits, Boundary, HeightMap, Summit, SummitOptions, Summits};
use crate::units::Dimension;
use crate::vocabulary::{metrics as names, summit_columns, tables};

use super::steps::at_step;
use super::{
    adhesion_share_field, beyond_fit_field, coefficient_fields, ContactInput, FrictionTask,
};
use crate::nodes::contact_view::{step_nominal_pressures, ContactView};

/// The interference ω (m) of the summit at (iy, ix); see the module docs.
fn interference(fields: &ContactView, iy: usize, ix: usize) -> Result<f64, NodeError> {
    let outside = || NodeError::new("a summit lies outside the contact fields");
    let at = |a: &PointMap| a.get((iy, ix)).ok_or_else(outside);
    let upper = match &fields.deformation_upper {
        Some(u) => at(u)?,
        None => 0.0,
    };
    Ok(summit_interference(
        fields.pressure.get((iy, ix)).copied().ok_or_else(outside)?,
        at(&fields.deformation_lower)? + upper,
        at(&fields.plastic_penetration)?,
        at(&fields.gap)?,
    ))
}

fn state_name(state: DeformationState) -> &'static str {
    match state {
        DeformationState::NotInContact => "not_in_contact",
        DeformationState::Elastic => "elastic",
        DeformationState::ElasticPlastic => "elastic_plastic",
        DeformationState::FullyPlastic => "fully_plastic",
    }
}

/// The metrics at each load step of the contact (the earlier steps' maps derived from their
/// pressure, `StepPressure::view`; the final step's read as stored) on the summits of the
/// composite height (the same at every step), and the summits table of the final step.
pub(super) fn compute(
    task: &FrictionTask,
    contact: &ContactInput,
    artifact: &Artifact,
    nominal_area: Option<f64>,
    periodic: bool,
    summits_table: bool,
    tables: &mut BTreeMap<String, Table>,
) -> Result<Vec<Vec<Field>>, NodeError> {
    let maps = ContactView::of(artifact, contact.task.material())?;
    let found = composite_summits(&maps, periodic)?;
    let summits: Vec<&Summit> = found
        .summits
        .iter()
        .filter(|s| s.radius.is_finite() && s.radius > 0.0)
        .collect();
    let on = SummitSet {
        summits: &summits,
        statistics: &found,
        nominal_area,
    };
    let n = step_nominal_pressures(artifact)?.len();
    let mut rows = Vec::with_capacity(n);
    let mut previous = None;
    for step in 0..n - 1 {
        let earlier = contact
            .task
            .step_pressure(artifact, step, previous.take())
            .map_err(|e| at_step(e, step, n))?;
        let row = earlier
            .view(artifact)
            .and_then(|view| step_row(task, &view, &on))
            .map_err(|e| at_step(e, step, n))?;
        rows.push(row.0);
        previous = Some(earlier);
    }
    drop(previous);
    let (metrics, contacts, result) = step_row(task, &maps, &on)?;
    rows.push(metrics);
    if summits_table {
        tables.insert(
            String::from(tables::SUMMITS),
            summits_table_of(&summits, &contacts, &result.summits),
        );
    }
    Ok(rows)
}

/// The summits a per-summit node reads at every load step.
struct SummitSet<'a> {
    /// The summits with a finite positive radius.
    summits: &'a [&'a Summit],
    /// All summits found, with their statistics.
    statistics: &'a Summits,
    nominal_area: Option<f64>,
}

/// The metrics of one load step (`maps`) on the summits, with each summit's contact and
/// forces.
fn step_row(
    task: &FrictionTask,
    maps: &ContactView<'_>,
    on: &SummitSet<'_>,
) -> Result<(Vec<Field>, Vec<SummitContact>, PerSummitResult), NodeError> {
    let (ny, nx) = maps.composite_height.dim();
    let section_area = nx as f64 * maps.dx * ny as f64 * maps.dy;
    let contacts = on
        .summits
        .iter()
        .map(|s| {
            Ok(SummitContact {
                radius: s.radius,
                interference: interference(maps, s.iy, s.ix)?,
            })
        })
        .collect::<Result<Vec<_>, NodeError>>()?;
    let result = per_summit_friction(
        &contacts,
        task.asperity_laws()?.as_ref(),
        &task.material,
        &task.adhesion,
        AdhesionBeyondFits::default(),
    )
    .map_err(|e| NodeError::new(format!("per-summit friction: {e}")))?;
    let mu_s = result.mu_s.ok_or_else(|| {
        NodeError::new(format!(
            "no compressive net force on the summits (sum F_n = {} N, sum F_a = {} N): the section carries no friction",
            result.total_normal_force, result.total_adhesion_force
        ))
    })?;
    let area = on.nominal_area.unwrap_or(section_area);
    let mut metrics = coefficient_fields(mu_s).to_vec();
    push_forces(
        &mut metrics,
        &result,
        area / section_area,
        maps.nominal_pressure * area,
        maps.nominal_pressure,
    );
    if let (Some(sigma_s), Some(radius)) = (
        on.statistics.statistics.height_std,
        on.statistics.statistics.mean_radius,
    ) {
        metrics.push(dimensionless(
            names::PLASTICITY_INDEX,
            task.material.plasticity_index(sigma_s, radius),
        ));
    }
    push_counts(
        &mut metrics,
        &result,
        maps.area_fraction,
        area,
        section_area,
        on.summits.len(),
    );
    push_local_mu(&mut metrics, &result);
    Ok((metrics, contacts, result))
}

fn dimensionless(name: &'static str, v: f64) -> Field {
    Field::float(name, v, Dimension::Dimensionless)
}

/// The summits of the composite height the contact was solved on.
fn composite_summits(maps: &ContactView<'_>, periodic: bool) -> Result<Summits, NodeError> {
    let map = HeightMap::new(maps.composite_height.to_owned(), maps.dx, maps.dy)
        .map_err(|e| NodeError::new(format!("composite height: {e}")))?;
    find_summits(
        &map,
        SummitOptions {
            boundary: if periodic {
                Boundary::Periodic
            } else {
                Boundary::Open
            },
            min_height: None,
            min_prominence: None,
        },
    )
    .map_err(|e| NodeError::new(format!("summits: {e}")))
}

/// The section's forces scaled by `scale` (apparent / section area) to the apparent area, and
/// the contact's own load `contact_load` (N) at its nominal pressure (Pa).
fn push_forces(
    metrics: &mut Vec<Field>,
    result: &PerSummitResult,
    scale: f64,
    contact_load: f64,
    nominal_pressure: f64,
) {
    metrics.extend([
        beyond_fit_field(result.load_beyond_fit, result.total_normal_force),
        Field::float(
            names::EXTERNAL_LOAD,
            scale * (result.total_normal_force - result.total_adhesion_force),
            Dimension::Force,
        ),
        Field::float(
            names::NOMINAL_PRESSURE,
            nominal_pressure,
            Dimension::Pressure,
        ),
        Field::float(
            names::NORMAL_LOAD,
            scale * result.total_normal_force,
            Dimension::Force,
        ),
        Field::float(
            names::ADHESION_FORCE,
            scale * result.total_adhesion_force,
            Dimension::Force,
        ),
        Field::float(
            names::FRICTION_FORCE,
            scale * result.total_friction_force.max(0.0),
            Dimension::Force,
        ),
        Field::float(names::CONTACT_NORMAL_LOAD, contact_load, Dimension::Force),
        adhesion_share_field(result.total_adhesion_force, result.total_normal_force),
    ]);
}

/// Contact counts and areas, and the summits by deformation state.
fn push_counts(
    metrics: &mut Vec<Field>,
    result: &PerSummitResult,
    area_fraction: f64,
    area: f64,
    section_area: f64,
    summit_count: usize,
) {
    let [_, elastic, elastic_plastic, fully_plastic] = result.state_counts;
    let in_contact = elastic + elastic_plastic + fully_plastic;
    metrics.extend([
        dimensionless(names::CONTACTS, in_contact as f64),
        Field::float(names::REAL_AREA, area_fraction * area, Dimension::Area),
        dimensionless(names::AREA_FRACTION, area_fraction),
        Field::float(names::APPARENT_AREA, area, Dimension::Area),
        Field::float(names::SECTION_AREA, section_area, Dimension::Area),
        Field::int(names::SUMMIT_COUNT, summit_count as i64),
        Field::int(names::ELASTIC_SUMMITS, elastic as i64),
        Field::int(names::ELASTIC_PLASTIC_SUMMITS, elastic_plastic as i64),
        Field::int(names::FULLY_PLASTIC_SUMMITS, fully_plastic as i64),
    ]);
}

/// Load-weighted quantiles of the local μ_i = Q_i/(F_n − F_a)_i of the summits in contact, each
/// weighted by its net load (F_n − F_a)_i > 0 (the weights of μ_s = Σ Q_i / Σ (F_n − F_a)_i). A
/// negative local value (the literal KE 2004 Q_max on 4.29 < x ≤ 6) counts as 0.
fn push_local_mu(metrics: &mut Vec<Field>, result: &PerSummitResult) {
    let local: Vec<(f64, f64)> = result
        .summits
        .iter()
        .filter_map(|s| {
            s.local_mu
                .map(|m| (m.max(0.0), s.normal_force - s.adhesion_force))
        })
        .collect();
    super::per_spot::push_local_mu_quantiles(metrics, &local);
}

/// One row per summit: position, geometry, interference, state and forces (section values).
fn summits_table_of(
    summits: &[&Summit],
    contacts: &[SummitContact],
    forces: &[SummitFriction],
) -> Table {
    let rows: Vec<(&Summit, &SummitContact, &SummitFriction)> = summits
        .iter()
        .copied()
        .zip(contacts)
        .zip(forces)
        .map(|((s, c), f)| (s, c, f))
        .collect();
    let column = |f: &dyn Fn(&(&Summit, &SummitContact, &SummitFriction)) -> f64| {
        rows.iter().map(f).collect::<Vec<f64>>()
    };
    let mut t = Table::default();
    t.push_int(
        summit_columns::IX,
        rows.iter().map(|r| r.0.ix as i64).collect(),
    );
    t.push_int(
        summit_columns::IY,
        rows.iter().map(|r| r.0.iy as i64).collect(),
    );
    t.push_float(summit_columns::X, Dimension::Length, column(&|r| r.0.x));
    t.push_float(summit_columns::Y, Dimension::Length, column(&|r| r.0.y));
    t.push_float(
        summit_columns::HEIGHT,
        Dimension::Length,
        column(&|r| r.0.height),
    );
    t.push_float(
        summit_columns::RADIUS,
        Dimension::Length,
        column(&|r| r.0.radius),
    );
    t.push_float(
        summit_columns::INTERFERENCE,
        Dimension::Length,
        column(&|r| r.1.interference),
    );
    t.push_float(
        summit_columns::INTERFERENCE_RATIO,
        Dimension::Dimensionless,
        column(&|r| r.2.interference_ratio),
    );
    t.push_text(
        summit_columns::STATE,
        rows.iter()
            .map(|r| state_name(r.2.state).to_string())
            .collect(),
    );
    t.push_float(
        summit_columns::NORMAL_FORCE,
        Dimension::Force,
        column(&|r| r.2.normal_force),
    );
    t.push_float(
        summit_columns::ADHESION_FORCE,
        Dimension::Force,
        column(&|r| r.2.adhesion_force),
    );
    t.push_float(
        summit_columns::FRICTION_FORCE,
        Dimension::Force,
        column(&|r| r.2.friction_force.max(0.0)),
    );
    t
}
