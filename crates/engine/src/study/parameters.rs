//! Parameter spaces: axes (lists, `range`, `linspace`, `logspace`, `glob` over files) combined
//! by `product` and `zip`, plus seeded Latin-hypercube sampling, expanded into scenarios.

use std::path::Path;

use indexmap::IndexMap;
use rand_chacha::rand_core::{Rng, SeedableRng};
use serde::Deserialize;

use crate::syntax::RawValue;
use crate::syntax::{is_parameter_name, Located, SourceLocation};
use crate::units::Dimension;
use crate::value::ParamValue;

/// The parameter section of a study. Scenarios are the cartesian product of every `product`
/// axis (first declared varies slowest), each `zip` group (its axes advance together) and the
/// `latin_hypercube` sample set, in that order.
#[derive(Debug, Clone, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ParameterSpace {
    /// Axes combined by cartesian product: `name: [values]`, `{range: [first, last, step?]}`,
    /// `{linspace: [first, last, count]}` or `{logspace: [first, last, count]}`.
    #[serde(default)]
    pub product: IndexMap<String, Located<Axis>>,
    /// Groups of axes of equal length that advance together; each group is one product axis.
    #[serde(default)]
    pub zip: Vec<Located<IndexMap<String, Located<Axis>>>>,
    /// Seeded Latin-hypercube samples over ranges; one product axis.
    #[serde(default)]
    pub latin_hypercube: Option<Located<LatinHypercube>>,
}

/// One parameter axis, as written.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis(pub RawValue);

impl<'de> Deserialize<'de> for Axis {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        RawValue::deserialize(deserializer).map(Axis)
    }
}

impl schemars::JsonSchema for Axis {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "ParameterAxis".into()
    }

    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let endpoint = schemars::json_schema!({"type": ["number", "string"]});
        schemars::json_schema!({
            "description": "A parameter axis: a list of values (numbers, quantities such as '1.19 um', text, lists), or one of {range: [first, last, step?]} (integers or quantities, both ends included), {linspace: [first, last, count]}, {logspace: [first, last, count]} (geometric spacing between the two end VALUES, not exponents), {glob: 'scans/*-upper.x3p', values: paths|stems} (the matching files, sorted; relative to the study file; stems: the text the one '*' matched).",
            "anyOf": [
                {"type": "array"},
                {"type": "object", "properties": {"range": {"type": "array", "items": endpoint, "minItems": 2, "maxItems": 3}}, "required": ["range"], "additionalProperties": false},
                {"type": "object", "properties": {"linspace": {"type": "array", "minItems": 3, "maxItems": 3}}, "required": ["linspace"], "additionalProperties": false},
                {"type": "object", "properties": {"logspace": {"type": "array", "minItems": 3, "maxItems": 3}}, "required": ["logspace"], "additionalProperties": false},
                {"type": "object", "properties": {"glob": {"type": "string"}, "values": {"enum": ["paths", "stems"]}}, "required": ["glob"], "additionalProperties": false}
            ]
        })
    }
}

/// Seeded Latin-hypercube sampling: `samples` points, each range split into `samples` equal
/// strata, one point per stratum per dimension, strata paired by independent permutations.
#[derive(Debug, Clone, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LatinHypercube {
    /// Number of samples (scenarios contributed).
    pub samples: usize,
    /// Seed of the ChaCha8 generator: the same seed gives the same samples everywhere.
    pub seed: u64,
    /// `name: [low, high]` — numbers or quantities of one dimension.
    pub ranges: IndexMap<String, Located<Axis>>,
}

/// An error in the parameter section.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{parameter}: {message}")]
pub struct ParameterError {
    pub location: SourceLocation,
    pub parameter: String,
    pub message: String,
}

/// The expanded scenarios: one row of values per scenario, columns in `names` order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Scenarios {
    pub names: Vec<String>,
    pub rows: Vec<Vec<ParamValue>>,
    /// Where each parameter is declared.
    pub locations: Vec<SourceLocation>,
}

/// Upper bound on the number of scenarios, to turn a typo (`range: [1, 1e9]`) into an error
/// instead of an out-of-memory crash.
pub const MAX_SCENARIOS: usize = 10_000_000;

