//! Study files: the YAML format, its parsing with locations, and its static checks (names,
//! references, cycles, outputs). Node bodies are typed by the application's [`NodeSpec`].

mod error;
mod file_axis;
mod names;
mod overrides;
mod parameters;
mod summary_spec;
mod yaml_budget;

pub use crate::resolve::ResolveContext;
pub use crate::syntax::{
    did_you_mean, FromParamValue, Located, Param, RawValue, SourceLocation, SpannedName, SpecError,
};
pub use error::StudyError;
pub use names::{MAX_FILE_NAME_BYTES, MAX_NAME_BYTES, NAME_AFFIX_BYTES};
pub use overrides::{OverrideSyntaxError, ParameterOverride};
pub use parameters::{Axis, LatinHypercube, ParameterError, ParameterSpace, Scenarios};
pub use summary_spec::{split_metric, SummarySpec, RUN_TIME_METRIC};

use std::path::{Path, PathBuf};

use indexmap::IndexMap;
use petgraph::graph::DiGraph;
use serde::Deserialize;

use crate::columns::{key_column, SCENARIO, STATUS};
use crate::node::NodeSpec;

/// Name of the scenarios table, always available in `outputs`.
pub const SCENARIOS_TABLE: &str = "scenarios";

/// A study file as written.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(title = "asperity study", bound = "N: schemars::JsonSchema")]
pub struct StudyFile<N> {
    /// Study name: letters, digits, '-', '_' and '.', not starting with '.' or '-', at most 191
    /// bytes; results go to `results/<study>/`.
    pub study: Located<String>,
    /// Free text describing the study.
    #[serde(default)]
    pub description: Option<String>,
    /// Parameter axes and how they combine into scenarios. Omitted: one scenario.
    #[serde(default)]
    pub parameters: ParameterSpace,
    /// Named nodes: `name: {<kind>: {...}}`. Upstream nodes are referenced by name; parameters as
    /// `${name}`.
    pub nodes: IndexMap<String, Located<N>>,
    /// Tables to write (default: all). Only the nodes these tables need are computed.
    #[serde(default)]
    pub outputs: Option<Located<Vec<Located<String>>>>,
    /// Grouped summaries of node metrics over scenarios (mean, standard deviation, count): each
    /// becomes a table `summary_<name>`.
    #[serde(default)]
    pub summaries: IndexMap<String, Located<SummarySpec>>,
}

/// A parsed and statically checked study.
#[derive(Debug)]
pub struct Study<N> {
    pub path: PathBuf,
    pub source: String,
    /// blake3 hex digest of the study file's bytes.
    pub file_hash: String,
    pub file: StudyFile<N>,
    /// Node names in a topological order (upstream first).
    pub order: Vec<String>,
    /// Tables requested by `outputs` (all when omitted).
    pub outputs: Vec<String>,
    /// Command-line overrides applied to the parameter axes (`--set name=value`), in order.
    pub overrides: Vec<(String, String)>,
}

/// Largest study file read, bytes. The shipped studies are under 6 KiB and a study spelling out
/// 10⁵ parameter values is about 1 MiB; 16 MiB leaves room for generated studies, while a device,
/// a log file or a data file named by mistake is refused at once instead of being parsed.
pub const MAX_STUDY_FILE_BYTES: u64 = 16 << 20;

/// The text of the study file `path`: a regular file of at most [`MAX_STUDY_FILE_BYTES`] in
/// UTF-8; a FIFO, device or directory is refused before it is opened.
fn read_study_source(path: &Path) -> Result<String, String> {
    let bytes = crate::regular_file::read_regular(path, MAX_STUDY_FILE_BYTES, "study file")
        .map_err(|m| format!("cannot read the study file: {m}"))?;
    String::from_utf8(bytes).map_err(|e| {
        format!(
            "cannot read the study file: not UTF-8 text (invalid byte at offset {}); a study \
             file is YAML text",
            e.utf8_error().valid_up_to()
        )
    })
}

impl<N: NodeSpec> Study<N> {
    /// Reads, parses and checks a study file.
    pub fn load(path: &Path) -> Result<Self, StudyError> {
        let source = read_study_source(path).map_err(|message| StudyError {
            path: path.to_path_buf(),
            location: SourceLocation::default(),
            context: String::new(),
            message,
            snippet: None,
        })?;
        Self::from_source(path, source)
    }

    /// Parses and checks study text; `path` names it in errors and anchors relative paths.
    pub fn from_source(path: &Path, source: String) -> Result<Self, StudyError> {
        let file: StudyFile<N> = serde_saphyr::from_str(&source)
            .map_err(|e| StudyError::from_yaml(path, &source, &e))?;
        let err = |location, context: String, message: String| {
            StudyError::at(path, &source, location, context, message)
        };
        names::check_study_name(&file.study.value)
            .map_err(|m| err(file.study.location, String::from("study"), m))?;
        if file.nodes.is_empty() {
            let line = source
                .lines()
                .position(|l| l.starts_with("nodes:"))
                .map_or(0, |i| i as u64 + 1);
            return Err(err(
                SourceLocation { line, column: 1 },
                String::from("nodes"),
                String::from("a study needs at least one node"),
            ));
        }
        let order = check_graph(&file).map_err(|(loc, ctx, msg)| err(loc, ctx, msg))?;
        check_scenario_columns(&file).map_err(|(loc, ctx, msg)| err(loc, ctx, msg))?;
        let mut outputs = check_outputs(&file).map_err(|(loc, ctx, msg)| err(loc, ctx, msg))?;
        for table in
            summary_spec::check_summaries(&file).map_err(|(loc, ctx, msg)| err(loc, ctx, msg))?
        {
            if !outputs.contains(&table) {
                outputs.push(table);
            }
        }
        Ok(Self {
            file_hash: blake3::hash(source.as_bytes()).to_hex().to_string(),
            path: path.to_path_buf(),
            source,
            file,
            order,
            outputs,
            overrides: Vec::new(),
        })
    }

