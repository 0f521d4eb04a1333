//! Every number that reaches a table is physically possible, or its row is flagged or failed with
//! a sentence (`src/nodes/validity`): the cases of issue #31, each reproduced on a small
//! quickstart-like study, and the documentation written from the rules.

use std::path::Path;

use asperity::engine::artifact::{Artifact, Table};
use asperity::engine::execute::{NodeOutcome, NodeStatus};
use asperity::engine::plan::Plan;
use asperity::engine::value::Field;
use asperity::nodes::validity::{check_artifact, rules_markdown, FRICTION};
use asperity::units::Dimension;

use crate::nodes_common::{float, outcomes, plan_error, run};

/// A 64² surface of 0.125 mm, its contact with a flat at 20 MPa (fields kept) and friction nodes:
/// statistical full stick, junction shear per spot.
const BASE: &str = r#"
study: validity
nodes:
  lower:
    surface:
      synthetic: {grid: [64, 64], size: [0.125 mm, 0.125 mm], sq: 0.05 um, hurst: 0.8,
                  correlation_length: 40 um, seed: 1}
  contact:
    contact:
      lower: lower
      lower_material: s235jr
      nominal_pressures: [20 MPa]
      fields: true
  stick:
    friction:
      model: full_stick
      lower: lower
      lower_material: s235jr
      nominal_pressures: [20 MPa]
  shear:
    friction:
      model: junction_shear
      contact: contact
      lower_material: s235jr
"#;

fn named<'a>(plan: &Plan, report: &'a [Option<NodeOutcome>], name: &str) -> &'a NodeOutcome {
    let i = plan
        .nodes
        .iter()
        .position(|n| n.names.iter().any(|x| x == name))
        .unwrap();
    report[i].as_ref().unwrap()
}

fn failure(o: &NodeOutcome) -> &str {
    match &o.status {
        NodeStatus::Failed(m) => m,
        other => panic!("not failed: {other:?} {:?}", o.metrics),
    }
}

#[test]
fn the_base_study_is_ok() {
    let (plan, report) = run(BASE, "validity-base");
    for o in report.outcomes.iter().flatten() {
        assert_eq!(o.label(), "ok", "{:?} {}", o.status, o.message());
    }
    assert_eq!(report.flagged, 0);
    assert!(float(named(&plan, &report.outcomes, "contact"), "area_fraction") < 1.0);
}

#[test]
fn a_nominal_pressure_above_the_hardness_is_refused_at_validate_and_at_run() {
    let text = BASE.replace(
        "nominal_pressures: [20 MPa]\n  shear",
        "nominal_pressures: [10 GPa]\n  shear",
    );
    let e = plan_error(&text);
    assert!(e.contains("f.yaml:"), "{e}");
    assert!(e.contains("nominal_pressures[0]"), "{e}");
    assert!(
        e.contains("exceeds the flow pressure H = 1.96133e9 Pa"),
        "{e}"
    );
    // As a force the pressure is known only at run time: 156 N on 0.125² mm² is 9.98 GPa.
    let text = BASE.replace(
        "nominal_pressures: [20 MPa]\n  shear",
        "loads: [156 N]\n  shear",
    );
    let (plan, report) = run(&text, "validity-force");
    let m = failure(named(&plan, &report.outcomes, "stick")).to_string();
    assert!(m.contains("exceeds the flow pressure"), "{m}");
    assert!(m.contains("5.09 times the nominal area"), "{m}");
}

#[test]
fn a_gw_area_beyond_the_nominal_area_fails_and_a_steep_contact_is_flagged() {
    let (plan, report) = run(&BASE.replace("sq: 0.05 um", "sq: 64 um"), "validity-rough");
    let m = failure(named(&plan, &report.outcomes, "stick"));
    assert!(
        m.contains("`area_fraction` = ") && m.contains("outside [0, 1]"),
        "{m}"
    );
    assert!(m.contains("Greenwood–Williamson"), "{m}");
    let contact = named(&plan, &report.outcomes, "contact");
    assert_eq!(contact.label(), "flagged");
    assert!(
        contact.message().contains("rms slope Sdq = "),
        "{}",
        contact.message()
    );
    assert!(report.flagged >= 1);
}