impl ParameterSpace {
    /// Every parameter name as written, with its location, in declaration order.
    pub fn declared_names(&self) -> Vec<(&str, SourceLocation)> {
        let axes = self
            .product
            .iter()
            .chain(self.zip.iter().flat_map(|g| g.value.iter()))
            .chain(
                self.latin_hypercube
                    .iter()
                    .flat_map(|l| l.value.ranges.iter()),
            );
        axes.map(|(name, axis)| (name.as_str(), axis.location))
            .collect()
    }

    /// Expands the space into scenarios (a study with no parameters has one scenario); `glob`
    /// patterns are relative to `base`, the study file's folder.
    pub fn expand(&self, base: &Path) -> Result<Scenarios, ParameterError> {
        let mut groups: Vec<Group> = Vec::new();
        for (name, axis) in &self.product {
            groups.push(Group {
                names: vec![(name.clone(), axis.location)],
                rows: axis_values(name, axis, base)?
                    .into_iter()
                    .map(|v| vec![v])
                    .collect(),
            });
        }
        for group in &self.zip {
            groups.push(zip_group(group, base)?);
        }
        if let Some(lhs) = &self.latin_hypercube {
            groups.push(latin_hypercube(lhs)?);
        }
        let mut names: Vec<(String, SourceLocation)> = Vec::new();
        for g in &groups {
            for (n, loc) in &g.names {
                if names.iter().any(|(m, _)| m == n) {
                    return Err(ParameterError {
                        location: *loc,
                        parameter: n.clone(),
                        message: String::from(
                            "declared twice; each parameter may appear in one axis only",
                        ),
                    });
                }
                names.push((n.clone(), *loc));
            }
        }
        let total = groups
            .iter()
            .try_fold(1usize, |acc, g| acc.checked_mul(g.rows.len()))
            .filter(|&n| n <= MAX_SCENARIOS);
        let Some(total) = total else {
            let (n, loc) = names.first().cloned().unwrap_or_default();
            return Err(ParameterError {
                location: loc,
                parameter: n,
                message: format!(
                    "the parameter space has more than {MAX_SCENARIOS} scenarios; reduce the axes"
                ),
            });
        };
        let mut rows = Vec::with_capacity(total);
        for mut index in 0..total {
            let mut parts: Vec<&Vec<ParamValue>> = Vec::with_capacity(groups.len());
            for g in groups.iter().rev() {
                parts.push(&g.rows[index % g.rows.len()]);
                index /= g.rows.len();
            }
            rows.push(parts.into_iter().rev().flatten().cloned().collect());
        }
        Ok(Scenarios {
            names: names.iter().map(|(n, _)| n.clone()).collect(),
            locations: names.iter().map(|(_, l)| *l).collect(),
            rows,
        })
    }
}

struct Group {
    names: Vec<(String, SourceLocation)>,
    rows: Vec<Vec<ParamValue>>,
}

fn zip_group(
    group: &Located<IndexMap<String, Located<Axis>>>,
    base: &Path,
) -> Result<Group, ParameterError> {
    let mut columns = Vec::new();
    for (name, axis) in &group.value {
        columns.push((name.clone(), axis.location, axis_values(name, axis, base)?));
    }
    let Some(first) = columns.first() else {
        return Err(ParameterError {
            location: group.location,
            parameter: String::from("zip"),
            message: String::from(
                "a zip group needs at least one axis: `zip: [{a: [...], b: [...]}]`",
            ),
        });
    };
    let len = first.2.len();
    if let Some((name, loc, values)) = columns.iter().find(|c| c.2.len() != len) {
        return Err(ParameterError {
            location: *loc,
            parameter: name.clone(),
            message: format!(
                "zip axes must have equal lengths: '{}' has {len} values, '{name}' has {}",
                columns[0].0,
                values.len()
            ),
        });
    }
    Ok(Group {
        names: columns.iter().map(|c| (c.0.clone(), c.1)).collect(),
        rows: (0..len)
            .map(|i| columns.iter().map(|c| c.2[i].clone()).collect())
            .collect(),
    })
}

