//! The contract of a friction law: the [`FrictionLaw`] trait a study's node and the numerics
//! call, the [`LawDescriptor`] the registry ([`super::registry::LAWS`]) lists, what a law is
//! built from ([`LawInputs`]), the [`Method`]s and the [`ModelBasis`] labels.

use std::fmt;
use std::sync::Arc;

use super::asperity::AsperityLaws;
use super::parameters::{LawParameters, ParameterSpec, ReportedValue};
use super::spot::{SlidingDirection, SpotFriction, SpotGeometry, SpotLoad};
use crate::friction::error::FrictionError;
use crate::friction::material::Material;

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

/// The largest μ_s of a law that can carry adhesion and junction growth (full stick, junction
/// shear, ploughing) reported as `ok` — a bound stated by this project, not a published limit:
/// handbook static friction coefficients of dry metal pairs in air are of order 0.1–1, and 1.5
/// leaves room for clean junctions that grow under the tangential load. A larger section value
/// comes from a load too small for the law's range or from spots whose radius means nothing.
pub const DRY_METAL_MU_S_MAX: f64 = 1.5;

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
    /// The largest μ_s a row of the law reports as `ok`: above it the row is flagged, the law is
    /// outside what it can describe (docs/study-format.md, the models table).
    pub mu_s_max: f64,
    /// Where the law's validated range ends and what a spot or summit beyond it gets, one
    /// clause: the flag of a row with most of its load beyond the range names this law alone.
    pub validated_range: &'static str,
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
    /// `spot.radius` is `None` (the spot then carries no tangential load). `geometry` is the
    /// spot's ploughing geometry along [`Self::sliding_direction`], given to a law that has one
    /// (the others ignore it).
    fn spot_friction(
        &self,
        spot: &SpotLoad,
        geometry: Option<&SpotGeometry>,
    ) -> Option<SpotFriction>;

    /// The values that identify the built law beyond the material: its parameters and what it
    /// derived from the material (key and table columns, in order).
    fn reported_values(&self) -> Vec<ReportedValue>;

    /// For a law with a deformation part: the sliding direction ψ of the upper body over the
    /// lower, along which it reads each spot's loaded front ([`super::ploughing::front`]);
    /// `None` (the default) for a law that reads none. A law that returns `None` has no
    /// direction in its parameters, key or row.
    fn sliding_direction(&self) -> Option<SlidingDirection> {
        None
    }
}
