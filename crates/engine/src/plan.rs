//! Planning: scenarios × named nodes → a DAG of unique node instances with content keys.
//!
//! Each named node is instantiated under each scenario's parameter values, upstream first. Two
//! instances with the same key (same kind, version, resolved parameters and upstream keys) are
//! one node shared by every scenario that needs it, whatever their names.
//!
//! Scenarios are resolved in parallel, each with its own upstream tasks (instances with one key
//! are interchangeable: the key is exactly what determines a result), and then merged in scenario
//! order, so the instances, their order and the first error found are those of resolving the
//! scenarios one after the other, whatever the thread count.

use std::cell::RefCell;
use std::collections::HashSet;
use std::fmt::Write as _;
use std::sync::{Arc, Mutex};

use rayon::prelude::*;

use crate::hash::{node_key, KeyMap, NodeKey};
use crate::node::{NodeSpec, NodeTask};
use crate::resolve::FileHashes;
use crate::study::{ResolveContext, Scenarios, Study, StudyError};
use crate::value::ParamValue;

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

/// Scenarios resolved by one parallel task before they are merged: the task and key of each node
/// of each scenario (scenario after scenario, nodes in topological order), and which parameters
/// the scenarios used.
type Resolved = Result<(Vec<(Arc<dyn NodeTask>, NodeKey)>, Vec<bool>), StudyError>;

/// Scenarios resolved while the block before them is merged (bounds the tasks held before
/// deduplication).
const BLOCK: usize = 1 << 12;

/// Scenarios per parallel task.
const CHUNK: usize = 128;

/// Instances the plan makes room for at once (more are added as they come).
const INITIAL_CAPACITY: usize = 1 << 20;

