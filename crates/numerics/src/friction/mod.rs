//! Stage 3: statistical, per-summit and per-contact-spot static-friction models
//! (Greenwood–Williamson, Kogut–Etsion, CEB, full stick, junction shear). Equations, sources and
//! the confirmation status of every constant: `docs/friction-models.md`.
//!
//! * [`gw_functions`] — GW functions F_n(t) and Gaussian helpers (GW 1966);
//! * [`summit_statistics`] — σ, σ_s, y_s, R, η, β, α from spectral moments (Nayak 1971, McCool 1986),
//!   two surfaces combined by adding moments;
//! * [`material`] — composite modulus, hardness factor K, critical values ω_c, P_c, A_c, plasticity
//!   index ψ (with σ_s), Tabor's yield strength Y = H/2.8, adhesion parameters Δγ, ε;
//! * [`adhesion`] — the Kogut–Etsion 2003 adhesion fits of a contacting asperity and the
//!   DMT / Lennard-Jones force of a non-contacting one;
//! * [`laws`] — the friction laws as an open set: the [`FrictionLaw`] trait, its per-spot types
//!   ([`laws::spot`]), the single-asperity laws as ratios to the KE critical values
//!   ([`AsperityLaws`]), and one room per law beside its descriptor (name, [`ModelBasis`],
//!   methods, parameters): Kogut–Etsion (KE 2002 load/area, KE 2004 Q_max), CEB, full stick
//!   (Brizmer–Kligerman–Etsion with the Jackson–Green 2005 hand-over and the parameterised
//!   μ(P*) = a coth(a P*^b)), junction shear, ploughing (its closed forms, the deformation part
//!   per spot and each spot's geometry along the sliding direction); the one registry
//!   [`laws::LAWS`];
//! * [`statistical_integrals`] — P(d*), A(d*), F_s(d*), Q_max(d*), N(d*) and the load beyond the
//!   validated range, for every model;
//! * [`net_load_grid`] — P − F_s on a d* grid, evaluated lazily (most points need P only);
//! * [`mod@static_friction`] — solve F = P − F_s for d*, μ_s = Q_max/F, μ(F) curves;
//! * [`per_summit`] — the same laws applied per identified summit, force-weighted μ and the
//!   homogenization to the whole surface;
//! * [`contact_spots`] — connected contact spots of a contact solution with their load, area and
//!   radius, and the Lennard-Jones adhesion across its gap;
//! * [`bodies`] — the two bodies of a contact solution: the sign convention of their heights,
//!   each body's deformed surface, which body flows and which ploughs, which moves;
//! * [`per_spot`] — the per-spot model of a contact section in one call: spots, adhesion, the
//!   ploughing geometry, the law per spot and the section's sums;
//! * `quadrature`, `root_finding` (crate-private) — adaptive Gauss–Kronrod and Brent (own implementations).
//!
//! The Li–Etsion–Talke (2010) model itself is not implemented (its equations were not found);
//! the full-stick line it builds on is, under its own name.
//!
//! All quantities are SI; nothing here prints, reads files or knows about the study engine.

pub mod adhesion;
pub mod bodies;
pub mod contact_spots;
pub mod error;
pub mod gw_functions;
pub mod laws;
pub mod material;
pub mod net_load_grid;
mod paraboloid_fit;
pub mod per_spot;
pub mod per_summit;
pub(crate) mod quadrature;
pub(crate) mod root_finding;
pub mod solve_settings;
pub mod static_friction;
pub mod statistical_integrals;
pub mod summit_statistics;

pub use adhesion::AdhesionBeyondFits;
pub use bodies::{BodyHardness, BodyMaps, ContactBodies, Ploughers};
pub use contact_spots::{Connectivity, ContactSpot, SpotLabels};
pub use error::FrictionError;
pub use gw_functions::{gw_function, upper_tail_probability, INTEGRAL_REL_TOL};
pub use laws::full_stick::jackson_green::JacksonGreenLaw;
pub use laws::full_stick::stick::{FullStickLaw, StickFrictionLaw};
pub use laws::kogut_etsion::{DeformationState, StaticFrictionForm};
pub use laws::ploughing::deformation::DeformationLaw;
pub use laws::ploughing::front::front_geometry;
pub use laws::spot::{FrontGeometry, SlidingDirection, SpotGeometry};
pub use laws::{
    find_law, law_names, AsperityLaws, ChangEtsionBogy, FrictionLaw, FullStick, FullStickOptions,
    JunctionShear, KogutEtsion, LawDescriptor, LawInputs, Method, ModelBasis, Ploughing,
    SpotFriction, SpotLoad, LAWS,
};
pub use material::{AdhesionParameters, CriticalValues, Material, TABOR_FACTOR};
pub use net_load_grid::{net_load, GridEvaluations, NetLoadGrid};
pub use per_spot::{
    per_spot_friction, per_spot_friction_with_baseline, sum_spots, ContactSection, PerSpotResult,
    SectionFriction, SectionGeometry,
};
pub use per_summit::{
    per_summit_friction, summit_friction, summit_interference, PerSummitResult, SummitContact,
    SummitFriction,
};
pub use quadrature::QuadratureOutcome;
pub use solve_settings::SolveSettings;
pub use static_friction::{
    static_friction, static_friction_at_pressure, static_friction_curve, static_friction_on_grid,
    SolveStatus, StaticFrictionResult,
};
pub use statistical_integrals::{AdhesionForce, IntegralValue, StatisticalModel};
pub use summit_statistics::{SpectralMoments, SummitStatistics, MCCOOL_ALPHA_BOUND};
