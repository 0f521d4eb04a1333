//! Errors of the contact solver.

use super::gap::GapError;
use super::options::{BadOption, Residuals, Termination};
use crate::fft2::FftFailure;
use crate::materials::MaterialError;

/// Why a contact problem could not be set up or solved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ContactError {
    #[error(transparent)]
    Material(#[from] MaterialError),
    #[error(transparent)]
    Gap(#[from] GapError),
    #[error(transparent)]
    Fft(#[from] FftFailure),
    #[error(transparent)]
    BadOption(#[from] BadOption),
    #[error("load step {step}: nominal pressure must be finite and > 0 Pa, got {pressure} Pa")]
    BadNominalPressure { step: usize, pressure: f64 },
    #[error("load step {step}: nominal pressures must be strictly ascending, got {pressure} Pa after {previous} Pa")]
    NotAscending {
        step: usize,
        pressure: f64,
        previous: f64,
    },
    #[error("load step {step}: nominal pressure {pressure} Pa is not below the flow pressure {flow_pressure} Pa (the whole surface would flow)")]
    AboveFlowPressure {
        step: usize,
        pressure: f64,
        flow_pressure: f64,
    },
    #[error("load step {step} at {pressure:e} Pa did not converge ({termination} after {iterations} iterations); relative residuals: separation {:.1e}, contact {:.1e}, plastic {:.1e}, force {:.1e}; try a looser `tolerance`, more load steps or a finer grid", residuals.separation, residuals.contact, residuals.plastic, residuals.force)]
    NotConverged {
        step: usize,
        pressure: f64,
        termination: Termination,
        iterations: usize,
        residuals: Residuals,
    },
    #[error("a pressure field of {} × {} points is not on the contact grid of {} × {} points", got.1, got.0, expected.1, expected.0)]
    FieldShape {
        /// `(ny, nx)` of the problem's grid.
        expected: (usize, usize),
        /// `(ny, nx)` of the field given.
        got: (usize, usize),
    },
}