#[test]
fn an_interface_factor_above_one_is_refused_at_validate() {
    for c in ["1e308", "1.5", "-0.1"] {
        let text = BASE.replace(
            "model: junction_shear",
            &format!("model: {{junction_shear: {{interface_factor: {c}}}}}"),
        );
        let e = plan_error(&text);
        assert!(
            e.contains("interface_factor") && e.contains("[0, 1]"),
            "{c}: {e}"
        );
    }
    let text = BASE.replace(
        "model: junction_shear",
        "model: {junction_shear: {interface_factor: 1}}",
    );
    assert_eq!(plan_error(&text), "");
}

#[test]
fn a_sub_picometre_sq_fails_at_the_surface_with_its_cause() {
    let dir = scratch("tiny");
    let (plan, report) = run(&base_on_checkerboard(&dir, 1e-300), "validity-tiny");
    let m = failure(named(&plan, &report.outcomes, "lower"));
    assert!(
        m.contains("`sq_m` = 0 is outside ≥ 1e-12 m") && m.contains("underflow"),
        "{m}"
    );
    for name in ["contact", "stick", "shear"] {
        let o = named(&plan, &report.outcomes, name);
        assert!(
            matches!(o.status, NodeStatus::Skipped(_)),
            "{name}: {:?}",
            o.status
        );
    }
}

#[test]
fn a_contact_flow_pressure_far_from_the_hardness_is_refused_and_a_near_one_flagged() {
    let with_flow = |p: &str| {
        BASE.replace(
            "nominal_pressures: [20 MPa]\n      fields: true",
            &format!("flow_pressure: {p}\n      nominal_pressures: [20 MPa]\n      fields: true"),
        )
    };
    let e = plan_error(&with_flow("21 MPa"));
    assert!(e.contains("flow pressure of 2.1e7 Pa"), "{e}");
    assert!(e.contains("H = 1.96133e9 Pa"), "{e}");
    assert!(e.contains("a factor of 93.4 apart"), "{e}");
    let (plan, report) = run(&with_flow("2.5 GPa"), "validity-flow");
    let shear = named(&plan, &report.outcomes, "shear");
    assert_eq!(shear.label(), "flagged");
    assert!(
        shear.message().contains("27.5 % apart"),
        "{}",
        shear.message()
    );
    assert_eq!(named(&plan, &report.outcomes, "contact").label(), "ok");
    // Within 1 %: no flag.
    let (plan, report) = run(&with_flow("1.97 GPa"), "validity-flow-near");
    assert_eq!(named(&plan, &report.outcomes, "shear").label(), "ok");
}

#[test]
fn coarse_grids_flag_the_contact_and_fail_spot_friction() {
    for n in [2, 3, 7] {
        let text = BASE.replace("grid: [64, 64]", &format!("grid: [{n}, {n}]"));
        let (plan, report) = run(&text, &format!("validity-grid{n}"));
        let contact = named(&plan, &report.outcomes, "contact");
        assert_eq!(contact.label(), "flagged", "{n}: {:?}", contact.status);
        assert!(
            contact.message().contains("resolves no contact spot"),
            "{n}"
        );
        let m = failure(named(&plan, &report.outcomes, "shear"));
        assert!(
            m.contains(&format!("{n}×{n} grid is too coarse")),
            "{n}: {m}"
        );
    }
    let (plan, report) = run(
        &BASE.replace("grid: [64, 64]", "grid: [8, 8]"),
        "validity-grid8",
    );
    assert!(!matches!(
        named(&plan, &report.outcomes, "shear").status,
        NodeStatus::Failed(_)
    ));
}

