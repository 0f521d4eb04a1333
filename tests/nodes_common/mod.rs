//! Helpers of the friction-node tests: run a study text through the engine on a fresh cache
//! and read the outcomes' metrics and tables.
#![allow(dead_code)]

use std::collections::BTreeMap;

use asperity::engine::artifact::{Artifact, ColumnData};
use asperity::engine::cache::Cache;
use asperity::engine::execute::{execute, ExecuteOptions, NoProgress, NodeOutcome, RunReport};
use asperity::engine::plan::Plan;
use asperity::engine::study::Study;
use asperity::engine::value::Value;
use asperity::nodes::TribologyNode;

pub fn study(text: &str) -> Study<TribologyNode> {
    Study::<TribologyNode>::from_source(std::path::Path::new("friction.yaml"), text.to_string())
        .unwrap()
}

pub fn run(text: &str, name: &str) -> (Plan, RunReport) {
    let dir = std::env::temp_dir().join(format!("asperity-friction-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let study = study(text);
    let plan = Plan::build(&study).unwrap();
    let options = ExecuteOptions {
        tables: study.outputs.clone(),
        memory_budget: 1 << 32,
        tool_version: String::from("test"),
    };
    let report = execute(&plan, &Cache::open(&dir).unwrap(), &options, &NoProgress).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    (plan, report)
}

/// The two bodies of the two-body friction tests, `nodes:` entries of a study: `rough`, 64² over
/// 64 µm, Sq 0.4 µm (seed 5), and `smooth`, Sq 2 nm (seed 6), both H 0.8 with a 16 µm
/// correlation length.
const ROUGH_AND_SMOOTH: &str = r#"
  rough:
    surface:
      synthetic: {grid: [64, 64], size: [64 um, 64 um], sq: 0.4 um, hurst: 0.8,
                  correlation_length: 16 um, seed: 5}
  smooth:
    surface:
      synthetic: {grid: [64, 64], size: [64 um, 64 um], sq: 2 nm, hurst: 0.8,
                  correlation_length: 16 um, seed: 6}
"#;

/// The study `name` whose nodes are the bodies `rough` and `smooth` ([`ROUGH_AND_SMOOTH`]) and
/// `nodes` (further `nodes:` entries, indented by two spaces).
pub fn rough_and_smooth(name: &str, nodes: &str) -> String {
    format!(
        "study: {name}\nnodes:{ROUGH_AND_SMOOTH}{}",
        nodes.trim_start_matches('\n')
    )
}

/// Every node of the plan computed in plan order (no engine, no cache), by name.
pub fn compute_all(plan: &Plan) -> BTreeMap<String, Artifact> {
    let mut done: Vec<Artifact> = Vec::new();
    for node in &plan.nodes {
        let inputs: Vec<&Artifact> = node.upstream.iter().map(|(_, u)| &done[*u]).collect();
        done.push(node.task.compute(&inputs).unwrap());
    }
    plan.nodes
        .iter()
        .map(|n| n.names[0].clone())
        .zip(done)
        .collect()
}

pub fn plan_error(text: &str) -> String {
    match Study::<TribologyNode>::from_source(std::path::Path::new("f.yaml"), text.to_string()) {
        Ok(study) => Plan::build(&study)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default(),
        Err(e) => e.to_string(),
    }
}

/// The outcomes of every instance of `kind`, in plan order.
pub fn outcomes<'a>(plan: &Plan, report: &'a RunReport, kind: &str) -> Vec<&'a NodeOutcome> {
    plan.nodes
        .iter()
        .zip(&report.outcomes)
        .filter(|(n, _)| n.task.kind() == kind)
        .map(|(_, o)| o.as_ref().unwrap())
        .collect()
}

pub fn float(o: &NodeOutcome, name: &str) -> f64 {
    match o.metrics.iter().find(|f| f.name == name).map(|f| &f.value) {
        Some(Value::Float(v)) => *v,
        other => panic!("metric {name}: {other:?}"),
    }
}

pub fn int(o: &NodeOutcome, name: &str) -> i64 {
    match o.metrics.iter().find(|f| f.name == name).map(|f| &f.value) {
        Some(Value::Int(v)) => *v,
        other => panic!("metric {name}: {other:?}"),
    }
}

pub fn boolean(o: &NodeOutcome, name: &str) -> bool {
    match o.metrics.iter().find(|f| f.name == name).map(|f| &f.value) {
        Some(Value::Bool(v)) => *v,
        other => panic!("metric {name}: {other:?}"),
    }
}

pub fn text<'a>(o: &'a NodeOutcome, name: &str) -> &'a str {
    match o.metrics.iter().find(|f| f.name == name).map(|f| &f.value) {
        Some(Value::Text(v)) => v,
        other => panic!("metric {name}: {other:?}"),
    }
}

pub fn column(o: &NodeOutcome, table: &str, name: &str) -> Vec<f64> {
    let t = &o.tables[table];
    match &t.columns.iter().find(|c| c.name == name).unwrap().data {
        ColumnData::Float(v) => v.clone(),
        other => panic!("{name}: {other:?}"),
    }
}
