//! The study file's syntax below every other engine layer: values that remember their location
//! (`Located`), untyped YAML values (`RawValue`), and `Param<T>` fields (a literal or a
//! `${name}` reference) with their typed conversion (`FromParamValue`) and errors (`SpecError`).

mod located;
mod param;
mod raw;

pub use located::{Located, SourceLocation, SpannedName};
pub(crate) use param::ParamForm;
pub use param::{did_you_mean, is_parameter_name, FromParamValue, Param, SpecError};
pub use raw::RawValue;
