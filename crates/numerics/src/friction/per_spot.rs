//! Static friction per contact spot of a contact solution (the deterministic stage 3 of the
//! reference workflow on a boundary-element result; project reference
//! `docs/friction-models.md`, "Per contact spot"). [`per_spot_friction`] is the one call a study's
//! node and the Python binding make: spots, adhesion, the ploughing geometry of a law with a
//! sliding direction, the law per spot and the section's sums.
//!
//! A contact spot is a connected set of points with p > 0 ([`super::contact_spots`]); its load
//! P_i = Σ p dA and area A_i are exact results of the contact solution and its radius R_i comes
//! from the composite topography ([`SpotLoad`]). Each spot gets the tangential capacity Q_i of
//! the chosen law ([`FrictionLaw::spot_friction`]), e.g.:
//!
//! * **full stick**: Q_i = μ(P_i*) P_i with P_i* = P_i/L_c(R_i), L_c = L̄_c P_c(R_i)
//!   ([`super::laws::full_stick`]);
//! * **junction shear** (Bowden–Tabor): Q_i = τ_s A_i, every junction fails in shear at the
//!   interfacial shear strength τ_s; no radius is needed;
//! * **Kogut–Etsion / CEB**: the interference x_i that gives P_i under the model's load law,
//!   then Q_i = P_c(R_i)·(Q/P_c)(x_i) ([`super::laws::interference`]);
//! * **ploughing**: junction shear plus the deformation part of the harder body's asperity on
//!   the spot's loaded front ([`super::laws::ploughing`], the bodies in [`super::bodies`]).
//!
//! The section's coefficient is Coulomb's law for the whole section,
//! μ_s = Σ Q_i / (Σ P_i − F_a), with F_a the adhesion of the section (from the gap around the
//! spots, [`super::contact_spots::adhesion_from_gap`]); the local μ_i = Q_i/P_i. What the sums
//! say about trust, each as the load it concerns: spots whose topography gives no convex radius
//! carry no Q under a radius-dependent law (a lower bound, `load_without_radius`); spots beyond
//! the validated range of the law (`load_beyond_fit`: full stick P_i* above the stick load fit at
//! ω* = 110, KE/CEB x_i above their fit limit, ploughing without the geometry its law needs);
//! merged spots under a law that rests on one asperity's radius (`load_merged`: two or more
//! summits of the composite topography in one spot, so no single radius describes it); spots
//! beyond the ploughing regime (`load_outside_regime`); one-pixel spots (resolution-limited).

use ndarray::ArrayView2;

use super::bodies::{motion, ContactBodies, Ploughers};
use super::contact_spots::{
    adhesion_from_gap, label_spots, measure_spots, Connectivity, ContactSpot, SpotLabels,
};
use super::error::FrictionError;
use super::laws::law::FrictionLaw;
use super::laws::ploughing::baseline::slope_baseline;
use super::laws::ploughing::front::front_geometry;
use super::laws::spot::{FrontGeometry, SlidingDirection, SpotFriction, SpotGeometry, SpotLoad};
use super::material::AdhesionParameters;
use crate::contact::PointMap;
use crate::materials::Side;

/// A solved contact as per-spot friction reads it (`[[iy, ix]]` maps of one grid).
#[derive(Debug, Clone, Copy)]
pub struct ContactSection<'a> {
    /// Pressure p (Pa).
    pub pressure: ArrayView2<'a, f64>,
    /// Gap after loading g (m), for the adhesion of the points out of contact.
    pub gap: PointMap<'a>,
    /// The two bodies: heights, deformations, hardness.
    pub bodies: ContactBodies<'a>,
    /// Grid spacings (dx, dy) (m).
    pub spacing: (f64, f64),
    /// Whether the contact was periodic (spots join across the edges).
    pub periodic: bool,
    /// Which neighbours join two contact points into one spot.
    pub connectivity: Connectivity,
    /// Δγ and ε of the Lennard-Jones adhesion.
    pub adhesion: AdhesionParameters,
}

