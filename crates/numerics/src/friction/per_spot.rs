//! Static friction per contact spot of a contact solution (the deterministic stage 3 of the
//! reference workflow on a boundary-element result; project reference
//! `docs/friction-models.md`, "Per contact spot").
//!
//! A contact spot is a connected set of points with p > 0 ([`super::contact_spots`]); its load
//! P_i = Σ p dA and area A_i are exact results of the contact solution and its radius R_i comes
//! from the composite topography. Each spot gets the tangential capacity Q_i of the chosen law
//! ([`FrictionLaw::spot_friction`]), e.g.:
//!
//! * **full stick**: Q_i = μ(P_i*) P_i with P_i* = P_i/L_c(R_i), L_c = L̄_c P_c(R_i)
//!   ([`super::full_stick`]);
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
//! at ω* = 110; KE/CEB x_i above [`AsperityLaws::fit_limit`]; junction shear has no fitted
//! range. One-pixel spots are resolution-limited: their number and load are reported.

use super::contact_spots::ContactSpot;
use super::error::FrictionError;
use super::laws::{AsperityLaws, FrictionLaw};
use super::material::Material;
use super::spot_slope::SpotSlope;

/// One contact spot as the per-spot model needs it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpotLoad {
    /// Normal load P_i = Σ p dA (N).
    pub load: f64,
    /// Contact area A_i (m²).
    pub area: f64,
    /// Radius of the composite topography at the spot (m); `None`: not convex.
    pub radius: Option<f64>,
    /// Number of grid points in the spot.
    pub pixels: usize,
}

/// Friction of one spot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpotFriction {
    /// Tangential capacity Q_i (N).
    pub friction_force: f64,
    /// Dimensionless load P_i* = P_i/L_c (full stick), x_i (KE/CEB); `None` otherwise.
    pub load_measure: Option<f64>,
    /// Whether the spot lies beyond the validated range of the law.
    pub beyond_fit: bool,
}

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

impl From<&ContactSpot> for SpotLoad {
    fn from(spot: &ContactSpot) -> Self {
        Self {
            load: spot.load,
            area: spot.area,
            radius: spot.radius,
            pixels: spot.pixels,
        }
    }
}

/// Q and x of one spot under an interference-driven law (Kogut–Etsion, CEB): the interference
/// x_i that gives P_i under the law's load law (smallest x with P_c(R_i)·(P/P_c)(x) ≥ P_i), then
/// Q_i = P_c(R_i)·(Q/P_c)(x_i); beyond the fit when x_i exceeds [`AsperityLaws::fit_limit`].
/// `None` without a radius.
pub fn interference_spot_friction(
    laws: &dyn AsperityLaws,
    material: &Material,
    spot: &SpotLoad,
) -> Option<SpotFriction> {
    let critical = material.critical_values(spot.radius?).load;
    let x = interference_for_load(laws, spot.load / critical);
    Some(SpotFriction {
        friction_force: critical * laws.friction_ratio(x),
        load_measure: Some(x),
        beyond_fit: x > laws.fit_limit(),
    })
}

/// The smallest x with (P/P_c)(x) ≥ `load_ratio` (bisection to rounding; the load laws of KE and
/// CEB rise monotonically with upward jumps).
pub fn interference_for_load(laws: &dyn AsperityLaws, load_ratio: f64) -> f64 {
    if load_ratio <= 0.0 {
        return 0.0;
    }
    let mut hi = 1.0;
    while laws.load_ratio(hi) < load_ratio && hi < 1e300 {
        hi *= 2.0;
    }
    let mut lo = 0.0;
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if laws.load_ratio(mid) >= load_ratio {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
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
/// the law's sliding direction (`slopes[i]` of `spots[i]`, [`super::spot_slope::spot_slopes`]),
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
