//! Friction laws as an open set: one [`FrictionLaw`] trait, one [`LawDescriptor`] per law and
//! one registry ([`LAWS`]) that maps the name a study writes to the law.
//!
//! A law is built from a [`LawInputs`] (the pair's [`Material`], the softer body's yield and shear
//! strengths and the law's own [`LawParameters`]) by its descriptor's `build` function. What the
//! methods ask of it:
//!
//! * **statistical** and **per summit** need the single-asperity laws as ratios to the
//!   Kogut–Etsion critical values ([`AsperityLaws`]: load, area and tangential capacity at the
//!   dimensionless interference x = ω/ω_c, their breaks and validated range);
//!   [`FrictionLaw::asperity_laws`] returns them, `None` for a law that has none (junction shear);
//! * **per spot** asks [`FrictionLaw::spot_friction`] for the tangential capacity of one contact
//!   spot of a contact solution (its exact load and area, and its radius).
//!
//! The descriptor states once the law's name, its [`ModelBasis`], the methods it supports (the
//! first is its default) and its parameters with their defaults and ranges; a test builds every
//! registered law for every method it claims. Adding a law: its own file in this folder and one
//! line in [`LAWS`] (ARCHITECTURE.md, "How to add a friction law").

mod chang_etsion_bogy;
mod full_stick;
mod junction_shear;
mod kogut_etsion;
mod parameters;
mod ploughing;

use std::fmt;
use std::sync::Arc;

use super::error::FrictionError;
use super::material::Material;
use super::per_spot::{SpotFriction, SpotLoad};
use super::spot_slope::{SlidingDirection, SpotSlope};

pub use chang_etsion_bogy::ChangEtsionBogy;
pub use full_stick::{FullStick, FullStickOptions};
pub use junction_shear::JunctionShear;
pub use kogut_etsion::KogutEtsion;
pub use parameters::{
    LawParameters, NumberRange, ParameterKind, ParameterSpec, ParameterValue, ReportedValue, Unit,
};
pub use ploughing::{Ploughing, SLIDING_DIRECTION};

/// Every friction law, in the order documentation lists them. The first is the default model.
pub const LAWS: &[&LawDescriptor] = &[
    &kogut_etsion::LAW,
    &chang_etsion_bogy::LAW,
    &full_stick::LAW,
    &junction_shear::LAW,
    &ploughing::LAW,
];

/// The law a study gets without `model`.
pub fn default_law() -> &'static LawDescriptor {
    LAWS[0]
}

/// The registered law called `name`.
pub fn find_law(name: &str) -> Option<&'static LawDescriptor> {
    LAWS.iter().copied().find(|law| law.name == name)
}

/// The names of the registered laws (for messages and the schema).
pub fn law_names() -> Vec<&'static str> {
    LAWS.iter().map(|law| law.name).collect()
}

/// How a friction coefficient is computed from the roughness.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// Greenwood–Williamson summit statistics with the laws' integrals.
    Statistical,
    /// The single-asperity laws per summit of a contact solution.
    PerSummit,
    /// The law per contact spot of a contact solution.
    PerSpot,
}

impl Method {
    /// Every method.
    pub const ALL: [Method; 3] = [Self::Statistical, Self::PerSummit, Self::PerSpot];

    /// The name studies write and tables carry.
    pub fn name(self) -> &'static str {
        match self {
            Self::Statistical => "statistical",
            Self::PerSummit => "per_summit",
            Self::PerSpot => "per_spot",
        }
    }

    /// `true` when the method evaluates the single-asperity laws ([`AsperityLaws`]).
    pub fn needs_asperity_laws(self) -> bool {
        matches!(self, Self::Statistical | Self::PerSummit)
    }
}

/// How far a law's constants are confirmed (written to every friction row as `model_basis`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ModelBasis {
    /// Published finite-element fits restated in the project reference (Kogut–Etsion, CEB).
    PublishedFits,
    /// A textbook law with a stated material parameter (junction shear).
    TextbookLaw,
    /// The law's structure is from the literature but some constants are attributed defaults that
    /// could not be confirmed (full stick: μ(P*) = a coth(a P*^b)); they are parameters.
    ParameterisedUnverified,
}

impl ModelBasis {
    /// The label written to tables.
    pub fn name(self) -> &'static str {
        match self {
            Self::PublishedFits => "published_fits",
            Self::TextbookLaw => "textbook_law",
            Self::ParameterisedUnverified => "parameterised_unverified",
        }
    }
}

/// What a law is built from.
#[derive(Debug, Clone, PartialEq)]
pub struct LawInputs {
    /// The pair: composite modulus, the softer body's hardness and Poisson ratio.
    pub material: Material,
    /// Yield strength Y of the softer body (Pa): given, or Tabor's H/2.8.
    pub yield_strength: f64,
    /// Shear strength k of the softer body (Pa): given, or von Mises Y/√3.
    pub shear_strength: f64,
    /// The law's own parameters (defaults where the study gives none).
    pub parameters: LawParameters,
}

