//! The one material description contact and friction share:
//! * [`BodyMaterial`] (`body`) — one body: E, ν and the strengths H, Y, k, p_lim, given or by the
//!   default rules (Y = H/2.8 Tabor, k = Y/√3 von Mises, p_lim = H), with its half-space
//!   compliance (1 − ν²)/E;
//! * [`MaterialPair`] (`pair`) — a lower body against an upper or a rigid one: the composite
//!   compliance and modulus ([`MaterialPair::composite`]), the softer body
//!   ([`MaterialPair::softer`]) and the pair's flow pressure;
//! * [`bounds`] — the one set of bounds with the reason for each, and [`MaterialError`];
//! * `builtin` — the built-in materials with their literature sources, looked up by name.
//!
//! `contact::ContactMaterial` and `friction::Material` are built from a [`MaterialPair`].

mod body;
pub mod bounds;
mod builtin;
mod pair;

pub use body::{BodyConstants, BodyMaterial, TABOR_FACTOR};
pub use bounds::MaterialError;
pub use builtin::{
    all_names, find_material, known_names, BuiltinMaterial, UnknownMaterial, BUILTIN_MATERIALS,
};
pub use pair::{Composite, MaterialPair, Side};
