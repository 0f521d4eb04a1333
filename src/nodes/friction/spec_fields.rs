//! Field-level helpers of the friction spec's resolution, shared by `setup` and `model_setup`:
//! located errors, the positive-value check and the choice among named values.

use crate::engine::study::{ResolveContext, SourceLocation, SpecError};

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

/// The value of `param` among `choices` (name, value); `None` when the field is absent.
pub(super) fn resolve_choice<T: Copy>(
    ctx: &ResolveContext<'_>,
    param: &Option<crate::engine::study::Param<String>>,
    field: &str,
    choices: &[(&str, T)],
) -> Result<Option<T>, SpecError> {
    let Some(p) = param else { return Ok(None) };
    let names: Vec<&str> = choices.iter().map(|(n, _)| *n).collect();
    let text = ctx.resolve_checked(p, field, |s: &String| {
        if names.contains(&s.as_str()) {
            Ok(())
        } else {
            Err(format!("is not one of: {}", names.join(", ")))
        }
    })?;
    Ok(choices.iter().find(|(n, _)| *n == text).map(|(_, v)| *v))
}