/// The sums of a section (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct PerSpotResult {
    /// One entry per input spot.
    pub spots: Vec<SpotFriction>,
    /// Σ P_i (N).
    pub total_normal_force: f64,
    /// Σ Q_i (N).
    pub total_friction_force: f64,
    /// Σ Q_d,i, the deformation part of Σ Q_i (N).
    pub total_deformation_force: f64,
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
    /// Σ P_i of the merged spots (two or more summits) whose Q rests on one radius (N).
    pub load_merged: f64,
    /// Number of spots with two or more summits.
    pub merged_spots: usize,
    /// Σ P_i of the spots beyond the ploughing regime (N).
    pub load_outside_regime: f64,
    /// Σ P_i of the one-pixel spots (N).
    pub load_one_pixel: f64,
    /// Number of one-pixel spots.
    pub one_pixel_spots: usize,
}

/// The ploughing geometry of a section, for a law with a sliding direction.
#[derive(Debug, Clone, PartialEq)]
pub struct SectionGeometry {
    /// Which body ploughs.
    pub ploughing: Ploughers,
    /// One entry per spot.
    pub spots: Vec<SpotGeometry>,
    /// (2/π) × the rms slope along ψ of the ploughing body's surface over the section (the
    /// share-weighted mean at equal hardness): the deformation part a topography statistic
    /// alone would give ([`super::laws::ploughing::baseline`]).
    pub slope_baseline: f64,
}

/// Everything [`per_spot_friction`] finds in a section.
#[derive(Debug, Clone, PartialEq)]
pub struct SectionFriction {
    /// The contact spots, in id order.
    pub spots: Vec<ContactSpot>,
    /// The ploughing geometry, for a law with a sliding direction.
    pub geometry: Option<SectionGeometry>,
    /// The law per spot and the section's sums.
    pub result: PerSpotResult,
}

/// The per-spot model of a contact section under `law`, in one call (see the module docs).
///
/// Errors: maps of different shapes, spacings not finite and > 0, non-finite heights,
/// deformations or gaps where they are read, a grid of 2³² points or more.
pub fn per_spot_friction(
    section: &ContactSection,
    law: &dyn FrictionLaw,
) -> Result<SectionFriction, FrictionError> {
    per_spot_friction_with_baseline(section, law, None)
}

/// [`per_spot_friction`] given the slope baseline `known` of an earlier call on a section of the
/// same undeformed heights, spacing and boundary under a law of the same sliding direction (an
/// earlier load step of the same contact): the baseline depends on nothing else, so it is
/// taken as it is instead of computed again, a pass over the grid per ploughing body. `None`
/// computes it.
pub fn per_spot_friction_with_baseline(
    section: &ContactSection,
    law: &dyn FrictionLaw,
    known: Option<f64>,
) -> Result<SectionFriction, FrictionError> {
    let (dx, dy) = section.spacing;
    let labels = label_spots(section.pressure, section.periodic, section.connectivity)?;
    let height = section.bodies.composite_height();
    let spots = measure_spots(&labels, section.pressure, height, dx, dy)?;
    let adhesion = adhesion_from_gap(section.gap, section.pressure, dx, dy, section.adhesion)?;
    let geometry = law
        .sliding_direction()
        .map(|direction| section_geometry(&labels, section, direction, known))
        .transpose()?;
    let loads: Vec<SpotLoad> = spots.iter().map(SpotLoad::from).collect();
    let per_spot = geometry.as_ref().map(|g| g.spots.as_slice());
    let result = sum_spots(&loads, per_spot, law, adhesion)?;
    Ok(SectionFriction {
        spots,
        geometry,
        result,
    })
}

