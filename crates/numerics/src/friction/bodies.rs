//! The two bodies of a contact solution as friction reads them: the sign convention of their
//! heights, the deformed surface of each, which body flows and which ploughs
//! (docs/friction-models.md, "Interface convention").
//!
//! **Heights.** As the contact's gap defines them (`contact::CompositeGap`), each body's heights
//! are measured from its own mean plane outward, towards the other body: the lower body's z₁
//! points up, the upper body's z₂ down, both on the same (x, y) grid. The contact is solved on
//! the composite z = z₁ + z₂ with the initial gap g₀ = max z − z and the gap after loading
//! g = g₀ + u − δ (δ the approach); u = u₁ + u₂ are the elastic normal displacements into the
//! two bodies, split by their compliances (u₁ = c₁/(c₁ + c₂) u, `deformation_lower`); where the
//! pressure reaches the flow pressure the interpenetration u_pl = −g is plastic.
//!
//! **Deformed surfaces.** In a frame with z up and the lower body's mean plane at 0, the lower
//! body's deformed surface is h₁ = z₁ − u₁ − s₁ u_pl and the upper body's
//! h₂ = (max z − δ) − z₂ + u₂ + s₂ u_pl, where s₁ + s₂ = 1 share the plastic penetration: the
//! softer body flows (s = 1 for it, 0 for the harder one; ½ each at equal hardness). Then
//! h₂ − h₁ = g + u_pl = max(g, 0): the surfaces meet on the contact, and the **interface height**
//! at a contact point is h₁. Each body seen from itself (heights outward, towards the other) has
//! the deformed surface w_b = z_b − u_b − s_b u_pl ([`ContactBodies::deformed`]); on the contact
//! w₁ + w₂ = max z − δ, a constant.
//!
//! **Motion.** The upper body slides along the sliding direction d (angle ψ from +x towards +y)
//! over the fixed lower body; the lower body moves along −d relative to the upper
//! ([`motion`]). Only relative motion matters: swapping the bodies and reversing ψ describes the
//! same sliding.
//!
//! **Which body ploughs** ([`BodyHardness::ploughing`]): the harder body's asperities plough
//! grooves in the softer body (Bowden & Tabor); a rigid counter-body, or one without a hardness,
//! is the harder. At equal hardness each body ploughs with its own asperities, each carrying half
//! of the spot's deformation part — a rule of this project (`parameterised`), not a published
//! result.

use ndarray::ArrayView2;

use super::error::FrictionError;
use crate::contact::PointMap;
use crate::materials::{MaterialPair, Side};

/// The hardness of each body (Pa); `+∞` for a rigid body or one without a hardness (it does
/// not flow).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyHardness {
    /// The lower body's.
    pub lower: f64,
    /// The upper body's.
    pub upper: f64,
}

/// Which body's asperities plough the other.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ploughers {
    /// One body, the harder.
    One(Side),
    /// Both, at equal hardness, each with half of the deformation part.
    Both,
}

impl Ploughers {
    /// Its name in tables: `lower`, `upper` or `both`.
    pub fn name(self) -> &'static str {
        match self {
            Self::One(Side::Lower) => "lower",
            Self::One(Side::Upper) => "upper",
            Self::Both => "both",
        }
    }

    /// The ploughing bodies with the share of the deformation part each carries.
    pub fn bodies(self) -> impl Iterator<Item = (Side, f64)> {
        let (lower, upper) = match self {
            Self::One(Side::Lower) => (1.0, 0.0),
            Self::One(Side::Upper) => (0.0, 1.0),
            Self::Both => (0.5, 0.5),
        };
        [(Side::Lower, lower), (Side::Upper, upper)]
            .into_iter()
            .filter(|&(_, share)| share > 0.0)
    }
}

impl BodyHardness {
    /// The bodies of `pair` (a rigid upper body does not flow).
    pub fn of(pair: &MaterialPair) -> Self {
        let flows = |h: Option<f64>| h.unwrap_or(f64::INFINITY);
        Self {
            lower: flows(pair.lower().hardness()),
            upper: pair.upper().map_or(f64::INFINITY, |u| flows(u.hardness())),
        }
    }

    /// The harder body ploughs; both at equal hardness (see the module docs).
    pub fn ploughing(&self) -> Ploughers {
        if self.upper > self.lower {
            Ploughers::One(Side::Upper)
        } else if self.lower > self.upper {
            Ploughers::One(Side::Lower)
        } else {
            Ploughers::Both
        }
    }

