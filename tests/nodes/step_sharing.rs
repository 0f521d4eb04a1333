//! The earlier load steps' displacements `u = K p` are convolved once per contact, by the
//! contact, for all its consumers: its artifact holds them (when computed, and derived again
//! when read from the cache), the per-spot and per-summit nodes read them instead of convolving
//! each step themselves, and the maps they give equal, bit for bit, those a consumer derives
//! alone from the step's pressure (the unshared path, `contact::fields_from_pressure`).

use asperity::contact::{
    fields_from_pressure, Boundary, CompositeGap, ContactMaterial, ContactProblem, FieldRequest,
};
use asperity::engine::artifact::{Artifact, ColumnData};
use asperity::engine::cache::Cache;
use asperity::engine::execute::{execute, ExecuteOptions, NoProgress, NodeOutcome, RunReport};
use asperity::engine::plan::Plan;
use asperity::materials::{find_material, BodyMaterial, MaterialPair};
use asperity::nodes::ContactTask;
use ndarray::{Array2, Axis, Ix2, Ix3};

use crate::nodes_common::{compute_all, study};

/// Two rough bodies in contact over three load steps with fields, read by two per-spot nodes
/// (one ploughing: the deformed bodies' fronts) and a per-summit node.
const STUDY: &str = r#"
study: sharing
nodes:
  a:
    surface:
      synthetic: {grid: [64, 48], size: [0.2 mm, 0.15 mm], sq: 0.4 um, hurst: 0.8,
                  correlation_length: 30 um, seed: 1}
  b:
    surface:
      synthetic: {grid: [64, 48], size: [0.2 mm, 0.15 mm], sq: 0.3 um, hurst: 0.7,
                  correlation_length: 25 um, seed: 2}
  c:
    contact: {lower: a, upper: b, lower_material: s235jr, upper_material: s235jr,
              nominal_pressures: [2 MPa, 10 MPa, 40 MPa], fields: true}
  spot:
    friction: {method: per_spot, model: full_stick, contact: c, lower_material: s235jr,
               upper_material: s235jr}
  plough:
    friction: {model: ploughing, contact: c, lower_material: s235jr, upper_material: s235jr}
  summit:
    friction: {method: per_summit, model: kogut_etsion, contact: c, lower_material: s235jr,
               upper_material: s235jr}
"#;

const CONSUMERS: [&str; 3] = ["spot", "plough", "summit"];

fn index(plan: &Plan, name: &str) -> usize {
    plan.nodes.iter().position(|n| n.names[0] == name).unwrap()
}

/// The float column `name` of the contact's load curve.
fn load_curve(contact: &Artifact, name: &str) -> Vec<f64> {
    let column = contact.tables["load_curve"]
        .columns
        .iter()
        .find(|c| c.name == name)
        .unwrap();
    match &column.data {
        ColumnData::Float(v) => v.clone(),
        other => panic!("{other:?}"),
    }
}

/// The maps of earlier step `step` as a consumer derived them alone before the contact shared
/// its convolutions: the problem rebuilt on the contact's composite height, the step's pressure
/// convolved by a new operator.
fn unshared(contact: &Artifact, step: usize) -> asperity::contact::ContactFields {
    let z = contact.arrays["composite_height"]
        .view()
        .into_dimensionality::<Ix2>()
        .unwrap();
    let metric = |name: &str| match contact.metric(name).unwrap().value {
        asperity::engine::value::Value::Float(v) => v,
        ref other => panic!("{other:?}"),
    };
    let gap = CompositeGap::from_gap_array(z.mapv(|h| -h).view(), metric("dx"), metric("dy"));
    let s235jr = BodyMaterial::new(find_material("s235jr").unwrap().constants).unwrap();
    let material = ContactMaterial::new(MaterialPair::new(s235jr, Some(s235jr)));
    let problem = ContactProblem::new(gap.unwrap(), material, Boundary::Periodic);
    let points = &contact.arrays[&format!("pressure_step_{step}")];
    let mut pressure = Array2::<f64>::zeros(z.dim());
    for (&i, &p) in points
        .index_axis(Axis(0), 0)
        .iter()
        .zip(points.index_axis(Axis(0), 1))
    {
        pressure.as_slice_mut().unwrap()[i as usize] = p;
    }
    let approach = load_curve(contact, "approach")[step];
    let request = FieldRequest {
        pressure: true,
        ..FieldRequest::ALL
    };
    fields_from_pressure(&problem, pressure.view(), approach, request).unwrap()
}