impl Plan {
    /// Builds the plan of a study.
    pub fn build<N: NodeSpec>(study: &Study<N>) -> Result<Self, StudyError> {
        let scenarios = study.file.parameters.expand(study.dir()).map_err(|e| {
            study.error(e.location, format!("parameters.{}", e.parameter), e.message)
        })?;
        let node_names: Vec<String> = study.file.nodes.keys().cloned().collect();
        let resolver = Resolver::new(study, &scenarios.names, &node_names)?;
        let instances = scenarios.rows.len().saturating_mul(resolver.order.len());
        let mut merge = Merge::new(scenarios.rows.len(), instances, scenarios.names.len());
        let mut pending: Vec<Resolved> = Vec::new();
        for block in scenarios.rows.chunks(BLOCK) {
            let (resolved, merged) = rayon::join(
                || resolver.resolve_block(block),
                || merge.add_block(&resolver, std::mem::take(&mut pending)),
            );
            merged?;
            pending = resolved;
        }
        merge.add_block(&resolver, pending)?;
        merge.nodes.shrink_to_fit();
        let unused_parameters = scenarios
            .names
            .iter()
            .zip(&merge.used)
            .filter(|(_, u)| !**u)
            .map(|(n, _)| n.clone())
            .collect();
        Ok(Self {
            scenarios,
            node_names,
            nodes: merge.nodes,
            scenario_nodes: merge.scenario_nodes,
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

/// What resolving a scenario needs from the study: the node specs in topological order and the
/// upstream links between them.
struct Resolver<'a, N> {
    study: &'a Study<N>,
    parameter_names: &'a [String],
    /// Study node names in file order.
    node_names: &'a [String],
    /// File index of each node, in topological order.
    order: Vec<usize>,
    /// `links[p]`: `(role, position in order)` of each upstream node of the node at position `p`.
    links: Vec<Vec<(&'static str, usize)>>,
    file_hashes: FileHashes,
}

impl<'a, N: NodeSpec> Resolver<'a, N> {
    fn new(
        study: &'a Study<N>,
        parameter_names: &'a [String],
        node_names: &'a [String],
    ) -> Result<Self, StudyError> {
        let order: Vec<usize> = study
            .order
            .iter()
            .filter_map(|n| node_names.iter().position(|m| m == n))
            .collect();
        let mut links = Vec::with_capacity(order.len());
        for (p, &n) in order.iter().enumerate() {
            let mut upstream = Vec::new();
            for r in study.file.nodes[n].value.upstream() {
                let position = order[..p]
                    .iter()
                    .position(|&m| node_names[m] == r.node.value)
                    .ok_or_else(|| {
                        study.error(
                            r.node.location,
                            format!("nodes.{}", node_names[n]),
                            format!("upstream node '{}' is not planned", r.node.value),
                        )
                    })?;
                upstream.push((r.role, position));
            }
            links.push(upstream);
        }
        Ok(Self {
            study,
            parameter_names,
            node_names,
            order,
            links,
            file_hashes: Mutex::default(),
        })
    }

    /// Resolves a block of scenarios in parallel, in chunks of consecutive scenarios.
    fn resolve_block(&self, block: &[Vec<ParamValue>]) -> Vec<Resolved> {
        block
            .par_chunks(CHUNK)
            .map(|rows| {
                let used = RefCell::new(vec![false; self.parameter_names.len()]);
                let mut resolved = Vec::with_capacity(rows.len() * self.order.len());
                for row in rows {
                    self.resolve_scenario(row, &used, &mut resolved)?;
                }
                Ok((resolved, used.into_inner()))
            })
            .collect()
    }

    /// Instantiates and keys every node of one scenario, upstream first, appending them to `out`.
    fn resolve_scenario(
        &self,
        row: &[ParamValue],
        used: &RefCell<Vec<bool>>,
        out: &mut Vec<(Arc<dyn NodeTask>, NodeKey)>,
    ) -> Result<(), StudyError> {
        let first = out.len();
        for (&n, links) in self.order.iter().zip(&self.links) {
            let own = &out[first..];
            let spec = &self.study.file.nodes[n].value;
            let upstream: Vec<Arc<dyn NodeTask>> =
                links.iter().map(|&(_, u)| own[u].0.clone()).collect();
            let ctx = ResolveContext {
                names: self.parameter_names,
                values: row,
                upstream: &upstream,
                study_dir: self.study.dir(),
                used,
                file_hashes: &self.file_hashes,
                tables: &self.study.outputs,
            };
            let task = spec.instantiate(&ctx).map_err(|e| {
                self.study.error(
                    e.location,
                    format!("nodes.{}.{}.{}", self.node_names[n], spec.kind(), e.field),
                    e.message,
                )
            })?;
            let upstream_keys: Vec<(&str, NodeKey)> =
                links.iter().map(|&(role, u)| (role, own[u].1)).collect();
            let key = node_key(task.kind(), task.version(), &task.params(), &upstream_keys);
            out.push((task, key));
        }
        Ok(())
    }
}

/// The instances found so far, deduplicated by key in scenario order.
struct Merge {
    nodes: Vec<PlannedNode>,
    by_key: KeyMap<usize>,
    scenario_nodes: Vec<Vec<usize>>,
    /// Which parameters the scenarios merged so far used.
    used: Vec<bool>,
    /// The instance of each node of the scenario being added, in topological order.
    instance_at: Vec<usize>,
}

impl Merge {
    /// A merge of `scenarios` scenarios of at most `instances` instances.
    fn new(scenarios: usize, instances: usize, parameters: usize) -> Self {
        let capacity = instances.min(INITIAL_CAPACITY);
        Self {
            nodes: Vec::with_capacity(capacity),
            by_key: KeyMap::with_capacity_and_hasher(capacity, Default::default()),
            scenario_nodes: Vec::with_capacity(scenarios),
            used: vec![false; parameters],
            instance_at: Vec::new(),
        }
    }

    /// Adds the chunks of a resolved block in order; the first error found is the first of the
    /// block's scenarios.
    fn add_block<N>(
        &mut self,
        r: &Resolver<'_, N>,
        block: Vec<Resolved>,
    ) -> Result<(), StudyError> {
        for chunk in block {
            let (instances, used) = chunk?;
            self.used.iter_mut().zip(used).for_each(|(u, c)| *u |= c);
            let mut instances = instances.into_iter();
            while instances.len() > 0 {
                self.add(r, instances.by_ref().take(r.order.len()));
            }
        }
        Ok(())
    }

    /// Adds one resolved scenario: each node becomes a new instance or joins the one with its key.
    fn add<N>(
        &mut self,
        r: &Resolver<'_, N>,
        scenario: impl Iterator<Item = (Arc<dyn NodeTask>, NodeKey)>,
    ) {
        let mut instance_of = vec![usize::MAX; r.node_names.len()];
        self.instance_at.clear();
        for (p, (task, key)) in scenario.enumerate() {
            let instance_at = &self.instance_at;
            let index = *self.by_key.entry(key).or_insert_with(|| {
                let upstream = r.links[p]
                    .iter()
                    .map(|&(role, u)| (role, instance_at[u]))
                    .collect();
                self.nodes.push(PlannedNode {
                    key,
                    task,
                    names: Vec::new(),
                    upstream,
                });
                self.nodes.len() - 1
            });
            let name = &r.node_names[r.order[p]];
            if !self.nodes[index].names.contains(name) {
                self.nodes[index].names.push(name.clone());
            }
            self.instance_at.push(index);
            instance_of[r.order[p]] = index;
        }
        self.scenario_nodes.push(instance_of);
    }
}
