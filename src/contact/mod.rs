//! Stage 2: elastic–perfectly-plastic half-space contact of two rough surfaces.

mod fft2d;
mod gap;
mod influence;
mod material;

pub use fft2d::{FftFailure, RealFft2d};
pub use gap::{CompositeGap, GapError, GapSource};
pub use influence::Boundary;
pub use material::{BodyElasticity, ContactMaterial, MaterialError};