#[test]
fn the_contact_convolves_its_earlier_steps_once_and_every_consumer_reads_them() {
    let plan = Plan::build(&study(STUDY)).unwrap();
    let artifacts = compute_all(&plan);
    let contact = &artifacts["c"];
    let task = plan.nodes[index(&plan, "c")]
        .task
        .as_any()
        .downcast_ref::<ContactTask>()
        .unwrap();

    // One displacement per earlier step, held by the contact's artifact, never stored.
    let shared = contact.arrays["step_displacements"]
        .view()
        .into_dimensionality::<Ix3>()
        .unwrap();
    assert_eq!(shared.dim(), (2, 48, 64));
    let storage = plan.nodes[index(&plan, "c")].task.array_storage();
    assert!(!storage.stores("step_displacements"));

    // The maps a consumer reads, point by point, equal the unshared path's arrays, bit for bit,
    // with the pressure array of the step before reused.
    let mut previous = None;
    for step in 0..2 {
        let pressure = task.step_pressure(contact, step, previous.take()).unwrap();
        let view = pressure.view(contact).unwrap();
        let alone = unshared(contact, step);
        assert_eq!(
            Some(&pressure.pressure),
            alone.pressure.as_ref(),
            "step {step}"
        );
        for (name, read, stored) in [
            ("gap", view.gap, &alone.gap),
            (
                "deformation_lower",
                view.deformation_lower,
                &alone.deformation_first,
            ),
            (
                "deformation_upper",
                view.deformation_upper.unwrap(),
                &alone.deformation_second,
            ),
            (
                "plastic_penetration",
                view.plastic_penetration,
                &alone.plastic_penetration,
            ),
        ] {
            let stored = stored.as_ref().unwrap();
            assert_eq!(read.dim(), stored.dim(), "step {step} {name}");
            for (at, &value) in stored.indexed_iter() {
                assert_eq!(
                    read.at(at).to_bits(),
                    value.to_bits(),
                    "step {step} {name} {at:?}"
                );
            }
        }
        previous = Some(pressure);
    }

    // The consumers read the contact's displacements rather than convolving the steps
    // themselves: with them changed, their earlier steps change and the final one does not;
    // without them, they fail naming the array.
    let mut changed = contact.clone();
    changed
        .arrays
        .get_mut("step_displacements")
        .unwrap()
        .mapv_inplace(|u| 0.5 * u);
    let mut missing = contact.clone();
    missing.arrays.remove("step_displacements");
    for name in CONSUMERS {
        let consumer = &plan.nodes[index(&plan, name)].task;
        let original = &artifacts[name].tables["curve"];
        let with_changed = consumer.compute(&[&changed]).unwrap();
        let curve = &with_changed.tables["curve"];
        let row = |t: &asperity::engine::artifact::Table, step: usize| -> Vec<f64> {
            (t.columns.iter())
                .filter_map(|c| match &c.data {
                    ColumnData::Float(v) => Some(v[step]),
                    _ => None,
                })
                .collect()
        };
        for step in 0..2 {
            assert_ne!(
                row(original, step),
                row(curve, step),
                "{name}: step {step} ignores the shared displacement"
            );
        }
        assert_eq!(
            row(original, 2),
            row(curve, 2),
            "{name}: the final step is the contact's maps"
        );
        let error = consumer.compute(&[&missing]).unwrap_err();
        assert!(
            error.message.contains("step_displacements"),
            "{name}: {}",
            error.message
        );
    }
}

/// Runs the study's `tables` on `cache`.
fn run(plan: &Plan, cache: &Cache, tables: &[&str]) -> RunReport {
    let options = ExecuteOptions {
        tables: tables.iter().map(|t| t.to_string()).collect(),
        memory_budget: 1 << 32,
        tool_version: String::from("test"),
    };
    execute(plan, cache, &options, &NoProgress).unwrap()
}

fn curve(plan: &Plan, report: &RunReport, name: &str) -> Vec<Vec<f64>> {
    let outcome: &NodeOutcome = report.outcomes[index(plan, name)].as_ref().unwrap();
    outcome.tables["curve"]
        .columns
        .iter()
        .filter_map(|c| match &c.data {
            ColumnData::Float(v) => Some(v.clone()),
            _ => None,
        })
        .collect()
}

/// Through the engine: the consumers of a contact read from the cache (whose entry keeps the
/// pressures only, the displacements derived again for them) give the earlier steps' rows of
/// the consumers of a contact computed in the same run, bit for bit.
#[test]
fn a_cached_contact_shares_the_same_displacements() {
    let dir = std::env::temp_dir().join(format!("asperity-step-sharing-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let study = study(STUDY);
    let plan = Plan::build(&study).unwrap();
    let all: Vec<&str> = study.outputs.iter().map(String::as_str).collect();
    let fresh = run(&plan, &Cache::open(&dir.join("fresh")).unwrap(), &all);
    assert!(fresh.all_ok(), "{:?}", fresh.outcomes);
    let cache = Cache::open(&dir.join("two-runs")).unwrap();
    assert!(run(&plan, &cache, &["contacts"]).all_ok());
    let second = run(&plan, &cache, &all);
    assert!(second.all_ok(), "{:?}", second.outcomes);
    assert_eq!(
        second.cached, 3,
        "the surfaces and the contact come from the cache"
    );
    for name in CONSUMERS {
        let (a, b) = (curve(&plan, &fresh, name), curve(&plan, &second, name));
        assert_eq!(a.len(), b.len());
        for (x, y) in a.iter().zip(&b) {
            assert_eq!(x[..2], y[..2], "{name}: the earlier steps");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