fn axis_values(
    name: &str,
    axis: &Located<Axis>,
    base: &Path,
) -> Result<Vec<ParamValue>, ParameterError> {
    let err = |message: String| ParameterError {
        location: axis.location,
        parameter: name.to_string(),
        message,
    };
    if !is_parameter_name(name) {
        return Err(err(String::from(
            "parameter names must start with a letter or '_' and contain only letters, digits and '_'",
        )));
    }
    let values = match &axis.value.0 {
        RawValue::List(items) => items
            .iter()
            .map(RawValue::to_param_value)
            .collect::<Result<Vec<_>, _>>()
            .map_err(&err)?,
        RawValue::Map(map) if map.contains_key("glob") => {
            super::file_axis::glob_values(map, base).map_err(&err)?
        }
        RawValue::Map(map) if map.len() == 1 => {
            let (form, args) = map.first().ok_or_else(|| err(String::new()))?;
            let args = match args {
                RawValue::List(a) => a
                    .iter()
                    .map(RawValue::to_param_value)
                    .collect::<Result<Vec<_>, _>>()
                    .map_err(&err)?,
                _ => return Err(err(format!("'{form}' takes a list, e.g. {form}: [1, 5]"))),
            };
            match form.as_str() {
                "range" => range(&args).map_err(&err)?,
                "linspace" => spaced(&args, false).map_err(&err)?,
                "logspace" => spaced(&args, true).map_err(&err)?,
                other => {
                    return Err(err(format!(
                        "unknown axis form '{other}'{}; use range, linspace, logspace or glob",
                        crate::syntax::did_you_mean(
                            other,
                            ["range", "linspace", "logspace", "glob"].into_iter()
                        )
                    )))
                }
            }
        }
        _ => {
            return Err(err(String::from(
                "an axis is a list of values or one of {range: [...]}, {linspace: [...]}, {logspace: [...]}, {glob: 'scans/*.x3p'}",
            )))
        }
    };
    if values.is_empty() {
        return Err(err(String::from("an axis needs at least one value")));
    }
    Ok(values)
}

fn range(args: &[ParamValue]) -> Result<Vec<ParamValue>, String> {
    if !(2..=3).contains(&args.len()) {
        return Err(String::from(
            "range takes [first, last] or [first, last, step]",
        ));
    }
    if let (ParamValue::Int(a), ParamValue::Int(b)) = (&args[0], &args[1]) {
        let step = match args.get(2) {
            None => 1,
            Some(ParamValue::Int(s)) if *s > 0 => *s,
            Some(other) => return Err(format!("an integer range needs a step > 0, got {other}")),
        };
        if b < a {
            return Err(format!("range [{a}, {b}] is empty: last must be ≥ first"));
        }
        // i128: the span of two i64 values cannot overflow.
        let count = (i128::from(*b) - i128::from(*a)) / i128::from(step) + 1;
        if count > MAX_SCENARIOS as i128 {
            return Err(format!(
                "range has {count} values, more than {MAX_SCENARIOS}"
            ));
        }
        return Ok((0..count as i64)
            .map(|i| ParamValue::Int(a + i * step))
            .collect());
    }
    let (first, last, dim) = endpoints(&args[0], &args[1])?;
    let step = match args.get(2) {
        Some(s) => match s.as_dimensioned() {
            Some(v) if v.dimension == dim => v.si,
            _ => {
                return Err(format!(
                    "the step {s} must have the dimension of the end values ({})",
                    dim.name()
                ))
            }
        },
        None => {
            return Err(String::from(
                "a non-integer range needs a step: [first, last, step]",
            ))
        }
    };
    if step.is_nan() || step <= 0.0 || last < first {
        return Err(String::from("range needs last ≥ first and step > 0"));
    }
    let intervals = ((last - first) / step * (1.0 + 1e-12)).floor();
    if !intervals.is_finite() || intervals >= MAX_SCENARIOS as f64 {
        return Err(format!(
            "range has more than {MAX_SCENARIOS} values; use a larger step"
        ));
    }
    let count = intervals as usize + 1;
    Ok((0..count)
        .map(|i| quantity(first + i as f64 * step, dim))
        .collect())
}