    /// The share s_b of the plastic penetration `side` takes: 1 for the softer body, 0 for the
    /// harder, ½ at equal hardness.
    pub fn plastic_share(&self, side: Side) -> f64 {
        let (own, other) = match side {
            Side::Lower => (self.lower, self.upper),
            Side::Upper => (self.upper, self.lower),
        };
        if own < other {
            1.0
        } else if own > other {
            0.0
        } else {
            0.5
        }
    }
}

/// The direction in which `side` moves relative to the other body, as an angle (radians): the
/// upper body slides along ψ, the lower along ψ + π.
pub fn motion(side: Side, sliding_direction: f64) -> f64 {
    match side {
        Side::Upper => sliding_direction,
        Side::Lower => sliding_direction + std::f64::consts::PI,
    }
}

/// The maps of a solved contact that the bodies' surfaces follow from, `[[iy, ix]]` (m): the
/// heights as arrays, the deformations stored or derived from the step's displacement
/// ([`PointMap`]).
#[derive(Debug, Clone, Copy)]
pub struct BodyMaps<'a> {
    /// z₁ + z₂ (the lower heights against a flat).
    pub composite_height: ArrayView2<'a, f64>,
    /// z₂; `None`: the counter-body is a flat.
    pub upper_height: Option<ArrayView2<'a, f64>>,
    /// u₁.
    pub deformation_lower: PointMap<'a>,
    /// u₂; `None`: a rigid counter-body.
    pub deformation_upper: Option<PointMap<'a>>,
    /// u_pl (0 where the pressure is below the flow pressure).
    pub plastic_penetration: PointMap<'a>,
}

/// The two bodies of a solved contact (see the module docs).
#[derive(Debug, Clone, Copy)]
pub struct ContactBodies<'a> {
    maps: BodyMaps<'a>,
    hardness: BodyHardness,
    lower_plastic_share: f64,
}

impl<'a> ContactBodies<'a> {
    /// The bodies of `maps` with their hardness. Errors when a map has another shape than the
    /// composite height.
    pub fn new(maps: BodyMaps<'a>, hardness: BodyHardness) -> Result<Self, FrictionError> {
        let shape = maps.composite_height.dim();
        let named = [
            ("upper_height", maps.upper_height.map(|z| z.dim())),
            ("deformation_lower", Some(maps.deformation_lower.dim())),
            ("deformation_upper", maps.deformation_upper.map(|u| u.dim())),
            ("plastic_penetration", Some(maps.plastic_penetration.dim())),
        ];
        for (name, dim) in named {
            if let Some(found) = dim.filter(|&d| d != shape) {
                return Err(FrictionError::ShapeMismatch {
                    name,
                    expected: shape,
                    found,
                });
            }
        }
        Ok(Self {
            maps,
            hardness,
            lower_plastic_share: hardness.plastic_share(Side::Lower),
        })
    }

    /// The bodies' hardness.
    pub fn hardness(&self) -> BodyHardness {
        self.hardness
    }

    /// The composite height z₁ + z₂.
    pub fn composite_height(&self) -> ArrayView2<'a, f64> {
        self.maps.composite_height
    }

    /// `(ny, nx)`.
    pub fn dim(&self) -> (usize, usize) {
        self.maps.composite_height.dim()
    }

    /// The undeformed outward height z_b of `side` at `(iy, ix)` (z₁ = z − z₂).
    pub fn height(&self, side: Side, at: (usize, usize)) -> f64 {
        let upper = self.maps.upper_height.map_or(0.0, |z| z[at]);
        match side {
            Side::Lower => self.maps.composite_height[at] - upper,
            Side::Upper => upper,
        }
    }

    /// Row `iy` of the undeformed outward heights of `side` into `out` (length `nx`): the same
    /// values as [`Self::height`] at each point, for a pass over whole rows.
    pub fn height_row(&self, side: Side, iy: usize, out: &mut [f64]) {
        let composite = self.maps.composite_height.row(iy);
        let upper = self.maps.upper_height.as_ref().map(|z| z.row(iy));
        for (ix, z) in out.iter_mut().enumerate() {
            let upper = upper.map_or(0.0, |u| u[ix]);
            *z = match side {
                Side::Lower => composite[ix] - upper,
                Side::Upper => upper,
            };
        }
    }

    /// The deformed outward surface w_b = z_b − u_b − s_b u_pl of `side` at `(iy, ix)`.
    pub fn deformed(&self, side: Side, at: (usize, usize)) -> f64 {
        let (elastic, share) = match side {
            Side::Lower => (self.maps.deformation_lower.at(at), self.lower_plastic_share),
            Side::Upper => (
                self.maps.deformation_upper.map_or(0.0, |u| u.at(at)),
                1.0 - self.lower_plastic_share,
            ),
        };
        self.height(side, at) - elastic - share * self.maps.plastic_penetration.at(at)
    }
}