/// The fronts of the ploughing bodies of every spot and the slope baseline along `direction`
/// (`known`, or computed).
fn section_geometry(
    labels: &SpotLabels,
    section: &ContactSection,
    direction: SlidingDirection,
    known: Option<f64>,
) -> Result<SectionGeometry, FrictionError> {
    let ploughing = section.bodies.hardness().ploughing();
    let mut fronts: [Option<(f64, Vec<Option<FrontGeometry>>)>; 2] = [None, None];
    let mut baseline = 0.0;
    for (side, share) in ploughing.bodies() {
        let moving = SlidingDirection::new(motion(side, direction.angle()))?;
        let front = front_geometry(labels, &section.bodies, side, moving, section.spacing)?;
        let slot = match side {
            Side::Lower => 0,
            Side::Upper => 1,
        };
        fronts[slot] = Some((share, front));
        if known.is_none() {
            baseline += share
                * slope_baseline(
                    &section.bodies,
                    side,
                    direction,
                    section.spacing,
                    section.periodic,
                );
        }
    }
    let spots = (0..labels.count())
        .map(|id| SpotGeometry {
            fronts: fronts
                .each_ref()
                .map(|f| f.as_ref().map(|(share, fronts)| (*share, fronts[id]))),
        })
        .collect();
    Ok(SectionGeometry {
        ploughing,
        spots,
        slope_baseline: known.unwrap_or(baseline),
    })
}

/// The law per spot and the section's sums: `spots` with their ploughing geometry (one per spot,
/// for a law with a sliding direction) and the section's adhesion force `adhesion_force` (N,
/// ≥ 0). Errors on a non-finite or negative spot load or area, or a geometry list of another
/// length than the spots.
pub fn sum_spots(
    spots: &[SpotLoad],
    geometry: Option<&[SpotGeometry]>,
    law: &dyn FrictionLaw,
    adhesion_force: f64,
) -> Result<PerSpotResult, FrictionError> {
    if let Some(g) = geometry.filter(|g| g.len() != spots.len()) {
        return Err(FrictionError::InvalidParameter {
            name: "spot geometry",
            value: g.len() as f64,
            expected: "one geometry per spot",
        });
    }
    let mut result = PerSpotResult {
        spots: Vec::with_capacity(spots.len()),
        total_normal_force: 0.0,
        total_friction_force: 0.0,
        total_deformation_force: 0.0,
        total_area: 0.0,
        adhesion_force,
        mu_s: None,
        load_beyond_fit: 0.0,
        load_without_radius: 0.0,
        spots_without_radius: 0,
        load_merged: 0.0,
        merged_spots: 0,
        load_outside_regime: 0.0,
        load_one_pixel: 0.0,
        one_pixel_spots: 0,
    };
    for (i, spot) in spots.iter().enumerate() {
        check_spot(spot)?;
        let usable = SpotLoad {
            radius: spot.radius.filter(|r| r.is_finite() && *r > 0.0),
            ..*spot
        };
        let found = law.spot_friction(&usable, geometry.map(|g| &g[i]));
        result.add(spot, found);
    }
    let net = result.total_normal_force - adhesion_force;
    result.mu_s = (net > 0.0).then(|| result.total_friction_force / net);
    Ok(result)
}

impl PerSpotResult {
    /// Adds one spot and its friction (`None`: no radius, no Q).
    fn add(&mut self, spot: &SpotLoad, found: Option<SpotFriction>) {
        let friction = found.unwrap_or_else(|| {
            self.load_without_radius += spot.load;
            self.spots_without_radius += 1;
            SpotFriction::default()
        });
        let count = |yes: bool, load: &mut f64| {
            if yes {
                *load += spot.load;
            }
        };
        count(friction.beyond_fit, &mut self.load_beyond_fit);
        count(friction.outside_regime, &mut self.load_outside_regime);
        count(
            friction.radius_based && spot.summits > 1,
            &mut self.load_merged,
        );
        count(spot.pixels == 1, &mut self.load_one_pixel);
        self.merged_spots += usize::from(spot.summits > 1);
        self.one_pixel_spots += usize::from(spot.pixels == 1);
        self.total_normal_force += spot.load;
        self.total_friction_force += friction.friction_force;
        self.total_deformation_force += friction.deformation_force;
        self.total_area += spot.area;
        self.spots.push(friction);
    }
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
