//! The scenario table as the report groups it: parameters (swept or constant, replicate or
//! not) and, per node, the key of the instance each scenario uses.
//!
//! **Replicate axes** are parameters whose scenarios are repetitions of one configuration
//! (different random realisations); trends average over them (mean ± sample standard
//! deviation). Unless the user names them, a parameter is a replicate axis when its name is
//! `seed`, starts with `seed_` or ends with `_seed`, or is `replicate`, `realisation`,
//! `realization` or `repetition`. A parameter that is a function of an earlier swept parameter
//! (zipped with it, e.g. a correlation length that follows Sq) is not a separate axis.

use std::collections::BTreeMap;

use super::error::ReportError;
use super::quantity::{base_name, short_name, DisplayUnit};
use super::table::ResultTable;

/// Parameter names that are replicate axes by default (besides the `seed` patterns).
const REPLICATE_NAMES: [&str; 4] = ["replicate", "realisation", "realization", "repetition"];

/// One study parameter (a column of `scenarios.parquet`).
#[derive(Debug, Clone, PartialEq)]
pub struct Parameter {
    /// The parameter name (`sq`), the column without its unit suffix.
    pub name: String,
    /// SI unit (`m`), `""` when dimensionless.
    pub unit: String,
    /// Value per scenario: SI numbers, or for a text parameter the index into `categories`.
    pub values: Vec<Option<f64>>,
    /// The distinct values of a text parameter; empty for numeric ones.
    pub categories: Vec<String>,
    pub replicate: bool,
    /// How the values are shown.
    pub display: DisplayUnit,
}

impl Parameter {
    /// Number of distinct values.
    pub fn distinct(&self) -> usize {
        let mut bits: Vec<u64> = self.values.iter().flatten().map(|v| v.to_bits()).collect();
        bits.sort_unstable();
        bits.dedup();
        bits.len()
    }

    /// `Sq = 1.19 µm`, `material = steel`.
    pub fn describe(&self, value: Option<f64>) -> String {
        let text = match value {
            None => String::from("—"),
            Some(v) if !self.categories.is_empty() => {
                self.categories.get(v as usize).cloned().unwrap_or_default()
            }
            Some(v) => self.display.format(v),
        };
        format!("{} = {text}", short_name(&self.name))
    }
}

/// The node instances one named node resolves to, per scenario.
#[derive(Debug, Clone, PartialEq)]
pub struct NodeLink {
    /// The node name (`pair`), from the `<node>_key` column.
    pub node: String,
    pub keys: Vec<Option<String>>,
}

/// The scenarios of a results folder.
#[derive(Debug, Clone, PartialEq)]
pub struct ScenarioSet {
    pub count: usize,
    pub parameters: Vec<Parameter>,
    pub nodes: Vec<NodeLink>,
    /// Whether the replicate axes were named by the user (`--replicate`) or detected by name.
    pub replicates_named: bool,
}

fn is_default_replicate(name: &str) -> bool {
    name == "seed"
        || name.starts_with("seed_")
        || name.ends_with("_seed")
        || REPLICATE_NAMES.contains(&name)
}

impl ScenarioSet {
    /// Reads the parameters and node links of `scenarios.parquet`; `replicates` names the
    /// replicate axes (`None`: detect them by name).
    pub fn from_table(
        table: &ResultTable,
        replicates: Option<&[String]>,
    ) -> Result<Self, ReportError> {
        let mut parameters = Vec::new();
        let mut nodes = Vec::new();
        for (column, _) in &table.columns {
            if column == "scenario" || column == "status" {
                continue;
            }
            if let Some(node) = column.strip_suffix("_key") {
                if let Some(keys) = table.texts(column) {
                    nodes.push(NodeLink {
                        node: node.to_string(),
                        keys: keys.to_vec(),
                    });
                    continue;
                }
            }
            let unit = table.unit(column).to_string();
            let name = base_name(column, &unit).to_string();
            let (values, categories) = if let Some(v) = table.numbers(column) {
                (v.to_vec(), Vec::new())
            } else if let Some(texts) = table.texts(column) {
                let mut categories: Vec<String> = Vec::new();
                let values = texts
                    .iter()
                    .map(|t| {
                        t.as_ref().map(|t| {
                            let i = categories.iter().position(|c| c == t).unwrap_or_else(|| {
                                categories.push(t.clone());
                                categories.len() - 1
                            });
                            i as f64
                        })
                    })
                    .collect();
                (values, categories)
            } else {
                continue;
            };
            let display = DisplayUnit::for_slice(&unit, values.iter().flatten().copied());
            parameters.push(Parameter {
                replicate: is_default_replicate(&name),
                name,
                unit,
                values,
                categories,
                display,
            });
        }
        if let Some(named) = replicates {
            for name in named {
                if !parameters.iter().any(|p| &p.name == name) {
                    return Err(ReportError::UnknownReplicate {
                        name: name.clone(),
                        known: parameters
                            .iter()
                            .map(|p| p.name.as_str())
                            .collect::<Vec<_>>()
                            .join(", "),
                    });
                }
            }
            for p in &mut parameters {
                p.replicate = named.contains(&p.name);
            }
        }
        Ok(Self {
            count: table.rows,
            parameters,
            nodes,
            replicates_named: replicates.is_some(),
        })
    }

