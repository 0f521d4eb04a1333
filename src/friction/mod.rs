//! Stage 3: statistical and per-summit static-friction models (Greenwood–Williamson, Kogut–Etsion, CEB).
//!
//! * [`gw_functions`] — GW functions F_n(t) and Gaussian helpers (GW 1966);
//! * [`summit_statistics`] — σ, σ_s, y_s, R, η, β, α from spectral moments (Nayak 1971, McCool 1986),
//!   two surfaces combined by adding moments;
//! * [`material`] — composite modulus, hardness factor K, critical values ω_c, P_c, A_c, plasticity
//!   index ψ (with σ_s), adhesion parameters Δγ, ε;
//! * [`asperity_laws`] — single-asperity laws (KE 2002 load/area, KE 2003 adhesion, DMT/LJ,
//!   KE 2004 Q_max literal/clipped, CEB), with what was confirmed from the literature;
//! * [`statistical_integrals`] — P(d*), A(d*), F_s(d*), Q_max(d*), N(d*) for KE 2004 and CEB;
//! * [`mod@static_friction`] — solve F = P − F_s for d*, μ_s = Q_max/F, μ(F) curves;
//! * [`per_summit`] — the same laws applied per identified summit, force-weighted μ and the
//!   homogenization to the whole surface;
//! * `quadrature`, `root_finding` (crate-private) — adaptive Gauss–Kronrod and Brent (own implementations).
//!
//! # Not implemented: Li–Etsion–Talke (2010)
//! The LET model for high plasticity index (Li, Etsion & Talke, J. Tribol. 132 (2010), built on the
//! Brizmer–Kligerman–Etsion 2007 full-stick sliding-inception fits) is NOT implemented: its
//! equations could not be confirmed with the available literature search (no primary or secondary
//! text restating them was found), and the project rule is not to guess fitted constants. At high
//! ψ the KE 2004 model gives Q_max contributions only from asperities with x ≤ 6, which is the
//! regime LET was designed to improve; results there should be read with that limitation.
//!
//! All quantities are SI; nothing here prints, reads files or knows about the study engine.

pub mod asperity_laws;
pub mod error;
pub mod gw_functions;
pub mod material;
pub mod per_summit;
pub(crate) mod quadrature;
pub(crate) mod root_finding;
pub mod static_friction;
pub mod statistical_integrals;
pub mod summit_statistics;

pub use asperity_laws::{AdhesionBeyondFits, AsperityModel, DeformationState, StaticFrictionForm};
pub use error::FrictionError;
pub use gw_functions::{gw_function, upper_tail_probability, INTEGRAL_REL_TOL};
pub use material::{AdhesionParameters, CriticalValues, Material};
pub use per_summit::{
    per_summit_friction, summit_friction, PerSummitResult, SummitContact, SummitFriction,
};
pub use quadrature::QuadratureOutcome;
pub use static_friction::{
    net_load, static_friction, static_friction_at_pressure, static_friction_curve,
    static_friction_on_grid, NetLoadGrid, SolveSettings, SolveStatus, StaticFrictionResult,
};
pub use statistical_integrals::{AdhesionForce, IntegralValue, ModelOptions, StatisticalModel};
pub use summit_statistics::{SpectralMoments, SummitStatistics, MCCOOL_ALPHA_BOUND};
