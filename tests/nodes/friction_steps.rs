//! Friction at every load step (`friction_curve`): each step of a per-spot, per-summit and
//! statistical node on a stepped contact equals the same node on the contact stopped at that
//! step, the last step is the row, and every step carries its own validity.

use asperity::engine::artifact::ColumnData;
use asperity::engine::execute::NodeOutcome;
use asperity::engine::plan::Plan;
use asperity::engine::value::Value;

use crate::nodes_common::{column, float, run, text};

/// Two rough bodies, the contact solved over three load steps (`c3`) and stopped after each
/// earlier step (`c1`, `c2`), and on each a per-spot, a per-summit and a statistical node.
fn study_text() -> String {
    let mut text = String::from(
        r#"
study: steps
nodes:
  a:
    surface:
      synthetic: {grid: [64, 64], size: [0.2 mm, 0.2 mm], sq: 0.4 um, hurst: 0.8,
                  correlation_length: 30 um, seed: 1}
  b:
    surface:
      synthetic: {grid: [64, 64], size: [0.2 mm, 0.2 mm], sq: 0.3 um, hurst: 0.7,
                  correlation_length: 25 um, seed: 2}
"#,
    );
    let loads = ["2 MPa", "2 MPa, 10 MPa", "2 MPa, 10 MPa, 40 MPa"];
    for (i, pressures) in loads.iter().enumerate() {
        let c = i + 1;
        text.push_str(&format!(
            "  c{c}:\n    contact: {{lower: a, upper: b, lower_material: s235jr, \
             upper_material: s235jr, nominal_pressures: [{pressures}], fields: true}}\n\
             \x20 spot{c}:\n    friction: {{method: per_spot, model: full_stick, contact: c{c}, \
             lower_material: s235jr, upper_material: s235jr}}\n\
             \x20 summit{c}:\n    friction: {{method: per_summit, model: kogut_etsion, \
             contact: c{c}, lower_material: s235jr, upper_material: s235jr}}\n\
             \x20 stat{c}:\n    friction: {{model: full_stick, lower: a, upper: b, contact: c{c}, \
             lower_material: s235jr, upper_material: s235jr}}\n"
        ));
    }
    text
}

/// The outcome of the node called `name`.
fn node<'a>(
    plan: &Plan,
    report: &'a asperity::engine::execute::RunReport,
    name: &str,
) -> &'a NodeOutcome {
    let i = plan
        .nodes
        .iter()
        .position(|n| n.names.iter().any(|m| m == name))
        .unwrap_or_else(|| panic!("no node {name}"));
    report.outcomes[i].as_ref().unwrap()
}

/// The value of column `name` of the `curve` table at `step`.
fn cell(o: &NodeOutcome, name: &str, step: usize) -> Value {
    let c = o.tables["curve"]
        .columns
        .iter()
        .find(|c| c.name == name)
        .unwrap_or_else(|| panic!("no curve column {name}"));
    match &c.data {
        ColumnData::Float(v) => Value::Float(v[step]),
        ColumnData::Int(v) => Value::Int(v[step]),
        ColumnData::Bool(v) => Value::Bool(v[step]),
        ColumnData::Text(v) => Value::Text(v[step].clone()),
    }
}

/// `a` and `b` within `relative` of the larger magnitude (exactly equal when `relative` is 0).
fn close(a: f64, b: f64, relative: f64) -> bool {
    (a - b).abs() <= relative * a.abs().max(b.abs())
}

#[test]
fn every_step_equals_the_node_on_the_contact_stopped_there() {
    let (plan, report) = run(&study_text(), "steps");
    assert!(report.all_ok(), "{:?}", report.outcomes);
    for method in ["spot", "summit", "stat"] {
        let stepped = node(&plan, &report, &format!("{method}3"));
        let curve = &stepped.tables["curve"];
        assert_eq!(curve.rows(), 3, "{method}");
        let steps: Vec<i64> = match &curve.columns[0].data {
            ColumnData::Int(v) => v.clone(),
            other => panic!("{other:?}"),
        };
        assert_eq!(curve.columns[0].name, "step");
        assert_eq!(steps, [0, 1, 2]);
        // The last step is the row, every metric of it, bit for bit.
        for field in &stepped.metrics {
            assert_eq!(
                cell(stepped, &field.name, 2),
                field.value,
                "{method} {}",
                field.name
            );
        }
        assert_eq!(
            column(stepped, "curve", "nominal_pressure"),
            [2e6, 10e6, 40e6],
            "{method}"
        );
        for step in 0..2 {
            let stopped = node(&plan, &report, &format!("{method}{}", step + 1));
            // The statistical steps are solved each alone: bit for bit. The earlier steps'
            // maps of the contact are derived from their pressure (equal to the solver's to
            // 1e-12 of each map's largest value), so the per-spot and per-summit sums agree to
            // round-off.
            let tolerance = if method == "stat" { 0.0 } else { 1e-9 };
            for field in &stopped.metrics {
                match (&field.value, cell(stepped, &field.name, step)) {
                    (Value::Float(a), Value::Float(b)) => assert!(
                        close(*a, b, tolerance) || (a.abs() < 1e-30 && b.abs() < 1e-30),
                        "{method} step {step} {}: {a} vs {b}",
                        field.name
                    ),
                    (value, other) => {
                        assert_eq!(*value, other, "{method} step {step} {}", field.name)
                    }
                }
            }
            assert_eq!(
                cell(stepped, "step_status", step),
                Value::Text(stopped.label().to_string()),
                "{method} step {step}"
            );
        }
        assert_eq!(
            text(stepped, "method"),
            text(node(&plan, &report, &format!("{method}1")), "method")
        );
        let mu = column(stepped, "curve", "mu_s");
        assert!(
            mu.iter().all(|m| m.is_finite() && *m >= 0.0),
            "{method}: {mu:?}"
        );
        assert_eq!(mu[2], float(stepped, "mu_s"));
    }
}