    /// Indices of the swept parameters that are not replicate axes (more than one value).
    /// A parameter whose value is determined by an earlier swept one (a zipped texture value
    /// that follows Sq, say) is not an axis of its own: it moves with that one.
    pub fn swept(&self) -> Vec<usize> {
        let mut axes: Vec<usize> = Vec::new();
        for j in 0..self.parameters.len() {
            let p = &self.parameters[j];
            if p.replicate || p.distinct() < 2 {
                continue;
            }
            if !axes.iter().any(|&i| self.determines(i, j)) {
                axes.push(j);
            }
        }
        axes
    }

    /// Whether every two scenarios with equal values of parameter `i` have equal values of `j`.
    fn determines(&self, i: usize, j: usize) -> bool {
        let mut seen: BTreeMap<Option<u64>, Option<u64>> = BTreeMap::new();
        (0..self.count).all(|s| {
            let vi = self.value(i, s).map(f64::to_bits);
            let vj = self.value(j, s).map(f64::to_bits);
            *seen.entry(vi).or_insert(vj) == vj
        })
    }

    /// Names of the replicate axes that vary.
    pub fn replicate_names(&self) -> Vec<&str> {
        self.parameters
            .iter()
            .filter(|p| p.replicate && p.distinct() > 1)
            .map(|p| p.name.as_str())
            .collect()
    }

    /// Scenario indices grouped by the values of the parameters `by` (in order of first
    /// appearance), each group with its label (`Sq = 0.38 µm, angle = 0°`).
    pub fn groups(&self, by: &[usize]) -> Vec<(String, Vec<usize>)> {
        let mut order: Vec<Vec<Option<u64>>> = Vec::new();
        let mut members: BTreeMap<Vec<Option<u64>>, Vec<usize>> = BTreeMap::new();
        for s in 0..self.count {
            let key: Vec<Option<u64>> = by
                .iter()
                .map(|&p| self.value(p, s).map(f64::to_bits))
                .collect();
            if !members.contains_key(&key) {
                order.push(key.clone());
            }
            members.entry(key).or_default().push(s);
        }
        order
            .into_iter()
            .filter_map(|key| members.remove(&key))
            .map(|scenarios| {
                let label = scenarios
                    .first()
                    .map(|&s| self.describe(s, by))
                    .unwrap_or_default();
                (label, scenarios)
            })
            .collect()
    }

    /// The value of parameter `p` in scenario `s`.
    pub fn value(&self, p: usize, s: usize) -> Option<f64> {
        self.parameters
            .get(p)
            .and_then(|p| p.values.get(s).copied().flatten())
    }

    /// `Sq = 0.38 µm, seed = 2` for the parameters `params` of scenario `s`.
    pub fn describe(&self, s: usize, params: &[usize]) -> String {
        params
            .iter()
            .filter_map(|&p| {
                self.parameters
                    .get(p)
                    .map(|par| par.describe(self.value(p, s)))
            })
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The node links whose keys are rows of `table` (judged by the first key present).
    pub fn links_into<'a>(
        &'a self,
        index: &'a BTreeMap<String, usize>,
    ) -> impl Iterator<Item = &'a NodeLink> + 'a {
        self.nodes.iter().filter(move |link| {
            link.keys
                .iter()
                .flatten()
                .next()
                .is_some_and(|k| index.contains_key(k))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parameter(name: &str, values: &[f64]) -> Parameter {
        Parameter {
            name: name.to_string(),
            unit: String::new(),
            values: values.iter().map(|&v| Some(v)).collect(),
            categories: Vec::new(),
            replicate: is_default_replicate(name),
            display: DisplayUnit::none(),
        }
    }

    #[test]
    fn zipped_parameters_that_follow_an_axis_are_not_axes() {
        let set = ScenarioSet {
            count: 6,
            parameters: vec![
                parameter("sq", &[1.0, 1.0, 2.0, 2.0, 3.0, 3.0]),
                parameter("lambda", &[10.0, 10.0, 20.0, 20.0, 30.0, 30.0]),
                parameter("seed_i", &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]),
                parameter("load", &[5.0, 9.0, 5.0, 9.0, 5.0, 9.0]),
            ],
            nodes: Vec::new(),
            replicates_named: false,
        };
        // `lambda` moves with `sq`; `seed_i` is a replicate axis; `load` is independent.
        assert_eq!(set.swept(), [0, 3]);
    }
}
