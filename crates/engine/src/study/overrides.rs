//! Parameter overrides from the command line: `--set n=64` replaces the axis of parameter `n`
//! for one run without editing the study file (reduced grids in CI, a quick look at one value).
//!
//! The value is YAML, like an axis in the file: a scalar (`64`, `1.19 um`) becomes a one-value
//! axis, a list (`[1, 2]`) or a generator (`{range: [1, 3]}`) replaces the axis as written.
//! Only `product` and `zip` axes can be overridden; a `zip` group keeps its equal-length rule.

use std::str::FromStr;

use crate::study::parameters::{Axis, ParameterSpace};
use crate::study::{did_you_mean, Study, StudyError};
use crate::syntax::RawValue;

/// One `NAME=VALUE` override of a parameter axis.
#[derive(Debug, Clone, PartialEq)]
pub struct ParameterOverride {
    /// The parameter whose axis is replaced.
    pub name: String,
    /// The replacement, as written after `=` (kept for the tables' metadata).
    pub text: String,
    axis: Axis,
}

/// A `--set` argument that is not `NAME=VALUE` with a YAML value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{message}")]
pub struct OverrideSyntaxError {
    pub argument: String,
    pub message: String,
}

impl FromStr for ParameterOverride {
    type Err = OverrideSyntaxError;

    fn from_str(argument: &str) -> Result<Self, Self::Err> {
        let err = |message: String| OverrideSyntaxError {
            argument: argument.to_string(),
            message,
        };
        let Some((name, text)) = argument.split_once('=') else {
            return Err(err(String::from(
                "expected NAME=VALUE, e.g. `--set n=64`, `--set \"sq=[0.38 um, 1.19 um]\"` or `--set \"seed={range: [1, 3]}\"`",
            )));
        };
        let (name, text) = (name.trim(), text.trim());
        if name.is_empty() {
            return Err(err(String::from("the parameter name before '=' is empty")));
        }
        if text.is_empty() {
            return Err(err(format!(
                "no value after '{name}='; give a value, a list or a range"
            )));
        }
        let raw: RawValue = serde_saphyr::from_str(text).map_err(|e| {
            err(match super::yaml_budget::breach(&e) {
                Some(breach) => super::yaml_budget::budget_message(breach),
                None => format!("the value is not valid YAML: {}", e.without_snippet()),
            })
        })?;
        let axis = match raw {
            list @ (RawValue::List(_) | RawValue::Map(_)) => Axis(list),
            scalar => Axis(RawValue::List(vec![scalar])),
        };
        Ok(Self {
            name: name.to_string(),
            text: text.to_string(),
            axis,
        })
    }
}

impl ParameterSpace {
    /// Replaces the axis of parameter `name`, keeping its place in the scenario order.
    fn override_axis(&mut self, name: &str, axis: &Axis) -> Result<(), String> {
        if let Some(slot) = self.product.get_mut(name) {
            slot.value = axis.clone();
            return Ok(());
        }
        for group in &mut self.zip {
            if let Some(slot) = group.value.get_mut(name) {
                slot.value = axis.clone();
                return Ok(());
            }
        }
        if let Some(lhs) = &self.latin_hypercube {
            if lhs.value.ranges.contains_key(name) {
                return Err(format!(
                    "'{name}' is sampled by latin_hypercube and cannot be overridden; edit its range or `samples` in the study file"
                ));
            }
        }
        let declared = self
            .product
            .keys()
            .chain(self.zip.iter().flat_map(|g| g.value.keys()));
        let names: Vec<&str> = declared.map(String::as_str).collect();
        Err(format!(
            "the study declares no parameter '{name}'{}; parameters: {}",
            did_you_mean(name, names.iter().copied()),
            if names.is_empty() {
                String::from("none")
            } else {
                names.join(", ")
            }
        ))
    }
}

impl<N> Study<N> {
    /// Applies command-line overrides in order (a later one for the same name wins) and records
    /// them for the tables' metadata. An unknown name is an error with a suggestion.
    pub fn apply_overrides(&mut self, overrides: &[ParameterOverride]) -> Result<(), StudyError> {
        for o in overrides {
            let location = self
                .file
                .parameters
                .product
                .get(&o.name)
                .map(|a| a.location)
                .unwrap_or_default();
            if let Err(message) = self.file.parameters.override_axis(&o.name, &o.axis) {
                return Err(StudyError::at(
                    &self.path,
                    &self.source,
                    location,
                    format!("--set {}={}", o.name, o.text),
                    message,
                ));
            }
            self.overrides.retain(|(name, _)| name != &o.name);
            self.overrides.push((o.name.clone(), o.text.clone()));
        }
        Ok(())
    }
}
