//! Planning: scenarios × named nodes → a DAG of unique node instances with content keys.
//!
//! Each named node is instantiated under each scenario's parameter values, upstream first. Two
//! instances with the same key (same kind, version, resolved parameters and upstream keys) are
//! one node shared by every scenario that needs it, whatever their names.

use std::cell::RefCell;
use std::collections::{HashMap, HashSet};
use std::fmt::Write as _;
use std::sync::Arc;

use crate::hash::{node_key, NodeKey};
use crate::node::{NodeSpec, NodeTask};
use crate::study::{ResolveContext, Scenarios, Study, StudyError};

/// One unique node instance.
#[derive(Debug, Clone)]
pub struct PlannedNode {
    pub key: NodeKey,
    pub task: Arc<dyn NodeTask>,
    /// The study node names that resolve to this instance.
    pub names: Vec<String>,
    /// `(role, instance index)` of each upstream instance, in the spec's order.
    pub upstream: Vec<(&'static str, usize)>,
}

/// The planned study.
#[derive(Debug)]
pub struct Plan {
    pub scenarios: Scenarios,
    /// Study node names in file order.
    pub node_names: Vec<String>,
    /// Unique instances, upstream before downstream.
    pub nodes: Vec<PlannedNode>,
    /// `scenario_nodes[s][n]`: instance index of study node `n` in scenario `s`.
    pub scenario_nodes: Vec<Vec<usize>>,
    /// Parameters that no node uses (a likely mistake, reported as a warning).
    pub unused_parameters: Vec<String>,
}

impl Plan {
    /// Builds the plan of a study.
    pub fn build<N: NodeSpec>(study: &Study<N>) -> Result<Self, StudyError> {
        let scenarios = study.file.parameters.expand(study.dir()).map_err(|e| {
            study.error(e.location, format!("parameters.{}", e.parameter), e.message)
        })?;
        let node_names: Vec<String> = study.file.nodes.keys().cloned().collect();
        let order: Vec<usize> = study
            .order
            .iter()
            .filter_map(|n| node_names.iter().position(|m| m == n))
            .collect();
        let used = RefCell::new(vec![false; scenarios.names.len()]);
        let file_hashes = RefCell::new(HashMap::new());
        let mut nodes: Vec<PlannedNode> = Vec::new();
        let mut by_key: HashMap<NodeKey, usize> = HashMap::new();
        let mut scenario_nodes = Vec::with_capacity(scenarios.rows.len());
        for row in &scenarios.rows {
            let mut instance_of = vec![usize::MAX; node_names.len()];
            for &n in &order {
                let name = &node_names[n];
                let spec = &study.file.nodes[n];
                let upstream_refs = spec.value.upstream();
                let mut upstream = Vec::with_capacity(upstream_refs.len());
                for r in &upstream_refs {
                    let u = node_names
                        .iter()
                        .position(|m| *m == r.node.value)
                        .map(|i| instance_of[i])
                        .filter(|&i| i != usize::MAX)
                        .ok_or_else(|| {
                            study.error(
                                r.node.location,
                                format!("nodes.{name}"),
                                format!("upstream node '{}' is not planned", r.node.value),
                            )
                        })?;
                    upstream.push((r.role, u));
                }
                let upstream_tasks: Vec<Arc<dyn NodeTask>> = upstream
                    .iter()
                    .map(|(_, u)| nodes[*u].task.clone())
                    .collect();
                let ctx = ResolveContext {
                    names: &scenarios.names,
                    values: row,
                    upstream: &upstream_tasks,
                    study_dir: study.dir(),
                    used: &used,
                    file_hashes: &file_hashes,
                };
                let task = spec.value.instantiate(&ctx).map_err(|e| {
                    study.error(
                        e.location,
                        format!("nodes.{name}.{}.{}", spec.value.kind(), e.field),
                        e.message,
                    )
                })?;
                let upstream_keys: Vec<(&str, NodeKey)> =
                    upstream.iter().map(|(r, u)| (*r, nodes[*u].key)).collect();
                let key = node_key(task.kind(), task.version(), &task.params(), &upstream_keys);
                let index = *by_key.entry(key).or_insert_with(|| {
                    nodes.push(PlannedNode {
                        key,
                        task,
                        names: Vec::new(),
                        upstream,
                    });
                    nodes.len() - 1
                });
                if !nodes[index].names.contains(name) {
                    nodes[index].names.push(name.clone());
                }
                instance_of[n] = index;
            }
            scenario_nodes.push(instance_of);
        }
        let used = used.into_inner();
        let unused_parameters = scenarios
            .names
            .iter()
            .zip(&used)
            .filter(|(_, u)| !**u)
            .map(|(n, _)| n.clone())
            .collect();
        Ok(Self {
            scenarios,
            node_names,
            nodes,
            scenario_nodes,
            unused_parameters,
        })
    }

    /// Instance indices needed to produce `tables`: the instances writing to those tables and
    /// everything upstream of them. Sorted (upstream first).
    pub fn needed_for(&self, tables: &[String]) -> Vec<usize> {
        let roots: Vec<usize> = (0..self.nodes.len())
            .filter(|&i| tables.iter().any(|t| t == self.nodes[i].task.table()))
            .collect();
        self.upstream_closure(&roots, None)
    }

    /// `roots` and every instance upstream of them (restricted to `within` when given), sorted
    /// (upstream first: instance indices are topologically ordered): the one walk of the
    /// instance DAG (edges: each node's `upstream` list).
    pub fn upstream_closure(&self, roots: &[usize], within: Option<&HashSet<usize>>) -> Vec<usize> {
        let mut seen: HashSet<usize> = HashSet::new();
        let mut stack: Vec<usize> = roots.to_vec();
        while let Some(i) = stack.pop() {
            if within.is_none_or(|w| w.contains(&i)) && seen.insert(i) {
                stack.extend(self.nodes[i].upstream.iter().map(|(_, u)| *u));
            }
        }
        let mut v: Vec<usize> = seen.into_iter().collect();
        v.sort_unstable();
        v
    }

    /// Graphviz DOT of the instance DAG; `cached(i)` marks instances already in the cache.
    pub fn to_dot(&self, cached: impl Fn(usize) -> bool) -> String {
        let mut out = String::from("digraph study {\n  rankdir=LR;\n  node [shape=box];\n");
        for (i, n) in self.nodes.iter().enumerate() {
            let style = if cached(i) {
                ", style=filled, fillcolor=\"#d9f2d9\""
            } else {
                ""
            };
            let _ = writeln!(
                out,
                "  n{i} [label=\"{}\\n{} {}\"{style}];",
                n.names.join(", "),
                n.task.kind(),
                n.key.short()
            );
        }
        for (i, n) in self.nodes.iter().enumerate() {
            for (role, u) in &n.upstream {
                let _ = writeln!(out, "  n{u} -> n{i} [label=\"{role}\"];");
            }
        }
        out.push_str("}\n");
        out
    }

    /// Mermaid flowchart of the instance DAG.
    pub fn to_mermaid(&self, cached: impl Fn(usize) -> bool) -> String {
        let mut out = String::from("flowchart LR\n");
        for (i, n) in self.nodes.iter().enumerate() {
            let mark = if cached(i) { " ✓" } else { "" };
            let _ = writeln!(
                out,
                "  n{i}[\"{}<br/>{} {}{mark}\"]",
                n.names.join(", "),
                n.task.kind(),
                n.key.short()
            );
        }
        for (i, n) in self.nodes.iter().enumerate() {
            for (role, u) in &n.upstream {
                let _ = writeln!(out, "  n{u} -->|{role}| n{i}");
            }
        }
        out
    }
}
