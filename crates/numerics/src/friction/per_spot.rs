//! Static friction per contact spot of a contact solution (the deterministic stage 3 of the
//! reference workflow on a boundary-element result; project reference
//! `docs/friction-models.md`, "Per contact spot").
//!
//! A contact spot is a connected set of points with p > 0 ([`super::contact_spots`]); its load
//! P_i = Σ p dA and area A_i are exact results of the contact solution and its radius R_i comes
//! from the composite topography ([`SpotLoad`]). This file only sums a section: each spot gets
//! the tangential capacity Q_i of the chosen law ([`FrictionLaw::spot_friction`]), e.g.:
//!
//! * **full stick**: Q_i = μ(P_i*) P_i with P_i* = P_i/L_c(R_i), L_c = L̄_c P_c(R_i)
//!   ([`super::laws::full_stick`]);
//! * **junction shear** (Bowden–Tabor): Q_i = τ_s A_i, every junction fails in shear at the
//!   interfacial shear strength τ_s; no radius is needed;
//! * **Kogut–Etsion / CEB**: the interference x_i that gives P_i under the model's load law
//!   (smallest x with P_c(R_i)·(P/P_c)(x) ≥ P_i; the laws rise monotonically with upward jumps),
//!   then Q_i = P_c(R_i)·(Q/P_c)(x_i).
//!
//! The section's coefficient is Coulomb's law for the whole section,
//! μ_s = Σ Q_i / (Σ P_i − F_a), with F_a the adhesion of the section (from the gap around the
//! spots, [`super::contact_spots::adhesion_from_gap`]); the local μ_i = Q_i/P_i. A spot whose
//! topography gives no convex radius cannot be assigned a radius-dependent law: it carries no Q
//! (a lower bound) and its load is reported (`load_without_radius`). Spots beyond the validated
//! range of the law add their load to `load_beyond_fit`: full stick P_i* above the stick load fit
//! at ω* = 110; KE/CEB x_i above the fit limit of their asperity laws; junction shear has no fitted
//! range. One-pixel spots are resolution-limited: their number and load are reported.

use super::error::FrictionError;
use super::laws::law::FrictionLaw;
use super::laws::spot::{SpotFriction, SpotLoad, SpotSlope};

/// The per-spot result of a section.
#[derive(Debug, Clone, PartialEq)]
pub struct PerSpotResult {
    /// One entry per input spot.
    pub spots: Vec<SpotFriction>,
    /// Σ P_i (N).
    pub total_normal_force: f64,
    /// Σ Q_i (N).
    pub total_friction_force: f64,
    /// Σ A_i (m²).
    pub total_area: f64,
    /// Adhesion force F_a of the section (N, attractive positive).
    pub adhesion_force: f64,
    /// μ_s = Σ Q_i / (Σ P_i − F_a); `None` when the denominator is not positive.
    pub mu_s: Option<f64>,
    /// Σ P_i of the spots beyond the law's validated range (N).
    pub load_beyond_fit: f64,
    /// Σ P_i of the spots without a convex radius (N; they carry no Q).
    pub load_without_radius: f64,
    /// Number of spots without a convex radius.
    pub spots_without_radius: usize,
    /// Σ P_i of the one-pixel spots (N).
    pub load_one_pixel: f64,
    /// Number of one-pixel spots.
    pub one_pixel_spots: usize,
    /// The deformation part Q_d,i of each spot's Q_i (N), for a law with one
    /// ([`per_spot_friction_on_slopes`]); empty otherwise.
    pub deformation: Vec<f64>,
    /// Σ Q_d,i (N).
    pub total_deformation_force: f64,
}

/// The per-spot model of a section: `spots` with the section's adhesion force `adhesion_force`
/// (N, ≥ 0). Errors on a non-finite or negative spot load or area.
pub fn per_spot_friction(
    spots: &[SpotLoad],
    law: &dyn FrictionLaw,
    adhesion_force: f64,
) -> Result<PerSpotResult, FrictionError> {
    section_friction(spots, None, law, adhesion_force)
}

/// [`per_spot_friction`] for a law with a deformation part: each spot with its geometry along
/// the law's sliding direction (`slopes[i]` of `spots[i]`, [`super::laws::ploughing::spot_slope::spot_slopes`]),
/// [`FrictionLaw::sloped_spot_friction`]; the deformation parts are summed apart. Errors also
/// when the lists differ in length.
pub fn per_spot_friction_on_slopes(
    spots: &[SpotLoad],
    slopes: &[SpotSlope],
    law: &dyn FrictionLaw,
    adhesion_force: f64,
) -> Result<PerSpotResult, FrictionError> {
    if slopes.len() != spots.len() {
        return Err(FrictionError::InvalidParameter {
            name: "spot slopes",
            value: slopes.len() as f64,
            expected: "one slope per spot",
        });
    }
    section_friction(spots, Some(slopes), law, adhesion_force)
}

fn section_friction(
    spots: &[SpotLoad],
    slopes: Option<&[SpotSlope]>,
    law: &dyn FrictionLaw,
    adhesion_force: f64,
) -> Result<PerSpotResult, FrictionError> {
    let mut result = PerSpotResult {
        spots: Vec::with_capacity(spots.len()),
        total_normal_force: 0.0,
        total_friction_force: 0.0,
        total_area: 0.0,
        adhesion_force,
        mu_s: None,
        load_beyond_fit: 0.0,
        load_without_radius: 0.0,
        spots_without_radius: 0,
        load_one_pixel: 0.0,
        one_pixel_spots: 0,
        deformation: Vec::new(),
        total_deformation_force: 0.0,
    };
    for (i, spot) in spots.iter().enumerate() {
        check_spot(spot)?;
        let usable = SpotLoad {
            radius: spot.radius.filter(|r| r.is_finite() && *r > 0.0),
            ..*spot
        };
        let found = match slopes {
            Some(slopes) => law.sloped_spot_friction(&usable, &slopes[i]),
            None => law.spot_friction(&usable).map(|f| (f, 0.0)),
        };
        let (friction, deformation) = found.unwrap_or_else(|| {
            result.load_without_radius += spot.load;
            result.spots_without_radius += 1;
            let none = SpotFriction {
                friction_force: 0.0,
                load_measure: None,
                beyond_fit: false,
            };
            (none, 0.0)
        });
        if friction.beyond_fit {
            result.load_beyond_fit += spot.load;
        }
        if spot.pixels == 1 {
            result.load_one_pixel += spot.load;
            result.one_pixel_spots += 1;
        }
        result.total_normal_force += spot.load;
        result.total_friction_force += friction.friction_force;
        result.total_area += spot.area;
        result.spots.push(friction);
        if slopes.is_some() {
            result.deformation.push(deformation);
            result.total_deformation_force += deformation;
        }
    }
    let net = result.total_normal_force - adhesion_force;
    result.mu_s = (net > 0.0).then(|| result.total_friction_force / net);
    Ok(result)
}

fn check_spot(spot: &SpotLoad) -> Result<(), FrictionError> {
    for (name, value) in [("spot load", spot.load), ("spot area", spot.area)] {
        if !(value.is_finite() && value >= 0.0) {
            return Err(FrictionError::InvalidParameter {
                name,
                value,
                expected: "a finite value >= 0",
            });
        }
    }
    Ok(())
}
