//! Stage 2: elastic–perfectly-plastic half-space contact of two rough surfaces.
//!
//! Build a [`CompositeGap`] from two height maps (or one against a flat), a [`ContactMaterial`]
//! and a [`Boundary`]; a [`ContactSolver`] then solves a list of nominal pressures with
//! load-controlled constrained conjugate gradients (Polonsky & Keer 1999) under pressure
//! saturation `0 ≤ p ≤ p_lim` (Almqvist et al. 2007), falling back to an outer search on the
//! approach when that stalls. Each step reports the true contact area, the stress ratio and the
//! other [`LoadStep`] quantities; pressure, gap and deformation fields only on request.

mod approach_search;
mod constrained_cg;
mod derived;
mod error;
mod free_set;
mod gap;
mod influence;
mod load_balance;
mod load_curve;
mod material;
mod multilevel;
mod options;
mod packed_symmetric;
mod point_fields;
mod problem;
mod restricted_matrix;
mod selection;
mod solver;
mod transforms;
mod work;
mod workspace;

pub use crate::fft2::{FftFailure, RealFft2d};
pub use crate::materials::MaterialError;
pub use derived::{
    fields_from_displacement, fields_from_pressure, DisplacementOperator, StepSolution,
};
pub use error::ContactError;
pub use gap::{CompositeGap, GapError, GapSource, HeightsView};
pub use influence::Boundary;
pub use load_curve::{ContactFields, LoadCurve, LoadStep};
pub use material::ContactMaterial;
pub use options::{
    BadOption, FieldRequest, Residuals, SolvePath, SolveStrategy, SolverOptions, Termination,
    MAX_TOLERANCE, MIN_TOLERANCE,
};
pub use packed_symmetric::PackedSymmetric;
pub use point_fields::{PointFields, PointMap, StepField};
pub use problem::ContactProblem;
pub use solver::ContactSolver;
pub use work::Work;
