//! The deformation part of static friction per contact spot, added to an adhesion part
//! (docs/friction-models.md, "Deformation part").
//!
//! Each spot `i` of a contact solution carries its load `P_i`, area `A_i` (hence
//! `a_i = √(A_i/π)`), paraboloid radius `R_i` ([`crate::friction::contact_spots`]), the tilt `tan θ_i` of
//! its junction plane along the sliding direction and its attack slope `tan α_i`
//! ([`super::spot_slope`]), and the tangential capacity `Q_a,i` an adhesion law gave it
//! ([`crate::friction::per_spot`]); `μ_a,i = Q_a,i/P_i`. A [`DeformationLaw`] adds a deformation force
//! `Q_d,i`:
//!
//! * **sphere ploughing** (additive split): `Q_d,i = μ_p(a_i/R_i) P_i`
//!   ([`super::closed_forms::sphere_ploughing`]); needs a convex radius;
//! * **cone ploughing** (additive split): `Q_d,i = (2/π) tan α_i · P_i`
//!   ([`super::closed_forms::cone_ploughing`]);
//! * **groove ploughing** (additive split): `Q_d,i = (2 A_side,i/A_i) P_i`, the Bowden–Tabor
//!   ratio of the spot's own cap along the sliding direction, of which the cone and the sphere
//!   are the closed forms;
//! * **tilted junction** (composition): `Q_i = P_i tan(φ_i + θ_i)`, `tan φ_i = μ_a,i`, so
//!   `Q_d,i = Q_i − Q_a,i` ([`super::closed_forms::tilted_junction`]); needs a plane.
//!
//! The additive split `μ = μ_adhesion + μ_deformation` is Bowden and Tabor's first
//! approximation (the two parts interact; they say so themselves); the tilted junction composes
//! the parts instead (the adhesion acts on the inclined plane), its deformation part is what the
//! tilt adds. Every spot is taken at its limit at once and keeps the normal load of the contact
//! solution (no redistribution of load between up- and down-slope spots under the tangential
//! load); a down-slope spot steeper than its friction angle then pushes forward (`Q_i < 0`).
//!
//! The section's coefficient is Coulomb's law for the whole section as in
//! [`crate::friction::per_spot`]: `μ_s = Σ(Q_a,i + Q_d,i)/(Σ P_i − F_a)`, split into
//! `μ_adhesion = Σ Q_a,i/(Σ P_i − F_a)` and `μ_deformation = Σ Q_d,i/(Σ P_i − F_a)`. A spot
//! without the geometry its law needs carries no deformation part (its number and load are
//! reported); so does a spot outside the law's range — a sphere cap with `a_i > R_i`, a locked
//! junction (`φ_i + θ_i ≥ 90°`) — then `μ_deformation` is a lower bound and the row says so.

use super::closed_forms::{cone_ploughing, sphere_ploughing, tilted_junction};
use crate::friction::error::FrictionError;
use crate::friction::laws::spot::contact_radius;

/// How the deformation part of a spot is computed (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DeformationLaw {
    /// A sphere of the spot's radius ploughing at the spot's contact radius.
    SpherePloughing,
    /// A cone of the spot's attack slope ploughing.
    ConePloughing,
    /// The spot's own cap ploughing along the sliding direction.
    GroovePloughing,
    /// The spot's junction inclined by its tilt along the sliding direction.
    TiltedJunction,
}

impl DeformationLaw {
    /// Every law with its name in studies and tables.
    pub const NAMED: [(&'static str, DeformationLaw); 4] = [
        ("groove", Self::GroovePloughing),
        ("cone", Self::ConePloughing),
        ("sphere", Self::SpherePloughing),
        ("tilted_junction", Self::TiltedJunction),
    ];

    /// The law called `name` in [`Self::NAMED`].
    pub fn named(name: &str) -> Option<Self> {
        Self::NAMED
            .iter()
            .find(|(n, _)| *n == name)
            .map(|&(_, law)| law)
    }
}

/// One contact spot as the deformation laws need it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DeformationSpot {
    /// Normal load P_i (N).
    pub load: f64,
    /// Contact area A_i (m²).
    pub area: f64,
    /// Radius R_i of the composite topography (m); `None`: not convex.
    pub radius: Option<f64>,
    /// `tan θ_i` of the junction plane along the sliding direction; `None`: no plane.
    pub tilt: Option<f64>,
    /// `tan α_i` from the highest point to the boundary; `None`: no boundary.
    pub attack_slope: Option<f64>,
    /// `2 A_side,i/A_i` along the sliding direction; `None`: no boundary.
    pub groove_ratio: Option<f64>,
    /// Tangential capacity of the adhesion law Q_a,i (N).
    pub adhesion_friction: f64,
}

/// Why a spot carries no deformation part.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unassigned {
    /// The law needs a radius, plane or attack slope the spot does not have.
    NoGeometry,
    /// The spot lies outside the law's range (`a > R`, or a locked junction).
    OutOfRange,
}

/// The deformation part of one spot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpotDeformation {
    /// Deformation force Q_d,i (N); 0 when unassigned.
    pub deformation_friction: f64,
    /// `Some` when the spot carries no deformation part, and why.
    pub unassigned: Option<Unassigned>,
}