/// A 16² text matrix of µm heights with `value` at one point.
fn height_file(dir: &Path, value: &str) -> String {
    let rows: Vec<String> = (0..16)
        .map(|j| {
            (0..16)
                .map(|i| match (i, j) {
                    (7, 5) => value.to_string(),
                    _ => format!("{:e}", 1e-6 * (((i * 7 + j * 13) % 11) as f64 - 5.0)),
                })
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect();
    let path = dir.join("heights.txt");
    std::fs::write(&path, rows.join("\n") + "\n").unwrap();
    path.display().to_string()
}

/// `BASE` with its lower surface read from a 64 × 64 checkerboard of 16 × 16 blocks of heights
/// ±`a` m (Sq = `a` exactly, one step in 16 differences, so that Sq = 2e-4 m keeps its rms slope
/// below the readers' bound of 100) on the same 0.125 mm square: a measured file is the way such
/// heights still arrive, since `validate` refuses a synthetic Sq outside [1 pm, the shorter side].
fn base_on_checkerboard(dir: &Path, a: f64) -> String {
    let mut text = String::from("# Width: 1.25e-4 m\n# Height: 1.25e-4 m\n# Value units: m\n");
    for iy in 0..64 {
        let row: Vec<String> = (0..64)
            .map(|ix| format!("{:e}", if (ix / 16 + iy / 16) % 2 == 0 { a } else { -a }))
            .collect();
        text.push_str(&row.join("\t"));
        text.push('\n');
    }
    let path = dir.join("checkerboard.txt");
    std::fs::write(&path, text).unwrap();
    BASE.replace(
        "synthetic: {grid: [64, 64], size: [0.125 mm, 0.125 mm], sq: 0.05 um, hurst: 0.8,\n                  correlation_length: 40 um, seed: 1}",
        &format!("file: {{path: \"{}\"}}", path.display()),
    )
}

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("asperity-validity-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn an_overflowing_height_fails_the_surface_and_inspect() {
    let dir = scratch("overflow");
    let path = height_file(&dir, "1e308");
    let text = format!(
        "study: overflow\nnodes:\n  s:\n    surface:\n      file: {{path: '{path}', pixel_size: 1 um}}\n"
    );
    let (plan, report) = run(&text, "validity-overflow");
    let m = failure(named(&plan, &report.outcomes, "s"));
    assert!(m.starts_with("`sq_m` is inf"), "{m}");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_asperity"))
        .arg("inspect")
        .arg(&path)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{stderr}");
    assert!(stderr.contains("`sq_m` is inf"), "{stderr}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_absurd_spacing_fails_the_surface_before_its_statistics() {
    let dir = scratch("spacing");
    let path = height_file(&dir, "0");
    let text = format!(
        "study: spacing\nnodes:\n  s:\n    surface:\n      file: {{path: '{path}', pixel_size: 1e308 m}}\n"
    );
    let (plan, report) = run(&text, "validity-spacing");
    let m = failure(named(&plan, &report.outcomes, "s"));
    assert!(m.contains("`dx_m` = 1e308 is outside ≤ 1 m"), "{m}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn heights_beyond_the_field_of_view_flag_the_surface() {
    let dir = scratch("tall");
    let (plan, report) = run(&base_on_checkerboard(&dir, 2e-4), "validity-tall");
    let surface = named(&plan, &report.outcomes, "lower");
    assert_eq!(surface.label(), "flagged");
    assert!(
        surface
            .message()
            .contains("exceeds the map's larger side 0.000125 m"),
        "{}",
        surface.message()
    );
    assert_eq!(named(&plan, &report.outcomes, "contact").label(), "flagged");
    let sq = float(outcomes(&plan, &report, "surface")[0], "sq");
    assert!(
        (sq / 2e-4 - 1.0).abs() < 1e-9,
        "a flagged row keeps its numbers: {sq}"
    );
}

fn artifact(metrics: Vec<Field>) -> Artifact {
    Artifact {
        metrics,
        ..Artifact::default()
    }
}

#[test]
fn non_finite_values_fail_with_the_column_named() {
    let mut a = artifact(vec![Field::float(
        "mu_s",
        f64::INFINITY,
        Dimension::Dimensionless,
    )]);
    let e = check_artifact(FRICTION, &mut a).unwrap_err().message;
    assert!(
        e.starts_with("`mu_s` is inf: a physical quantity is a finite number"),
        "{e}"
    );
    let mut table = Table::default();
    table.push_float("local_mu", Dimension::Dimensionless, vec![0.3, f64::NAN]);
    let mut a = artifact(Vec::new());
    a.tables.insert(String::from("spots"), table);
    let e = check_artifact(FRICTION, &mut a).unwrap_err().message;
    assert!(
        e.contains("`local_mu` (long table `spots`, row 1) is NaN"),
        "{e}"
    );
    let mut a = artifact(vec![Field::float("mu_s", -0.1, Dimension::Dimensionless)]);
    assert!(check_artifact(FRICTION, &mut a).is_err());
}

#[test]
fn resolution_limited_spots_carrying_most_of_the_load_flag_the_row() {
    let share = |v: f64| {
        let mut a = artifact(vec![Field::float(
            "load_share_one_pixel",
            v,
            Dimension::Dimensionless,
        )]);
        check_artifact(FRICTION, &mut a).map(|()| a.flags)
    };
    assert_eq!(share(0.5).unwrap(), Vec::<String>::new());
    let flags = share(0.8).unwrap();
    assert!(
        flags.len() == 1 && flags[0].contains("one-pixel spots"),
        "{flags:?}"
    );
    assert!(share(1.2).is_err());
}

#[test]
fn every_rule_is_in_the_documentation() {
    let docs =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/study-format.md"))
            .unwrap();
    let table = rules_markdown();
    assert!(
        docs.contains(&table),
        "docs/study-format.md must hold the rules table as written by rules_markdown():\n{table}"
    );
}

#[test]
fn run_prints_each_flag_and_exits_zero() {
    let dir = scratch("cli");
    let study = dir.join("tall.yaml");
    // Surface and contact only: the statistical friction of so tall a surface fails (exit 2).
    let text = base_on_checkerboard(&dir, 2e-4);
    std::fs::write(&study, text.split("  stick:").next().unwrap()).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_asperity"))
        .args(["run", "--quiet", "--cache"])
        .arg(dir.join("cache"))
        .arg("--out")
        .arg(dir.join("out"))
        .arg(&study)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("flagged: surface node 'lower' (")
            && stderr.contains("exceeds the map's larger side"),
        "{stderr}"
    );
    assert!(
        stderr.contains("flagged: contact node 'contact' ("),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn statistical_friction_on_a_grid_too_coarse_for_summit_statistics_fails() {
    let text = BASE.replace("grid: [64, 64]", "grid: [4, 4]");
    let (plan, report) = run(&text, "validity-coarse-moments");
    let m = failure(named(&plan, &report.outcomes, "stick"));
    assert!(
        m.contains("too coarse for summit statistics") && m.contains("4×4"),
        "{m}"
    );
}

#[test]
fn heights_of_a_kilometre_fail_the_surface_and_inspect() {
    let dir = scratch("km");
    let (plan, report) = run(&base_on_checkerboard(&dir, 2e3), "validity-km");
    let m = failure(named(&plan, &report.outcomes, "lower"));
    assert!(m.contains("beyond the ±10 m an instrument measures"), "{m}");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_asperity"))
        .arg("inspect")
        .arg(dir.join("checkerboard.txt"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("beyond the ±10 m an instrument measures")
    );
}

#[test]
fn inspect_refuses_a_profile_whose_rq_overflows() {
    let dir = scratch("profile");
    let path = dir.join("profile.txt");
    let rows: Vec<String> = (0..32)
        .map(|i| {
            let z = if i == 9 { 1e308 } else { 1e-6 * (i % 5) as f64 };
            format!("{:e} {z:e}", i as f64 * 1e-6)
        })
        .collect();
    std::fs::write(&path, rows.join("\n") + "\n").unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_asperity"))
        .arg("inspect")
        .arg(&path)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(!out.status.success(), "{stdout}");
    assert!(!stdout.contains("inf"), "{stdout}");
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("not physically possible"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}