    /// Study name.
    pub fn name(&self) -> &str {
        &self.file.study.value
    }

    /// The folder relative paths in the study are resolved against.
    pub fn dir(&self) -> &Path {
        self.path.parent().unwrap_or_else(|| Path::new("."))
    }

    /// An error at a location of this study.
    pub fn error(
        &self,
        location: SourceLocation,
        context: impl Into<String>,
        message: impl Into<String>,
    ) -> StudyError {
        StudyError::at(&self.path, &self.source, location, context, message)
    }
}

/// A failed static check: where, what it concerns, the message.
type CheckError = (SourceLocation, String, String);

fn check_graph<N: NodeSpec>(file: &StudyFile<N>) -> Result<Vec<String>, CheckError> {
    let names: Vec<&str> = file.nodes.keys().map(String::as_str).collect();
    let mut graph = DiGraph::<&str, ()>::new();
    let indices: Vec<_> = names.iter().map(|n| graph.add_node(n)).collect();
    for (i, (name, node)) in file.nodes.iter().enumerate() {
        if !valid_node_name(name) {
            return Err((
                node.location,
                format!("nodes.{name}"),
                String::from(
                    "node names start with a letter and contain only letters, digits, '_' and '-'",
                ),
            ));
        }
        for upstream in node.value.upstream() {
            let target = &upstream.node.value;
            let Some(j) = names.iter().position(|n| n == target) else {
                return Err((
                    upstream.node.location,
                    format!("nodes.{name}.{}", node.value.kind()),
                    format!(
                        "{} refers to node '{target}', which does not exist{}; nodes: {}",
                        upstream.role,
                        did_you_mean(target, names.iter().copied()),
                        names.join(", ")
                    ),
                ));
            };
            if j == i {
                return Err((
                    upstream.node.location,
                    format!("nodes.{name}"),
                    String::from("a node cannot use itself as an upstream node"),
                ));
            }
            graph.add_edge(indices[j], indices[i], ());
        }
    }
    match petgraph::algo::toposort(&graph, None) {
        Ok(order) => Ok(order.into_iter().map(|i| graph[i].to_string()).collect()),
        Err(cycle) => {
            let name = graph[cycle.node_id()];
            let location = file.nodes.get(name).map(|n| n.location).unwrap_or_default();
            Err((
                location,
                format!("nodes.{name}"),
                String::from(
                    "the nodes form a cycle through this node; upstream references must form a DAG",
                ),
            ))
        }
    }
}

/// The parameters' columns of the scenarios table must not clash with each other or with the
/// columns the engine writes there (`scenario`, `<node>_key`, `status`).
fn check_scenario_columns<N: NodeSpec>(file: &StudyFile<N>) -> Result<(), CheckError> {
    let mut columns = names::Columns::default();
    columns.fixed(SCENARIO, "the scenario number");
    for node in file.nodes.keys() {
        columns.fixed(&key_column(node), &format!("the key of node '{node}'"));
    }
    columns.fixed(STATUS, "the scenario's status");
    let declared = file.parameters.declared_names();
    for (i, &(name, location)) in declared.iter().enumerate() {
        // A name declared twice is the parameter expansion's error, said as such there.
        if declared[..i].iter().any(|(n, _)| *n == name) {
            continue;
        }
        columns
            .add(name, format!("parameter '{name}'"))
            .map_err(|m| {
                (
                    location,
                    format!("parameters.{name}"),
                    format!("{m} in scenarios.parquet; rename the parameter"),
                )
            })?;
    }
    Ok(())
}

pub(super) fn valid_node_name(name: &str) -> bool {
    let mut chars = name.chars();
    matches!(chars.next(), Some(c) if c.is_ascii_alphabetic())
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
}

/// The requested tables: `outputs` as written, or when omitted the scenarios table and the table
/// of every node kind the study uses (never an empty table of a kind it does not use).
fn check_outputs<N: NodeSpec>(file: &StudyFile<N>) -> Result<Vec<String>, CheckError> {
    let mut known: Vec<&str> = vec![SCENARIOS_TABLE];
    known.extend(N::all_tables());
    let used: Vec<&str> = N::all_tables()
        .iter()
        .copied()
        .filter(|t| file.nodes.values().any(|n| n.value.table() == *t))
        .collect();
    let Some(outputs) = &file.outputs else {
        return Ok(std::iter::once(SCENARIOS_TABLE)
            .chain(used)
            .map(String::from)
            .collect());
    };
    let mut result = Vec::new();
    for table in &outputs.value {
        if !known.contains(&table.value.as_str()) {
            return Err((
                table.location,
                String::from("outputs"),
                format!(
                    "unknown table '{}'{}; tables: {}",
                    table.value,
                    did_you_mean(&table.value, known.iter().copied()),
                    known.join(", ")
                ),
            ));
        }
        if table.value != SCENARIOS_TABLE && !used.contains(&table.value.as_str()) {
            return Err((
                table.location,
                String::from("outputs"),
                format!(
                    "no node of the study writes table '{}'; tables of this study: {}",
                    table.value,
                    std::iter::once(SCENARIOS_TABLE)
                        .chain(used.iter().copied())
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            ));
        }
        if !result.contains(&table.value) {
            result.push(table.value.clone());
        }
    }
    if result.is_empty() {
        return Err((
            outputs.location,
            String::from("outputs"),
            format!(
                "lists no table; omit it to write all ({})",
                known.join(", ")
            ),
        ));
    }
    Ok(result)
}
