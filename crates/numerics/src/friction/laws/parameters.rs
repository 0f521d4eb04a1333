//! A law's own parameters: their declaration ([`ParameterSpec`]: name, column, default, range),
//! their resolved values ([`LawParameters`]) and the values a built law reports
//! ([`ReportedValue`]).

use crate::friction::error::FrictionError;

fn undeclared(name: &'static str) -> FrictionError {
    FrictionError::InvalidParameter {
        name,
        value: f64::NAN,
        expected: "a parameter the law declares (its descriptor lists them)",
    }
}

/// The unit of a parameter or reported value (SI).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Unit {
    /// A pure number.
    Dimensionless,
    /// Pa.
    Pressure,
    /// rad.
    Angle,
}

/// An interval of allowed numbers: `min` and `max` with whether each end belongs to it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NumberRange {
    /// Lower end.
    pub min: f64,
    /// Whether `min` itself is allowed.
    pub min_inclusive: bool,
    /// Upper end (may be +∞).
    pub max: f64,
    /// Whether `max` itself is allowed.
    pub max_inclusive: bool,
}

impl NumberRange {
    /// `(0, +∞)`.
    pub const POSITIVE: Self = Self {
        min: 0.0,
        min_inclusive: false,
        max: f64::INFINITY,
        max_inclusive: false,
    };

    /// `true` when `v` lies in the range (never for NaN).
    pub fn contains(&self, v: f64) -> bool {
        let above = if self.min_inclusive {
            v >= self.min
        } else {
            v > self.min
        };
        let below = if self.max_inclusive {
            v <= self.max
        } else {
            v < self.max
        };
        above && below
    }

    /// The range as written in messages and docs: `(0, 1)`, `[0, 1]`, `> 0`.
    pub fn describe(&self) -> String {
        if self.max == f64::INFINITY {
            let op = if self.min_inclusive { ">=" } else { ">" };
            return format!("{op} {}", self.min);
        }
        format!(
            "{}{}, {}{}",
            if self.min_inclusive { '[' } else { '(' },
            self.min,
            self.max,
            if self.max_inclusive { ']' } else { ')' }
        )
    }
}

/// What kind of value a parameter takes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ParameterKind {
    /// A number in `range`, `default` when not given.
    Number {
        /// The value used when the study gives none.
        default: f64,
        /// The allowed values.
        range: NumberRange,
        /// Its unit.
        unit: Unit,
    },
    /// One of `options`, `default` when not given.
    Choice {
        /// The allowed names.
        options: &'static [&'static str],
        /// The name used when the study gives none.
        default: &'static str,
    },
}

/// The declaration of one parameter of a law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParameterSpec {
    /// The name inside the law's block (`model: {full_stick: {a: 0.3}}`).
    pub name: &'static str,
    /// The key and table column that carries it (without unit suffix).
    pub column: &'static str,
    /// What it means, with its source or status.
    pub description: &'static str,
    /// Its kind, default and range.
    pub kind: ParameterKind,
}

/// A resolved parameter value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ParameterValue {
    /// A number (SI).
    Number(f64),
    /// One of a choice's options.
    Choice(&'static str),
}

/// The resolved parameters of one law, in declaration order.
#[derive(Debug, Clone, PartialEq)]
pub struct LawParameters {
    values: Vec<(&'static ParameterSpec, ParameterValue)>,
}

impl ParameterSpec {
    /// The default value.
    pub fn default_value(&'static self) -> ParameterValue {
        match self.kind {
            ParameterKind::Number { default, .. } => ParameterValue::Number(default),
            ParameterKind::Choice { default, .. } => ParameterValue::Choice(default),
        }
    }

    /// `v` as this (numeric) parameter's value, or the expectation it misses.
    pub fn number(&'static self, v: f64) -> Result<ParameterValue, String> {
        match self.kind {
            ParameterKind::Number { range, .. } if range.contains(v) => {
                Ok(ParameterValue::Number(v))
            }
            ParameterKind::Number { range, .. } => {
                Err(format!("is out of range: must be {}", range.describe()))
            }
            ParameterKind::Choice { options, .. } => {
                Err(format!("is not one of: {}", options.join(", ")))
            }
        }
    }

    /// `text` as this (choice) parameter's value, or the expectation it misses.
    pub fn choice(&'static self, text: &str) -> Result<ParameterValue, String> {
        match self.kind {
            ParameterKind::Choice { options, .. } => options
                .iter()
                .find(|o| **o == text)
                .map(|o| ParameterValue::Choice(o))
                .ok_or_else(|| format!("is not one of: {}", options.join(", "))),
            ParameterKind::Number { range, .. } => {
                Err(format!("expected a number {}", range.describe()))
            }
        }
    }
}

impl LawParameters {
    /// Every parameter of `specs` at its default.
    pub fn defaults(specs: &'static [ParameterSpec]) -> Self {
        Self {
            values: specs.iter().map(|s| (s, s.default_value())).collect(),
        }
    }

    /// Sets the parameter called `name` (a value from [`ParameterSpec::number`] or
    /// [`ParameterSpec::choice`]); `false` when there is no such parameter.
    pub fn set(&mut self, name: &str, value: ParameterValue) -> bool {
        match self.values.iter_mut().find(|(s, _)| s.name == name) {
            Some(slot) => {
                slot.1 = value;
                true
            }
            None => false,
        }
    }

    /// The number called `name`; an error when the law declared no such numeric parameter.
    pub fn number(&self, name: &'static str) -> Result<f64, FrictionError> {
        match self.get(name) {
            Some(ParameterValue::Number(v)) => Ok(v),
            _ => Err(undeclared(name)),
        }
    }

    /// The choice called `name`; an error when the law declared no such choice parameter.
    pub fn choice(&self, name: &'static str) -> Result<&'static str, FrictionError> {
        match self.get(name) {
            Some(ParameterValue::Choice(c)) => Ok(c),
            _ => Err(undeclared(name)),
        }
    }

    fn get(&self, name: &str) -> Option<ParameterValue> {
        self.values
            .iter()
            .find(|(s, _)| s.name == name)
            .map(|(_, v)| *v)
    }

    /// The values as reported columns, in declaration order.
    pub fn reported(&self) -> Vec<ReportedValue> {
        self.values
            .iter()
            .map(|(spec, value)| ReportedValue {
                column: spec.column,
                value: *value,
                unit: match spec.kind {
                    ParameterKind::Number { unit, .. } => unit,
                    ParameterKind::Choice { .. } => Unit::Dimensionless,
                },
            })
            .collect()
    }
}

/// One value a built law reports (a key and table column).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReportedValue {
    /// Column name without unit suffix.
    pub column: &'static str,
    /// The value.
    pub value: ParameterValue,
    /// Its unit.
    pub unit: Unit,
}
