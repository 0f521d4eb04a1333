//! The columns of a per-spot law with a deformation part (`model: ploughing`): the section's
//! coefficient split into its adhesion and deformation parts, the load-weighted geometry of the
//! spots along the sliding direction, and the spots table's geometry and deformation columns
//! ([`crate::friction::spot_slope`], docs/friction-models.md "Deformation part").

use crate::engine::artifact::Table;
use crate::engine::value::Field;
use crate::friction::contact_spots::ContactSpot;
use crate::friction::laws::spot::contact_radius;
use crate::friction::{PerSpotResult, SpotSlope};
use crate::units::Dimension;
use crate::vocabulary::{metrics as names, spot_columns};

/// `mu_adhesion` and `mu_deformation` (their sum is `mu_s_computed`, both over Σ P_i − F_a as
/// computed), and the load-weighted means of the spots' |tilt|, attack slope and groove ratio.
pub(super) fn push_parts(
    metrics: &mut Vec<Field>,
    spots: &[ContactSpot],
    slopes: &[SpotSlope],
    result: &PerSpotResult,
) {
    let net = result.total_normal_force - result.adhesion_force;
    let n = |name: &'static str, v: f64| Field::float(name, v, Dimension::Dimensionless);
    let deformation = result.total_deformation_force;
    metrics.extend([
        n(
            names::MU_ADHESION,
            (result.total_friction_force - deformation) / net,
        ),
        n(names::MU_DEFORMATION, deformation / net),
    ]);
    let mean = |f: &dyn Fn(&SpotSlope) -> Option<f64>| {
        let (mut sum, mut load) = (0.0, 0.0);
        for (spot, slope) in spots.iter().zip(slopes) {
            if let Some(v) = f(slope) {
                sum += v * spot.load;
                load += spot.load;
            }
        }
        if load > 0.0 {
            sum / load
        } else {
            0.0
        }
    };
    metrics.extend([
        n(names::SPOT_TILT_ABS_MEAN, mean(&|s| s.tilt.map(f64::abs))),
        n(names::SPOT_ATTACK_SLOPE_MEAN, mean(&|s| s.attack_slope)),
        n(names::SPOT_GROOVE_RATIO_MEAN, mean(&|s| s.groove_ratio)),
    ]);
}

/// Per spot: tilt along the sliding direction and how its plane was fitted, attack slope, groove
/// ratio, cap height, contact radius, deformation force and local deformation coefficient
/// (0 where a value is undefined: `plane` says `none`, or the spot covers a periodic grid).
pub(super) fn extend_spots_table(
    t: &mut Table,
    spots: &[ContactSpot],
    slopes: &[SpotSlope],
    result: &PerSpotResult,
) {
    let column = |f: &dyn Fn(&SpotSlope) -> Option<f64>| {
        slopes
            .iter()
            .map(|s| f(s).unwrap_or(0.0))
            .collect::<Vec<f64>>()
    };
    t.push_float(
        spot_columns::TILT,
        Dimension::Dimensionless,
        column(&|s| s.tilt),
    );
    t.push_text(
        spot_columns::PLANE,
        slopes
            .iter()
            .map(|s| {
                String::from(match (s.gradient, s.dilated) {
                    (None, _) => "none",
                    (Some(_), true) => "dilated",
                    (Some(_), false) => "footprint",
                })
            })
            .collect(),
    );
    t.push_float(
        spot_columns::ATTACK_SLOPE,
        Dimension::Dimensionless,
        column(&|s| s.attack_slope),
    );
    t.push_float(
        spot_columns::GROOVE_RATIO,
        Dimension::Dimensionless,
        column(&|s| s.groove_ratio),
    );
    t.push_float(
        spot_columns::CAP_HEIGHT,
        Dimension::Length,
        column(&|s| s.cap_height),
    );
    t.push_float(
        spot_columns::CONTACT_RADIUS,
        Dimension::Length,
        spots.iter().map(|s| contact_radius(s.area)).collect(),
    );
    t.push_float(
        spot_columns::DEFORMATION_FORCE,
        Dimension::Force,
        result.deformation.clone(),
    );
    t.push_float(
        spot_columns::LOCAL_MU_DEFORMATION,
        Dimension::Dimensionless,
        spots
            .iter()
            .zip(&result.deformation)
            .map(|(s, q)| if s.load > 0.0 { q / s.load } else { 0.0 })
            .collect(),
    );
}
