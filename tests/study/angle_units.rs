//! One rule for plain numbers in angle fields (docs/study-format.md, "Angles need their unit"):
//! an angle is written with its unit; a plain number other than 0 is refused with the two
//! readings it could have, wherever the angle is written: `anisotropy.angle`, a law's
//! `sliding_direction`, a parameter axis (`${a}`) and `--set`.

use std::path::Path;

use asperity::engine::plan::Plan;
use asperity::engine::study::{ParameterOverride, Study};
use asperity::nodes::TribologyNode;

/// A ground surface at angle `LAY` against a flat, and a ploughing node sliding at `DIR`.
const STUDY: &str = r#"
study: angles
parameters:
  product:
    a: [AXIS]
nodes:
  s:
    surface:
      synthetic: {grid: [32, 32], size: [50 um, 50 um], sq: 1 um, hurst: 0.8,
                  correlation_length: 10 um, anisotropy: {ratio: 3, angle: LAY}, seed: 1}
  pair:
    contact: {lower: s, lower_material: s235jr,
              nominal_pressures: [20 MPa], fields: true}
  plough:
    friction: {model: {ploughing: {sliding_direction: DIR}}, contact: pair,
               lower_material: s235jr}
"#;

fn study(lay: &str, dir: &str, axis: &str) -> Result<Study<TribologyNode>, String> {
    let text = STUDY
        .replace("LAY", lay)
        .replace("DIR", dir)
        .replace("AXIS", axis);
    Study::<TribologyNode>::from_source(Path::new("angles.yaml"), text).map_err(|e| e.to_string())
}

/// The plan of the study, or the message that refused it.
fn plan(lay: &str, dir: &str, axis: &str, set: &[&str]) -> Result<Plan, String> {
    let mut s = study(lay, dir, axis)?;
    let overrides: Vec<ParameterOverride> = set.iter().map(|a| a.parse().unwrap()).collect();
    s.apply_overrides(&overrides).map_err(|e| e.to_string())?;
    Plan::build(&s).map_err(|e| e.to_string())
}

/// The key of the node kind `kind` (one instance each).
fn key(plan: &Plan, kind: &str) -> String {
    let node = plan.nodes.iter().find(|n| n.task.kind() == kind).unwrap();
    node.key.to_hex()
}

fn assert_refused(result: Result<Plan, String>, field: &str, plain: &str) {
    let Err(message) = result else {
        panic!("a plain angle must be refused");
    };
    let both = format!("'{plain} deg' or '{plain} rad'");
    assert!(
        message.contains(field) && message.contains("without its unit") && message.contains(&both),
        "{message}"
    );
}

#[test]
fn an_angle_with_its_unit_is_read_in_every_unit_and_zero_may_be_plain() {
    let base = plan("0 deg", "90 deg", "1", &[]).unwrap();
    for (lay, dir) in [
        ("0", "90°"),
        ("0 rad", "1.5707963267948966 rad"),
        ("0°", "90 deg"),
    ] {
        let other = plan(lay, dir, "1", &[]).unwrap();
        assert_eq!(key(&base, "surface"), key(&other, "surface"), "{lay}");
        assert_eq!(key(&base, "friction"), key(&other, "friction"), "{dir}");
    }
    let turned = plan("30 deg", "90 deg", "1", &[]).unwrap();
    assert_ne!(key(&base, "surface"), key(&turned, "surface"));
}

#[test]
fn a_plain_angle_is_refused_where_it_is_written() {
    assert_refused(
        plan("0.5", "90 deg", "1", &[]),
        "angles.yaml:10:76: nodes.s.surface.synthetic.anisotropy.angle",
        "0.5",
    );
    assert_refused(
        plan("0 deg", "6.2832", "1", &[]),
        "model.ploughing.sliding_direction",
        "6.2832",
    );
    assert_refused(plan("0 deg", "90", "1", &[]), "sliding_direction", "90");
}

#[test]
fn a_plain_angle_from_an_axis_or_an_override_is_refused_too() {
    assert_refused(
        plan("\"${a}\"", "90 deg", "1.57", &[]),
        "anisotropy.angle",
        "1.57",
    );
    assert_refused(
        plan("0 deg", "\"${a}\"", "45", &[]),
        "sliding_direction",
        "45",
    );
    assert_refused(
        plan("\"${a}\"", "90 deg", "30 deg", &["a=30"]),
        "anisotropy.angle",
        "30",
    );
    let axis = plan("\"${a}\"", "\"${a}\"", "30 deg", &[]).unwrap();
    let literal = plan("30 deg", "30 deg", "1", &[]).unwrap();
    assert_eq!(key(&axis, "surface"), key(&literal, "surface"));
    assert_eq!(key(&axis, "friction"), key(&literal, "friction"));
    let set = plan("\"${a}\"", "\"${a}\"", "1 deg", &["a=30 deg"]).unwrap();
    assert_eq!(key(&set, "friction"), key(&literal, "friction"));
}
