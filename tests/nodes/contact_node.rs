//! The `contact` node through the engine: two synthetic surfaces, load steps, fields on demand.

use asperity::engine::cache::Cache;
use asperity::engine::execute::{execute, ExecuteOptions, NoProgress, RunReport};
use asperity::engine::plan::Plan;
use asperity::engine::study::Study;
use asperity::engine::value::Value;
use asperity::nodes::TribologyNode;

use crate::nodes_common::{float, outcomes};

fn study_of(text: &str) -> Study<TribologyNode> {
    Study::<TribologyNode>::from_source(std::path::Path::new("contact.yaml"), text.to_string())
        .unwrap()
}

fn run(text: &str, cache: &std::path::Path) -> (Plan, RunReport) {
    let study = study_of(text);
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

/// A junction-shear friction node on the contact `pair` of `study`, and the tables to write.
fn with_friction(study: &str, outputs: &str) -> String {
    format!(
        "{study}  mu:
    friction:
      model: junction_shear
      contact: pair
      lower_material: {{youngs_modulus: 210 GPa, poisson_ratio: 0.3, hardness: 4 GPa}}
      upper_material: {{youngs_modulus: 210 GPa, poisson_ratio: 0.3, hardness: 4 GPa}}
{outputs}"
    )
}

/// The `nominal_pressures_Pa` parameter and the key of every contact instance of `plan`.
fn contact_instances(plan: &Plan) -> Vec<(Value, String)> {
    plan.nodes
        .iter()
        .filter(|n| n.task.kind() == "contact")
        .map(|n| {
            let pressures = n
                .task
                .params()
                .into_iter()
                .find(|f| f.column_name() == "nominal_pressures_Pa");
            (pressures.unwrap().value, n.key.to_string())
        })
        .collect()
}

fn plan_of(text: &str) -> Plan {
    Plan::build(&study_of(text)).unwrap()
}

#[test]
fn warm_start_steps_are_not_solved_when_no_table_shows_them() {
    let upper =
        "      upper: upper\n      upper_material: {youngs_modulus: 210 GPa, poisson_ratio: 0.3}\n";
    let stepped = study(upper, true);
    let last_only = stepped.replace("[5 MPa, 10 MPa, 20 MPa]", "[20 MPa]");
    assert_ne!(stepped, last_only);
    // Written: every step is solved and shown.
    let shown = plan_of(&with_friction(&stepped, ""));
    // Not written: only the last step is solved, and the instance is the one of a study that
    // lists it alone (same parameters, same key), whichever tables that study writes.
    let hidden = plan_of(&with_friction(&stepped, "outputs: [scenarios, friction]\n"));
    let alone = plan_of(&with_friction(&last_only, ""));
    let summaries = with_friction(
        &stepped,
        "outputs: [scenarios, friction]\nsummaries:\n  all:\n    metrics: [pair.area_fraction]\n",
    );
    let summarised = plan_of(&summaries);
    let (shown, hidden, alone) = (
        contact_instances(&shown),
        contact_instances(&hidden),
        contact_instances(&alone),
    );
    assert_eq!(hidden, alone);
    assert_eq!(shown.len(), 2);
    for ((full, full_key), (last, last_key)) in shown.iter().zip(&hidden) {
        let (Value::Floats(full), Value::Floats(last)) = (full, last) else {
            panic!("pressures are a list: {full:?} {last:?}")
        };
        assert_eq!(full, &[5e6, 1e7, 2e7]);
        assert_eq!(last, &[2e7]);
        assert_ne!(full_key, last_key);
    }
    // A summary of a contact metric writes the contacts table: every step is solved again.
    assert_eq!(contact_instances(&summarised), shown);

    // The last step solved alone agrees with the stepped one to the solver's tolerance.
    let dir = std::env::temp_dir().join(format!("asperity-contact-last-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let (plan_a, report_a) = run(&with_friction(&stepped, ""), &dir.join("a"));
    let (plan_b, report_b) = run(
        &with_friction(&stepped, "outputs: [scenarios, friction]\n"),
        &dir.join("b"),
    );
    assert!(report_a.all_ok() && report_b.all_ok());
    let finals = |plan: &Plan, report: &RunReport| -> Vec<(usize, f64, f64)> {
        outcomes(plan, report, "contact")
            .into_iter()
            .map(|o| {
                let steps = o.tables["load_curve"].columns[0].data.len();
                (
                    steps,
                    float(o, "area_fraction"),
                    float(o, "mean_separation"),
                )
            })
            .collect()
    };
    for ((steps_a, area_a, gap_a), (steps_b, area_b, gap_b)) in finals(&plan_a, &report_a)
        .into_iter()
        .zip(finals(&plan_b, &report_b))
    {
        assert_eq!((steps_a, steps_b), (3, 1));
        // 64² points: one point entering or leaving the contact moves A/A₀ by 1/4096.
        assert!((area_a - area_b).abs() <= 2.0 / 4096.0, "{area_a} {area_b}");
        // Every gap residual is below 1e-6 of the rms height, and the mean separation is a few
        // rms heights.
        assert!((gap_a - gap_b).abs() <= 1e-6 * gap_a, "{gap_a} {gap_b}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