/// The deformation model of a section.
#[derive(Debug, Clone, PartialEq)]
pub struct DeformationResult {
    /// One entry per input spot.
    pub spots: Vec<SpotDeformation>,
    /// Σ P_i (N).
    pub total_normal_force: f64,
    /// Σ Q_a,i (N).
    pub adhesion_friction: f64,
    /// Σ Q_d,i (N).
    pub deformation_friction: f64,
    /// Adhesion force F_a of the section (N, attractive positive).
    pub adhesion_force: f64,
    /// `Σ Q_a,i/(Σ P_i − F_a)`; `None` when the denominator is not positive.
    pub mu_adhesion: Option<f64>,
    /// `Σ Q_d,i/(Σ P_i − F_a)`; `None` when the denominator is not positive.
    pub mu_deformation: Option<f64>,
    /// Their sum; `None` when the denominator is not positive.
    pub mu_s: Option<f64>,
    /// Spots without the geometry the law needs, and their load (N).
    pub spots_without_geometry: usize,
    /// Σ P_i of those spots (N).
    pub load_without_geometry: f64,
    /// Spots outside the law's range.
    pub spots_out_of_range: usize,
    /// Σ P_i of those spots (N).
    pub load_out_of_range: f64,
}

impl DeformationLaw {
    /// Q_d of one spot, or why it has none (inputs as checked by [`deformation_friction`]).
    pub fn spot_deformation(self, spot: &DeformationSpot) -> Result<f64, Unassigned> {
        match self {
            Self::SpherePloughing => {
                let radius = spot.radius.ok_or(Unassigned::NoGeometry)?;
                let mu = sphere_ploughing(contact_radius(spot.area) / radius)
                    .ok_or(Unassigned::OutOfRange)?;
                Ok(mu * spot.load)
            }
            Self::ConePloughing => {
                let attack = spot.attack_slope.ok_or(Unassigned::NoGeometry)?;
                Ok(cone_ploughing(attack) * spot.load)
            }
            Self::GroovePloughing => {
                Ok(spot.groove_ratio.ok_or(Unassigned::NoGeometry)? * spot.load)
            }
            Self::TiltedJunction => {
                let tilt = spot.tilt.ok_or(Unassigned::NoGeometry)?;
                if spot.load <= 0.0 {
                    return Ok(0.0);
                }
                let mu = tilted_junction(spot.adhesion_friction / spot.load, tilt)
                    .ok_or(Unassigned::OutOfRange)?;
                Ok(mu * spot.load - spot.adhesion_friction)
            }
        }
    }
}

/// The deformation model of a section: `spots` under `law`, with the section's adhesion force
/// `adhesion_force` (N, ≥ 0). Errors on a non-finite or negative load, area, attack slope or
/// groove ratio, a non-finite adhesion capacity or tilt.
pub fn deformation_friction(
    spots: &[DeformationSpot],
    law: DeformationLaw,
    adhesion_force: f64,
) -> Result<DeformationResult, FrictionError> {
    let mut result = DeformationResult {
        spots: Vec::with_capacity(spots.len()),
        total_normal_force: 0.0,
        adhesion_friction: 0.0,
        deformation_friction: 0.0,
        adhesion_force,
        mu_adhesion: None,
        mu_deformation: None,
        mu_s: None,
        spots_without_geometry: 0,
        load_without_geometry: 0.0,
        spots_out_of_range: 0,
        load_out_of_range: 0.0,
    };
    for spot in spots {
        check_spot(spot)?;
        let spot = DeformationSpot {
            radius: spot.radius.filter(|r| r.is_finite() && *r > 0.0),
            ..*spot
        };
        let (deformation_friction, unassigned) = match law.spot_deformation(&spot) {
            Ok(q) => (q, None),
            Err(why) => {
                let (count, load) = match why {
                    Unassigned::NoGeometry => (
                        &mut result.spots_without_geometry,
                        &mut result.load_without_geometry,
                    ),
                    Unassigned::OutOfRange => (
                        &mut result.spots_out_of_range,
                        &mut result.load_out_of_range,
                    ),
                };
                *count += 1;
                *load += spot.load;
                (0.0, Some(why))
            }
        };
        result.total_normal_force += spot.load;
        result.adhesion_friction += spot.adhesion_friction;
        result.deformation_friction += deformation_friction;
        result.spots.push(SpotDeformation {
            deformation_friction,
            unassigned,
        });
    }
    let net = result.total_normal_force - adhesion_force;
    if net > 0.0 {
        result.mu_adhesion = Some(result.adhesion_friction / net);
        result.mu_deformation = Some(result.deformation_friction / net);
        result.mu_s = Some((result.adhesion_friction + result.deformation_friction) / net);
    }
    Ok(result)
}

fn check_spot(spot: &DeformationSpot) -> Result<(), FrictionError> {
    for (name, value) in [("spot load", spot.load), ("spot area", spot.area)] {
        if !(value.is_finite() && value >= 0.0) {
            return Err(FrictionError::InvalidParameter {
                name,
                value,
                expected: "a finite value >= 0",
            });
        }
    }
    let finite = [
        ("spot adhesion friction", Some(spot.adhesion_friction)),
        ("spot tilt", spot.tilt),
    ];
    for (name, value) in finite {
        if let Some(value) = value.filter(|v| !v.is_finite()) {
            return Err(FrictionError::InvalidParameter {
                name,
                value,
                expected: "a finite value",
            });
        }
    }
    let non_negative = [
        ("spot attack slope", spot.attack_slope),
        ("spot groove ratio", spot.groove_ratio),
    ];
    for (name, value) in non_negative {
        if let Some(value) = value.filter(|v| !(v.is_finite() && *v >= 0.0)) {
            return Err(FrictionError::InvalidParameter {
                name,
                value,
                expected: "a finite value >= 0",
            });
        }
    }
    Ok(())
}
