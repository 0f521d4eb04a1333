//! The deformation part of static friction of one contact spot from the loaded front of its
//! ploughing body (docs/friction-models.md, "Deformation part").
//!
//! A [`DeformationLaw`] turns the front of a ploughing body ([`FrontGeometry`],
//! [`super::front`]) into a deformation coefficient μ_d (the deformation force over the spot's
//! load):
//!
//! * **groove** (default): μ_d = A_side/A_f, the Bowden–Tabor ratio of the front's own cap
//!   (its silhouette along the motion over the front area), of which the cone and the sphere
//!   are the closed forms;
//! * **cone**: μ_d = (2/π) tan α of the front's attack slope
//!   ([`super::closed_forms::cone_ploughing`]);
//! * **sphere**: μ_d = μ_p(a_f/R_f) of the front radius a_f and the radius R_f of the sphere
//!   through the tip and the front boundary ([`FrontGeometry::sphere_radius`];
//!   [`super::closed_forms::sphere_ploughing`]); a_f ≤ R_f always holds for that sphere.
//!
//! An asperity that does not stand out of its front boundary (a cap height or attack slope
//! ≤ 0: the body is flat or concave there) ploughs nothing: μ_d = 0.

use super::closed_forms::{cone_ploughing, sphere_ploughing};
use crate::friction::laws::spot::FrontGeometry;

/// How the deformation part of a front is computed (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DeformationLaw {
    /// The front's own cap ploughing along the motion.
    Groove,
    /// A cone of the front's attack slope.
    Cone,
    /// The sphere through the front's tip and boundary at the front radius.
    Sphere,
}

impl DeformationLaw {
    /// Every law with its name in studies and tables.
    pub const NAMED: [(&'static str, DeformationLaw); 3] = [
        ("groove", Self::Groove),
        ("cone", Self::Cone),
        ("sphere", Self::Sphere),
    ];

    /// The law called `name` in [`Self::NAMED`].
    pub fn named(name: &str) -> Option<Self> {
        Self::NAMED
            .iter()
            .find(|(n, _)| *n == name)
            .map(|&(_, law)| law)
    }

    /// Whether the law rests on one asperity's radius.
    pub fn radius_based(self) -> bool {
        self == Self::Sphere
    }

    /// μ_d of one front; `None` when the law has no value there (a/R outside [0, 1], which the
    /// sphere through the front's tip and boundary never gives).
    pub fn coefficient(self, front: &FrontGeometry) -> Option<f64> {
        let Some(sphere_radius) = front.sphere_radius() else {
            return Some(0.0);
        };
        match self {
            Self::Groove => Some(front.groove_ratio),
            Self::Cone => Some(cone_ploughing(front.attack_slope)),
            Self::Sphere => sphere_ploughing(front.front_radius / sphere_radius),
        }
    }
}
