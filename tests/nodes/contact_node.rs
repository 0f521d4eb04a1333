//! The `contact` node through the engine: two synthetic surfaces, load steps, fields on demand.

use asperity::engine::cache::Cache;
use asperity::engine::execute::{execute, ExecuteOptions, NoProgress, RunReport};
use asperity::engine::plan::Plan;
use asperity::engine::study::Study;
use asperity::engine::value::Value;
use asperity::nodes::TribologyNode;

fn run(text: &str, cache: &std::path::Path) -> (Plan, RunReport) {
    let study =
        Study::<TribologyNode>::from_source(std::path::Path::new("contact.yaml"), text.to_string())
            .unwrap();
    let plan = Plan::build(&study).unwrap();
    let options = ExecuteOptions {
        tables: study.outputs.clone(),
        memory_budget: 1 << 32,
        tool_version: String::from("test"),
    };
    let report = execute(&plan, &Cache::open(cache).unwrap(), &options, &NoProgress).unwrap();
    (plan, report)
}

fn study(upper: &str, fields: bool) -> String {
    format!(
        r#"
study: contact
parameters:
  product:
    sq: [0.38 um, 1.19 um]
nodes:
  lower:
    surface:
      synthetic: {{grid: [64, 64], size: [0.25 mm, 0.25 mm], sq: "${{sq}}", hurst: 0.8,
                  correlation_length: 40 um, seed: 1}}
  upper:
    surface:
      synthetic: {{grid: [64, 64], size: [0.25 mm, 0.25 mm], sq: 1.19 um, hurst: 0.8,
                  correlation_length: 40 um, seed: 2}}
  pair:
    contact:
      lower: lower
{upper}      lower_material: {{youngs_modulus: 210 GPa, poisson_ratio: 0.3}}
      flow_pressure: 4 GPa
      nominal_pressures: [5 MPa, 10 MPa, 20 MPa]
      fields: {fields}
"#
    )
}

#[test]
fn contact_of_two_surfaces_is_load_stepped_and_cached() {
    let dir = std::env::temp_dir().join(format!("asperity-contact-node-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let upper =
        "      upper: upper\n      upper_material: {youngs_modulus: 210 GPa, poisson_ratio: 0.3}\n";
    let (plan, report) = run(&study(upper, true), &dir);
    assert!(report.all_ok(), "{:?}", report.outcomes);
    let contacts: Vec<_> = plan
        .nodes
        .iter()
        .enumerate()
        .filter(|(_, n)| n.task.kind() == "contact")
        .map(|(i, _)| report.outcomes[i].clone().unwrap())
        .collect();
    assert_eq!(contacts.len(), 2);
    for c in &contacts {
        let curve = &c.tables["load_curve"];
        let area = curve
            .columns
            .iter()
            .find(|col| col.name == "area_fraction")
            .unwrap();
        let asperity::engine::artifact::ColumnData::Float(a) = &area.data else {
            panic!("area fraction is not a float column")
        };
        assert_eq!(a.len(), 3);
        // The true contact area grows with the load and stays a small fraction at 20 MPa.
        assert!(a.windows(2).all(|w| w[1] > w[0]), "{a:?}");
        assert!(a[2] > 0.0 && a[2] < 0.2, "{a:?}");
        let theta = c.metrics.iter().find(|f| f.name == "stress_ratio").unwrap();
        let Value::Float(theta) = theta.value else {
            panic!()
        };
        assert!(theta > 0.0 && theta <= 1.0, "θ = {theta}");
    }
    // Fields were requested: they are in the cache and a rerun reuses everything.
    let cache = Cache::open(&dir).unwrap();
    let i = plan
        .nodes
        .iter()
        .position(|n| n.task.kind() == "contact")
        .unwrap();
    let entry = cache
        .load("contact", &plan.nodes[i].key, true)
        .unwrap()
        .unwrap();
    assert!(entry.artifact.arrays.contains_key("pressure"));
    let (_, again) = run(&study(upper, true), &dir);
    assert_eq!((again.computed, again.cached), (0, plan.nodes.len()));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn contact_against_a_rigid_flat_without_fields() {
    let dir = std::env::temp_dir().join(format!("asperity-contact-flat-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let (plan, report) = run(&study("", false), &dir);
    assert!(report.all_ok(), "{:?}", report.outcomes);
    let cache = Cache::open(&dir).unwrap();
    let i = plan
        .nodes
        .iter()
        .position(|n| n.task.kind() == "contact")
        .unwrap();
    let entry = cache
        .load("contact", &plan.nodes[i].key, true)
        .unwrap()
        .unwrap();
    assert!(entry.artifact.arrays.is_empty(), "no fields unless asked");
    let _ = std::fs::remove_dir_all(&dir);
}
