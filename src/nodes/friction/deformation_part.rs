//! The columns of a per-spot law with a deformation part (`model: ploughing`): the section's
//! coefficient split into its adhesion and deformation parts, the topography-only baseline of
//! the deformation part, which body ploughs, the load share beyond the ploughing regime, the
//! load-weighted geometry of the spots' loaded fronts, and the spots table's front and
//! deformation columns ([`crate::friction::laws::ploughing`], docs/friction-models.md
//! "Deformation part").

use crate::engine::artifact::Table;
use crate::engine::value::Field;
use crate::friction::contact_spots::ContactSpot;
use crate::friction::{FrontGeometry, PerSpotResult, SectionGeometry, SpotGeometry};
use crate::units::Dimension;
use crate::vocabulary::{metrics as names, spot_columns};

use super::share;

/// The share-weighted mean of `f` over a spot's ploughing bodies with a front (`None`: none).
fn front_mean(geometry: &SpotGeometry, f: &dyn Fn(&FrontGeometry) -> f64) -> Option<f64> {
    let (mut sum, mut weight) = (0.0, 0.0);
    for (share, front) in geometry.ploughers() {
        if let Some(front) = front {
            sum += share * f(front);
            weight += share;
        }
    }
    (weight > 0.0).then(|| sum / weight)
}

/// `mu_adhesion` and `mu_deformation` (their sum is `mu_s_computed`, both over Σ P_i − F_a as
/// computed), the baseline, the ploughing body, the regime share and the load-weighted means of
/// the fronts' attack slope, groove ratio and degree of penetration.
pub(super) fn push_parts(
    metrics: &mut Vec<Field>,
    spots: &[ContactSpot],
    geometry: &SectionGeometry,
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
        n(
            names::MU_DEFORMATION_SLOPE_BASELINE,
            geometry.slope_baseline,
        ),
        n(
            names::LOAD_SHARE_OUTSIDE_REGIME,
            share(result.load_outside_regime, result.total_normal_force),
        ),
    ]);
    let mean = |f: &dyn Fn(&FrontGeometry) -> f64| {
        let (mut sum, mut load) = (0.0, 0.0);
        for (spot, g) in spots.iter().zip(&geometry.spots) {
            if let Some(v) = front_mean(g, f) {
                sum += v * spot.load;
                load += spot.load;
            }
        }
        share(sum, load)
    };
    metrics.extend([
        n(names::SPOT_ATTACK_SLOPE_MEAN, mean(&|f| f.attack_slope)),
        n(names::SPOT_GROOVE_RATIO_MEAN, mean(&|f| f.groove_ratio)),
        n(names::SPOT_PENETRATION_MEAN, mean(&|f| f.penetration)),
    ]);
}

/// Per spot, share-weighted over its ploughing bodies' fronts: attack slope, groove ratio, cap
/// height, front area and radius, degree of penetration (0 where no front was measured: a spot
/// covering a periodic grid), and the deformation force, its local coefficient and the regime.
pub(super) fn extend_spots_table(
    t: &mut Table,
    geometry: &SectionGeometry,
    result: &PerSpotResult,
) {
    let column = |f: &dyn Fn(&FrontGeometry) -> f64| {
        geometry
            .spots
            .iter()
            .map(|g| front_mean(g, f).unwrap_or(0.0))
            .collect::<Vec<f64>>()
    };
    let dimensionless = Dimension::Dimensionless;
    t.push_float(
        spot_columns::ATTACK_SLOPE,
        dimensionless,
        column(&|f| f.attack_slope),
    );
    t.push_float(
        spot_columns::GROOVE_RATIO,
        dimensionless,
        column(&|f| f.groove_ratio),
    );
    t.push_float(
        spot_columns::CAP_HEIGHT,
        Dimension::Length,
        column(&|f| f.cap_height),
    );
    t.push_float(
        spot_columns::FRONT_AREA,
        Dimension::Area,
        column(&|f| f.front_area),
    );
    t.push_float(
        spot_columns::FRONT_RADIUS,
        Dimension::Length,
        column(&|f| f.front_radius),
    );
    t.push_float(
        spot_columns::PENETRATION,
        dimensionless,
        column(&|f| f.penetration),
    );
    let spots = &result.spots;
    t.push_float(
        spot_columns::DEFORMATION_FORCE,
        Dimension::Force,
        spots.iter().map(|s| s.deformation_force).collect(),
    );
    t.push_text(
        spot_columns::REGIME,
        spots
            .iter()
            .map(|s| {
                String::from(if s.outside_regime {
                    "beyond"
                } else {
                    "ploughing"
                })
            })
            .collect(),
    );
}
