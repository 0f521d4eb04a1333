//! `method: statistical`: KE 2004 / CEB / full-stick static friction on Greenwood–Williamson
//! summit statistics.
//!
//! Roughness: explicit, or Nayak/McCool summit statistics from the isotropic profile moments
//! m0, m2, m4 of the upstream surface(s) (`surfaces` metrics `m0_m2`, `m2`, `m4_per_m2`); two
//! surfaces are combined by adding moments (the equivalent sum surface). Nominal area: explicit or
//! the lower surface's `nx·dx · ny·dy`. Loads: each nominal pressure times A_n, each force, or the
//! nominal pressure of each load step of the upstream contact times A_n. Listed loads share one
//! net-load grid (`friction::static_friction_curve`); a contact's steps are solved each on its
//! own (the final one as when it was the only load). The row is at the **last** load (as the
//! contact node's row is at its last step) and `friction_curve` has one row per load
//! (`steps`). A load the model cannot carry fails the node with the library's message naming
//! the load.

use crate::engine::artifact::Artifact;
use crate::engine::node::NodeError;
use crate::engine::value::Field;
use crate::friction::{
    static_friction_curve, AdhesionBeyondFits, SolveSettings, SpectralMoments,
    StaticFrictionResult, StatisticalModel, SummitStatistics,
};
use crate::nodes::contact_view::step_nominal_pressures;
use crate::nodes::surface_view::SurfaceView;
use crate::units::Dimension;
use crate::vocabulary::{metrics as names, roles};

use super::{
    adhesion_share_field, beyond_fit_field, coefficient_fields, input, FrictionTask, Loads,
    Roughness,
};

fn moments(surface: &Artifact, role: &str) -> Result<SpectralMoments, NodeError> {
    let view = SurfaceView::of(surface, role)?;
    crate::nodes::validity::cross::moments_grid(view.nx, view.ny).map_err(NodeError::new)?;
    let (m0, m2, m4) = view.moments.ok_or_else(|| {
        NodeError::new(format!(
            "{role} surface has no spectral moments (maps with missing points have none: fill \
             them with `fill_missing: true`)"
        ))
    })?;
    SpectralMoments::new(m0, m2, m4)
        .map_err(|e| NodeError::new(format!("{role} surface moments: {e}")))
}

fn surface_area(surface: &Artifact) -> Result<f64, NodeError> {
    Ok(SurfaceView::of(surface, roles::LOWER)?.area())
}

/// The summit statistics and the nominal area of the node.
fn roughness_and_area(
    inputs: &[&Artifact],
    roughness: &Roughness,
    nominal_area: Option<f64>,
) -> Result<(SummitStatistics, f64), NodeError> {
    match roughness {
        Roughness::Explicit(s) => {
            let area = nominal_area
                .ok_or_else(|| NodeError::new("explicit roughness needs a nominal area"))?;
            Ok((*s, area))
        }
        Roughness::Surfaces { lower, upper } => {
            let lower_surface = input(inputs, *lower, roles::LOWER)?;
            let mut m = moments(lower_surface, roles::LOWER)?;
            if let Some(u) = upper {
                m = m.combined_with(&moments(input(inputs, *u, roles::UPPER)?, roles::UPPER)?);
            }
            let summits = SummitStatistics::from_spectral_moments(&m)
                .map_err(|e| NodeError::new(format!("summit statistics: {e}")))?;
            let area = match nominal_area {
                Some(a) => a,
                None => surface_area(lower_surface)?,
            };
            Ok((summits, area))
        }
    }
}