/// Builds a law from its inputs.
pub type BuildLaw = fn(&LawInputs) -> Result<Box<dyn FrictionLaw>, FrictionError>;

/// What the registry knows of a law before it is built.
#[derive(Debug)]
pub struct LawDescriptor {
    /// The name studies write (`model: full_stick`) and tables carry.
    pub name: &'static str,
    /// One line: what the law is and where it comes from.
    pub summary: &'static str,
    /// How far its constants are confirmed.
    pub basis: ModelBasis,
    /// The methods it supports; the first is its default.
    pub methods: &'static [Method],
    /// Its parameters, in the order of their columns.
    pub parameters: &'static [ParameterSpec],
    /// Its constructor.
    pub build: BuildLaw,
}

impl LawDescriptor {
    /// The method used when a study names none.
    pub fn default_method(&self) -> Method {
        self.methods[0]
    }

    /// `true` when the law supports `method`.
    pub fn supports(&self, method: Method) -> bool {
        self.methods.contains(&method)
    }

    /// The parameter called `name`.
    pub fn parameter(&self, name: &str) -> Option<&'static ParameterSpec> {
        self.parameters.iter().find(|p| p.name == name)
    }

    /// The parameters at their defaults.
    pub fn default_parameters(&self) -> LawParameters {
        LawParameters::defaults(self.parameters)
    }
}

/// A built friction law.
pub trait FrictionLaw: fmt::Debug + Send + Sync {
    /// Its registry entry (name, basis, methods, parameters).
    fn descriptor(&self) -> &'static LawDescriptor;

    /// The single-asperity laws for the statistical and per-summit methods; `None` when the law
    /// has none.
    fn asperity_laws(self: Arc<Self>) -> Option<Arc<dyn AsperityLaws>>;

    /// The tangential capacity of one contact spot; `None` when the law needs a radius and
    /// `spot.radius` is `None` (the spot then carries no tangential load).
    fn spot_friction(&self, spot: &SpotLoad) -> Option<SpotFriction>;

    /// The values that identify the built law beyond the material: its parameters and what it
    /// derived from the material (key and table columns, in order).
    fn reported_values(&self) -> Vec<ReportedValue>;

    /// For a law with a deformation part: the sliding direction along which it reads each
    /// spot's geometry ([`super::spot_slope`]); `None` (the default) for a law that reads none.
    fn sliding_direction(&self) -> Option<SlidingDirection> {
        None
    }

    /// The tangential capacity of a spot with its geometry along [`Self::sliding_direction`],
    /// and the part of it that is deformation (N). The default: [`Self::spot_friction`] with no
    /// deformation part.
    fn sloped_spot_friction(
        &self,
        spot: &SpotLoad,
        _geometry: &SpotSlope,
    ) -> Option<(SpotFriction, f64)> {
        self.spot_friction(spot).map(|f| (f, 0.0))
    }
}

/// Single-asperity laws as ratios to the Kogut–Etsion critical values of the asperity
/// (x = ω/ω_c, P/P_c, A/A_c, Q_max/P_c with ω_c = (πKH/(2E'))² R, P_c = (2/3)πKHRω_c,
/// A_c = πRω_c; [`super::material`]), so the statistical integrals, the per-summit model and the
/// per-spot inversion treat every interference-driven law alike.
pub trait AsperityLaws: fmt::Debug + Send + Sync {
    /// P/P_c at x (0 for x ≤ 0).
    fn load_ratio(&self, x: f64) -> f64;

    /// A/A_c at x (0 for x ≤ 0).
    fn area_ratio(&self, x: f64) -> f64;

    /// Q_max/P_c at x (0 for x ≤ 0).
    fn friction_ratio(&self, x: f64) -> f64;

    /// Breaks in x of the load and area laws (smooth between them).
    fn load_breaks(&self) -> Vec<f64>;

    /// Breaks in x of the friction law below [`AsperityLaws::friction_support`].
    fn friction_breaks(&self) -> Vec<f64>;

    /// The x beyond which Q_max/P_c is zero (+∞ when it never is).
    fn friction_support(&self) -> f64;

    /// The x beyond which the friction law is outside its validated range.
    fn fit_limit(&self) -> f64;

    /// κ ∈ (0, 1] with P/P_c(x′) ≤ P/P_c(x)/κ for every x′ ≤ x: the load laws increase between
    /// their breaks, so κ is the product of the drops at the breaks (1 when the law never drops).
    fn load_drop_bound(&self) -> f64 {
        self.load_breaks()
            .iter()
            .map(|&b| {
                let before = self.load_ratio(b);
                let after = self.load_ratio(b * (1.0 + 1e-12));
                if before > 0.0 {
                    (after / before).min(1.0)
                } else {
                    1.0
                }
            })
            .product()
    }
}
