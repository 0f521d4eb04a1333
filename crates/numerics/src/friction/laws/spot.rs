//! What a law is given of one contact spot and what it answers: the per-spot contract of
//! [`super::law::FrictionLaw`]. A contact spot is a connected set of points with p > 0 of a
//! contact solution ([`crate::friction::contact_spots`]); its load and area are exact results of
//! the solution, its radius a fit. A law with a deformation part also reads the spot's geometry
//! along the sliding direction ([`SpotSlope`], measured by
//! [`super::ploughing::spot_slope::spot_slopes`]).

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

/// The geometry of one spot in one sliding direction
/// ([`super::ploughing::spot_slope`] measures it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpotSlope {
    /// Gradient `(∂z/∂x, ∂z/∂y)` of the fitted plane; `None` when even the dilated points are
    /// collinear (a grid of one row or column).
    pub gradient: Option<(f64, f64)>,
    /// `tan θ = g · d` of the plane along the sliding direction; `None` without a plane.
    pub tilt: Option<f64>,
    /// Number of points of the plane fit.
    pub plane_points: usize,
    /// Whether the plane took the 8-neighbour ring too (the footprint alone was collinear).
    pub dilated: bool,
    /// Height of the cap `z_peak − z_b` (m): the spot's penetration; `None` without a ring (a
    /// spot covering a periodic grid).
    pub cap_height: Option<f64>,
    /// `tan α = (z_peak − z_b)/r_b`; `None` without a ring.
    pub attack_slope: Option<f64>,
    /// Groove cross-section along the sliding direction over half the footprint, `2 A_side/A`;
    /// `None` without a ring.
    pub groove_ratio: Option<f64>,
}
