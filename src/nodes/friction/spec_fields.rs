//! Field-level helpers of the friction spec's resolution, shared by the files of the friction spec's resolution:
//! located errors and the positive-value check.

use crate::engine::study::{SourceLocation, SpecError};

/// A located error of the field `field`.
pub(super) fn spec_error(
    location: SourceLocation,
    field: &str,
    message: impl Into<String>,
) -> SpecError {
    SpecError {
        location,
        field: field.to_string(),
        message: message.into(),
    }
}

/// `Ok` for a value > 0, else the out-of-range message in `unit`.
pub(super) fn positive(v: f64, unit: &str) -> Result<(), String> {
    if v > 0.0 {
        Ok(())
    } else {
        Err(format!("is out of range: must be > 0 {unit}"))
    }
}
