//! Friction laws as an open set: one [`FrictionLaw`] trait, one [`LawDescriptor`] per law and
//! one registry ([`LAWS`]) that maps the name a study writes to the law. Each law's physics
//! lives in its own room beside its descriptor.
//!
//! A law is built from a [`LawInputs`] (the pair's [`Material`](crate::friction::Material), the
//! softer body's yield and shear strengths and the law's own [`LawParameters`]) by its
//! descriptor's `build` function. What the methods ask of it:
//!
//! * **statistical** and **per summit** need the single-asperity laws as ratios to the
//!   Kogut–Etsion critical values ([`AsperityLaws`]: load, area and tangential capacity at the
//!   dimensionless interference x = ω/ω_c, their breaks and validated range);
//!   [`FrictionLaw::asperity_laws`] returns them, `None` for a law that has none (junction shear);
//! * **per spot** asks [`FrictionLaw::spot_friction`] for the tangential capacity of one contact
//!   spot of a contact solution (its exact load and area, and its radius: [`spot`]).
//!
//! Rooms: [`law`] (the contract), [`registry`], [`parameters`], [`spot`] (the per-spot types),
//! [`asperity`] (the single-asperity trait), [`interference`] (the one implementation of the
//! interference-driven laws), [`kogut_etsion`], [`chang_etsion_bogy`], [`full_stick`] (with the
//! Brizmer–Kligerman–Etsion and Jackson–Green asperities), [`junction_shear`], [`ploughing`]
//! (with its closed forms, the deformation part per spot and the spot geometry).
//!
//! The descriptor states once the law's name, its [`ModelBasis`], the methods it supports (the
//! first is its default) and its parameters with their defaults and ranges; a test builds every
//! registered law for every method it claims. Adding a law: its own file in this folder and one
//! line in [`LAWS`] (ARCHITECTURE.md, "How to add a friction law").

pub mod asperity;
pub mod chang_etsion_bogy;
pub mod full_stick;
pub mod interference;
pub mod junction_shear;
pub mod kogut_etsion;
pub mod law;
pub mod parameters;
pub mod ploughing;
pub mod registry;
pub mod spot;

pub use asperity::AsperityLaws;
pub use chang_etsion_bogy::ChangEtsionBogy;
pub use full_stick::{FullStick, FullStickOptions};
pub use junction_shear::JunctionShear;
pub use kogut_etsion::KogutEtsion;
pub use law::{BuildLaw, FrictionLaw, LawDescriptor, LawInputs, Method, ModelBasis};
pub use parameters::{
    LawParameters, NumberRange, ParameterKind, ParameterSpec, ParameterValue, ReportedValue, Unit,
};
pub use ploughing::{Ploughing, SLIDING_DIRECTION};
pub use registry::{default_law, find_law, law_names, LAWS};
pub use spot::{SpotFriction, SpotLoad};