fn spaced(args: &[ParamValue], geometric: bool) -> Result<Vec<ParamValue>, String> {
    let form = if geometric { "logspace" } else { "linspace" };
    let [a, b, n] = args else {
        return Err(format!("{form} takes [first, last, count]"));
    };
    let count = match n {
        ParamValue::Int(n) if *n >= 1 && (*n as usize) <= MAX_SCENARIOS => *n as usize,
        other => {
            return Err(format!(
                "{form} count must be a whole number ≥ 1, got {other}"
            ))
        }
    };
    let (first, last, dim) = endpoints(a, b)?;
    if geometric && !(first > 0.0 && last > 0.0) {
        return Err(String::from(
            "logspace needs positive end values (it spaces values geometrically between them)",
        ));
    }
    Ok((0..count)
        .map(|i| {
            let t = if count == 1 {
                0.0
            } else {
                i as f64 / (count - 1) as f64
            };
            let v = if geometric {
                (first.ln() + t * (last.ln() - first.ln())).exp()
            } else {
                first + t * (last - first)
            };
            // Pin the end points exactly: users compare against the values they wrote.
            let v = if i + 1 == count && count > 1 { last } else { v };
            quantity(v, dim)
        })
        .collect())
}

fn endpoints(a: &ParamValue, b: &ParamValue) -> Result<(f64, f64, Dimension), String> {
    match (a.as_dimensioned(), b.as_dimensioned()) {
        (Some(x), Some(y)) if x.dimension == y.dimension => {
            // Keep the whole span finite, so every generated value is finite too.
            if (y.si - x.si).is_finite() {
                Ok((x.si, y.si, x.dimension))
            } else {
                Err(format!(
                    "end values {a} and {b} span more than the floating-point range"
                ))
            }
        }
        (Some(x), Some(y)) => Err(format!(
            "end values have different dimensions: {a} is a {}, {b} is a {}",
            x.dimension.name(),
            y.dimension.name()
        )),
        _ => Err(format!(
            "end values must be numbers or quantities, got {a} and {b}"
        )),
    }
}

fn quantity(si: f64, dimension: Dimension) -> ParamValue {
    if dimension == Dimension::Dimensionless {
        ParamValue::Number(si)
    } else {
        ParamValue::Quantity(crate::units::DimensionedValue { si, dimension })
    }
}

fn latin_hypercube(lhs: &Located<LatinHypercube>) -> Result<Group, ParameterError> {
    let spec = &lhs.value;
    let err = |parameter: &str, location, message: String| ParameterError {
        location,
        parameter: parameter.to_string(),
        message,
    };
    if spec.samples == 0 || spec.samples > MAX_SCENARIOS {
        return Err(err(
            "latin_hypercube",
            lhs.location,
            format!("samples must be between 1 and {MAX_SCENARIOS}"),
        ));
    }
    if spec.ranges.is_empty() {
        return Err(err(
            "latin_hypercube",
            lhs.location,
            String::from("needs at least one range: `ranges: {name: [low, high]}`"),
        ));
    }
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(spec.seed);
    let n = spec.samples;
    let mut names = Vec::new();
    let mut columns = Vec::new();
    for (name, axis) in &spec.ranges {
        let bounds = match &axis.value.0 {
            RawValue::List(items) if items.len() == 2 => items
                .iter()
                .map(RawValue::to_param_value)
                .collect::<Result<Vec<_>, _>>()
                .map_err(|m| err(name, axis.location, m))?,
            _ => {
                return Err(err(
                    name,
                    axis.location,
                    String::from("a Latin-hypercube range is [low, high]"),
                ))
            }
        };
        let (low, high, dim) =
            endpoints(&bounds[0], &bounds[1]).map_err(|m| err(name, axis.location, m))?;
        if high <= low || high.is_nan() || low.is_nan() {
            return Err(err(name, axis.location, String::from("needs high > low")));
        }
        // Fisher–Yates permutation of the strata, then a uniform point inside each stratum.
        let mut strata: Vec<usize> = (0..n).collect();
        for i in (1..n).rev() {
            let j = (rng.next_u64() % (i as u64 + 1)) as usize;
            strata.swap(i, j);
        }
        let column: Vec<ParamValue> = strata
            .iter()
            .map(|&s| {
                let u = (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
                quantity(low + (high - low) * (s as f64 + u) / n as f64, dim)
            })
            .collect();
        names.push((name.clone(), axis.location));
        columns.push(column);
    }
    Ok(Group {
        names,
        rows: (0..n)
            .map(|i| columns.iter().map(|c| c[i].clone()).collect())
            .collect(),
    })
}
