//! What a law is given of one contact spot and what it answers: the per-spot contract of
//! [`super::law::FrictionLaw`]. A contact spot is a connected set of points with p > 0 of a
//! contact solution ([`crate::friction::contact_spots`]); its load and area are exact results of
//! the solution, its radius a fit. A law with a deformation part also reads the loaded front of
//! the ploughing body's deformed surface along its motion ([`SpotGeometry`], measured by
//! [`super::ploughing::front::front_geometry`]).

use crate::friction::contact_spots::ContactSpot;
use crate::friction::error::FrictionError;

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
    /// Summits of the composite topography inside the spot: two or more, and the spot is
    /// several asperities merged into one junction, for which one radius means nothing.
    pub summits: usize,
}

impl From<&ContactSpot> for SpotLoad {
    fn from(spot: &ContactSpot) -> Self {
        Self {
            load: spot.load,
            area: spot.area,
            radius: spot.radius,
            pixels: spot.pixels,
            summits: spot.summits,
        }
    }
}

/// Friction of one spot.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SpotFriction {
    /// Tangential capacity Q_i (N).
    pub friction_force: f64,
    /// The part of Q_i that is deformation (ploughing), Q_d,i (N); 0 for an adhesion law.
    pub deformation_force: f64,
    /// Dimensionless load P_i* = P_i/L_c (full stick), x_i (KE/CEB); `None` otherwise.
    pub load_measure: Option<f64>,
    /// Whether the spot lies beyond the validated range of the law.
    pub beyond_fit: bool,
    /// Whether Q_i rests on one asperity's radius (the single-asperity laws, the sphere
    /// ploughing law): meaningless on a merged spot.
    pub radius_based: bool,
    /// The degree of penetration D_p of a ploughing law (the largest of its ploughing bodies');
    /// `None` for other laws.
    pub penetration: Option<f64>,
    /// Whether D_p lies beyond the ploughing regime (wedge forming or cutting).
    pub outside_regime: bool,
}

/// The equivalent contact radius `a = √(A/π)` of a spot of area `A` (m², m).
pub fn contact_radius(area: f64) -> f64 {
    (area / std::f64::consts::PI).sqrt()
}

/// A sliding direction in the surface plane: the angle ψ from +x towards +y (radians).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlidingDirection {
    angle: f64,
    cos: f64,
    sin: f64,
}

impl SlidingDirection {
    /// The direction at angle `angle` (radians, finite); 0 slides along +x.
    pub fn new(angle: f64) -> Result<Self, FrictionError> {
        if !angle.is_finite() {
            return Err(FrictionError::InvalidParameter {
                name: "sliding_direction",
                value: angle,
                expected: "a finite angle in radians",
            });
        }
        Ok(Self {
            angle,
            cos: angle.cos(),
            sin: angle.sin(),
        })
    }

    /// The angle ψ (radians).
    pub fn angle(&self) -> f64 {
        self.angle
    }

    /// cos ψ.
    pub fn cos(&self) -> f64 {
        self.cos
    }

    /// sin ψ.
    pub fn sin(&self) -> f64 {
        self.sin
    }

    /// The component `g · d` of a gradient along the direction.
    pub fn along(&self, gradient: (f64, f64)) -> f64 {
        gradient.0 * self.cos + gradient.1 * self.sin
    }

    /// The coordinate of the offset `(x, y)` (m) across the direction, `(−sin ψ, cos ψ) · (x, y)`.
    pub fn across(&self, (x, y): (f64, f64)) -> f64 {
        y * self.cos - x * self.sin
    }
}

/// The loaded front of one spot on one ploughing body's deformed surface, along the direction
/// that body moves ([`super::ploughing::front`] measures it and says how).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrontGeometry {
    /// Cap height h = w_tip − w_f of the asperity above its front boundary (m); negative where
    /// the surface is concave.
    pub cap_height: f64,
    /// tan α = h/r_f, the mean slope from the tip down to the front boundary.
    pub attack_slope: f64,
    /// A_side/A_f: the cap's silhouette along the motion over the front area.
    pub groove_ratio: f64,
    /// Front area A_f (m²).
    pub front_area: f64,
    /// a_f = √(2A_f/π) (m).
    pub front_radius: f64,
    /// Degree of penetration D_p = max(h, 0)/a_f.
    pub penetration: f64,
}

impl FrontGeometry {
    /// R_f = (a_f² + h²)/(2h), the radius of the sphere through the tip and the front boundary
    /// (a cap of height h over the radius a_f); `None` when h ≤ 0 (no asperity).
    pub fn sphere_radius(&self) -> Option<f64> {
        let (a, h) = (self.front_radius, self.cap_height);
        (h > 0.0).then(|| (a * a + h * h) / (2.0 * h))
    }
}

/// The ploughing geometry of one spot: the front of each ploughing body and the share of the
/// deformation part it carries (1 for the harder body; ½ each at equal hardness,
/// [`crate::friction::bodies::BodyHardness::ploughing`]). A front is `None` when the spot has
/// no ring ahead of the tip (it covers a periodic grid).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpotGeometry {
    /// Up to two `(share, front)` pairs: the lower body's, then the upper body's.
    pub fronts: [Option<(f64, Option<FrontGeometry>)>; 2],
}

impl SpotGeometry {
    /// The ploughing bodies' `(share, front)`.
    pub fn ploughers(&self) -> impl Iterator<Item = (f64, Option<&FrontGeometry>)> {
        self.fronts
            .iter()
            .flatten()
            .map(|(share, front)| (*share, front.as_ref()))
    }
}