/// The metrics at each load (the last the row's).
pub(super) fn compute(
    task: &FrictionTask,
    inputs: &[&Artifact],
    roughness: &Roughness,
    nominal_area: Option<f64>,
    loads: &Loads,
) -> Result<Vec<Vec<Field>>, NodeError> {
    let (summits, area) = roughness_and_area(inputs, roughness, nominal_area)?;
    let model = StatisticalModel::new(
        task.asperity_laws()?,
        summits,
        task.material,
        task.adhesion,
        area,
        AdhesionBeyondFits::default(),
    )
    .map_err(|e| NodeError::new(format!("friction model: {e}")))?;
    let results = match loads {
        Loads::Pressures(p) => {
            let forces: Vec<f64> = p.iter().map(|p| p * area).collect();
            solve_each_load(&model, &forces, area)?
        }
        Loads::Forces(f) => solve_each_load(&model, f, area)?,
        // Each step of the contact alone: the final one as when it was the only load.
        Loads::FromContact(c) => {
            let pressures = step_nominal_pressures(input(inputs, *c, roles::CONTACT)?)?;
            let mut results = Vec::with_capacity(pressures.len());
            for p in pressures {
                results.extend(solve_each_load(&model, &[p * area], area)?);
            }
            results
        }
    };
    results
        .iter()
        .map(|r| {
            let mu_s = r.mu_s.ok_or_else(|| {
                NodeError::new(format!(
                    "no static friction coefficient at the non-compressive load {} N",
                    r.external_load
                ))
            })?;
            let mut metrics = coefficient_fields(mu_s).to_vec();
            metrics.extend(result_fields(r, &summits, area));
            Ok(metrics)
        })
        .collect()
}

/// The static friction at each external load (N), with an error naming the load that failed.
fn solve_each_load(
    model: &StatisticalModel,
    forces: &[f64],
    area: f64,
) -> Result<Vec<StaticFrictionResult>, NodeError> {
    static_friction_curve(model, forces, &SolveSettings::default())
        .map_err(|e| NodeError::new(format!("friction solve: {e}")))?
        .into_iter()
        .zip(forces)
        .map(|(r, f)| {
            r.map_err(|e| {
                NodeError::new(format!(
                    "friction solve at load {} N (nominal pressure {} Pa): {e}",
                    crate::units::format_number(*f),
                    crate::units::format_number(f / area)
                ))
            })
        })
        .collect()
}

/// The row of the last load: forces, separation, contact, the summit statistics the model used
/// and the solve's diagnostics.
fn result_fields(last: &StaticFrictionResult, summits: &SummitStatistics, area: f64) -> Vec<Field> {
    let n = |name: &'static str, v: f64| Field::float(name, v, Dimension::Dimensionless);
    vec![
        beyond_fit_field(last.load_beyond_fit, last.contact_load),
        Field::float(names::EXTERNAL_LOAD, last.external_load, Dimension::Force),
        Field::float(
            names::NOMINAL_PRESSURE,
            last.external_load / area,
            Dimension::Pressure,
        ),
        Field::float(names::NORMAL_LOAD, last.contact_load, Dimension::Force),
        Field::float(names::ADHESION_FORCE, last.adhesion_force, Dimension::Force),
        adhesion_share_field(last.adhesion_force, last.contact_load),
        Field::float(
            names::FRICTION_FORCE,
            last.static_friction_force.max(0.0),
            Dimension::Force,
        ),
        Field::float(
            names::SEPARATION,
            last.separation_from_heights,
            Dimension::Length,
        ),
        n(names::D_STAR, last.d_star),
        n(names::PLASTICITY_INDEX, last.plasticity_index),
        n(names::CONTACTS, last.contacting_summits),
        Field::float(names::REAL_AREA, last.real_contact_area, Dimension::Area),
        n(names::AREA_FRACTION, last.real_contact_area / area),
        Field::float(names::APPARENT_AREA, area, Dimension::Area),
        Field::float(names::GW_SIGMA, summits.sigma, Dimension::Length),
        Field::float(names::GW_SIGMA_S, summits.sigma_s, Dimension::Length),
        Field::float(names::GW_SUMMIT_RADIUS, summits.radius, Dimension::Length),
        Field::float(
            names::GW_SUMMIT_DENSITY,
            summits.density,
            Dimension::InverseArea,
        ),
        n(names::GW_BETA, summits.beta),
        Field::int(names::ROOTS_FOUND, last.status.roots_found as i64),
        Field::int(names::ITERATIONS, last.status.brent_iterations as i64),
        n(names::RESIDUAL, last.status.relative_residual),
        n(
            names::INTEGRAL_ERROR,
            last.status.max_integral_relative_error,
        ),
    ]
}
