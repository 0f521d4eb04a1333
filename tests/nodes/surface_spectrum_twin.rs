//! `twin: {spectrum: measured}` through the engine: every readable areal file of the shared
//! folder gets a twin without hand-set parameters, the shipped Alicona crop that no self-affine
//! twin fits gets one (and the self-affine twin's failure names it), and line scans and
//! files in mismatched units fail with a clear message.

use std::path::{Path, PathBuf};

use asperity::engine::execute::{NodeOutcome, NodeStatus, RunReport};
use asperity::engine::plan::Plan;
use asperity::surface::io::{read_topography_channel, TopographyData};

use crate::common;
use crate::nodes_common::{float, int, plan_error, run, text};

/// The outcome of the node named `name`.
fn outcome<'a>(plan: &Plan, report: &'a RunReport, name: &str) -> &'a NodeOutcome {
    let i = plan
        .nodes
        .iter()
        .position(|n| n.names.iter().any(|m| m == name))
        .unwrap_or_else(|| panic!("no node {name}"));
    report.outcomes[i].as_ref().unwrap()
}

fn failure(o: &NodeOutcome) -> &str {
    match &o.status {
        NodeStatus::Failed(m) => m,
        other => panic!("expected a failure, got {other:?}"),
    }
}

fn succeeded(o: &NodeOutcome) -> bool {
    !matches!(o.status, NodeStatus::Failed(_) | NodeStatus::Skipped(_))
}

fn shipped(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("studies/data/twin-comparison")
        .join(name)
        .display()
        .to_string()
}

/// Every file of the shared folder, by its path relative to the folder.
fn data_files(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() && path.file_name().is_some_and(|n| n != "LICENSES") {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e != "md" && e != "json") {
                files.push(path);
            }
        }
    }
    files.sort();
    files
}

/// A twin of every areal file the readers read, with the defaults alone (a plane removed,
/// missing points filled, the file's own grid and size, its Sq): it works and has the
/// measurement's Sq wherever the file surface with that preprocessing works (which is run on the
/// files whose twin fails, to tell); every line scan is refused with the reason.
#[test]
fn every_readable_areal_file_gets_a_spectrum_twin_without_hand_set_parameters() {
    let Some(data) = common::data_dir() else {
        return;
    };
    let node = |name: &str, surface: String| format!("  {name}:\n    surface:\n      {surface}\n");
    let mut twins = String::new();
    let mut files = Vec::new();
    for (i, path) in data_files(&data).into_iter().enumerate() {
        let areal = match read_topography_channel(&path, None) {
            Ok(t) => matches!(t.data, TopographyData::Areal(_)),
            Err(_) => continue,
        };
        let of = format!(
            "twin: {{of: [\"{}\"], spectrum: measured, sq: measured, seed: 1}}",
            path.display()
        );
        twins.push_str(&node(&format!("t{i}"), of));
        files.push((i, path, areal));
    }
    let (plan, report) = run(
        &format!("study: every-file\nnodes:\n{twins}"),
        "spectrum-every-file",
    );
    let (mut twinned, mut problems) = (Vec::new(), Vec::new());
    let (mut surfaces, mut failed) = (String::new(), Vec::new());
    for (i, path, areal) in &files {
        let twin = outcome(&plan, &report, &format!("t{i}"));
        let file = path.strip_prefix(&data).unwrap().display().to_string();
        if !areal {
            let m = failure(twin);
            if !(m.contains("line scan") && m.contains("2-D power spectra")) {
                problems.push(format!("{file}: {m}"));
            }
        } else if succeeded(twin) {
            let (sq, measured) = (float(twin, "sq"), float(twin, "twin_measured_sq"));
            if (sq / measured - 1.0).abs() > 1e-9 || text(twin, "twin_spectrum") != "measured" {
                problems.push(format!(
                    "{file}: twin Sq {sq} against the measured {measured}"
                ));
            }
            twinned.push(file);
        } else {
            let f = format!(
                "file: {{path: \"{}\", form_degree: 1, fill_missing: true}}",
                path.display()
            );
            surfaces.push_str(&node(&format!("f{i}"), f));
            failed.push((format!("f{i}"), file, failure(twin).to_string()));
        }
    }
    if !failed.is_empty() {
        let (plan, report) = run(
            &format!("study: files\nnodes:\n{surfaces}"),
            "spectrum-files",
        );
        for (name, file, twin_failure) in &failed {
            if succeeded(outcome(&plan, &report, name)) {
                problems.push(format!(
                    "{file}: the file surface works, its twin not: {twin_failure}"
                ));
            } else {
                println!("{file}: neither the file surface nor its twin: {twin_failure}");
            }
        }
    }
    println!(
        "spectrum twins of {} files: {}",
        twinned.len(),
        twinned.join(", ")
    );
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    assert!(twinned.len() >= 30, "{twinned:?}");
}

/// The shipped Alicona crop has no power-law band: its self-affine twin fails naming the
/// spectrum twin, which works on it and reproduces its Sq; a power-law tail needs a band too.
#[test]
fn a_surface_without_a_power_law_band_gets_a_spectrum_twin() {
    let al3d = shipped("al3d.txt");
    let text = format!(
        r#"
study: al3d-twins
nodes:
  self_affine:
    surface:
      twin: {{of: ["{al3d}"], preprocess: {{form_degree: 2, l_filter: 11 um}}, sq: measured,
              grid: [256, 256], size: [112 um, 112 um], seed: 1}}
  spectrum:
    surface:
      twin: {{of: ["{al3d}"], preprocess: {{form_degree: 2, l_filter: 11 um}}, sq: measured,
              spectrum: measured, grid: [256, 256], size: [112 um, 112 um], seed: 1}}
  tail:
    surface:
      twin: {{of: ["{al3d}"], preprocess: {{form_degree: 2, l_filter: 11 um}}, sq: measured,
              spectrum: measured, extrapolation: power_law, seed: 1}}
"#
    );
    let (plan, report) = run(&text, "spectrum-al3d");
    let m = failure(outcome(&plan, &report, "self_affine"));
    assert!(
        m.contains("hurst_band") && m.contains("`spectrum: measured`"),
        "{m}"
    );
    let twin = outcome(&plan, &report, "spectrum");
    assert!(succeeded(twin), "{:?}", twin.status);
    assert!((float(twin, "sq") / float(twin, "twin_measured_sq") - 1.0).abs() < 1e-12);
    assert_eq!(int(twin, "grid_nx"), 256);
    assert!(int(twin, "twin_modes_longer_than_measured") > 0);
    // Twice the crop's side at its spacing: the grid loses only the wavelengths longer than
    // the crop, the few modes next to q = 0.
    let share = float(twin, "twin_grid_power_share");
    assert!((share - 1.0).abs() < 0.02, "{share}");
    assert!(twin.flags.is_empty(), "{:?}", twin.flags);
    let m = failure(outcome(&plan, &report, "tail"));
    assert!(m.contains("extrapolation: zero"), "{m}");
}

/// A calibrated text matrix of `rows` (heights of `amplitude` times order 1, in `unit`; side
/// `width`).
fn write_matrix(path: &Path, width: &str, unit: &str, rows: usize, amplitude: f64) {
    let mut text = format!("# Width: {width}\n# Height: {width}\n# Value units: {unit}\n");
    for iy in 0..rows {
        let row: Vec<String> = (0..rows)
            .map(|ix| {
                let (x, y) = (ix as f64, iy as f64);
                format!(
                    "{:e}",
                    amplitude * ((0.7 * x).sin() + (0.3 * y + 0.2 * x).cos() + 0.1 * (x * y).sin())
                )
            })
            .collect();
        text.push_str(&(row.join("\t") + "\n"));
    }
    std::fs::write(path, text).unwrap();
}

/// Line scans and files in mismatched units fail naming the fix.
#[test]
fn line_scans_and_mismatched_units_are_refused_with_the_reason() {
    let dir = std::env::temp_dir().join(format!("asperity-spectrum-bad-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let profile = dir.join("profile.txt");
    let line: String = (0..64)
        .map(|i| {
            format!(
                "{:e}\t{:e}\n",
                i as f64 * 1e-6,
                1e-7 * (0.3 * i as f64).sin()
            )
        })
        .collect();
    std::fs::write(&profile, line).unwrap();
    // The metre file's heights are 30 times the micrometre file's (more than the twin's factor
    // of 10), not 10⁶ times: metres of height over a 32 µm map are refused by the readers'
    // rms-slope bound before the twin compares the two.
    write_matrix(&dir.join("um.txt"), "32 µm", "um", 32, 1.0);
    write_matrix(&dir.join("m.txt"), "32 µm", "m", 32, 3e-5);
    write_matrix(&dir.join("mm.txt"), "32 mm", "um", 32, 1.0);
    let twin = |of: &str| {
        format!(
            "    surface:\n      twin: {{of: [{of}], spectrum: measured, sq: measured, seed: 1}}\n"
        )
    };
    let path = |name: &str| format!("\"{}\"", dir.join(name).display());
    let text = format!(
        "study: bad\nnodes:\n  profile:\n{}  heights:\n{}  lateral:\n{}",
        twin(&path("profile.txt")),
        twin(&format!("{}, {}", path("um.txt"), path("m.txt"))),
        twin(&format!("{}, {}", path("um.txt"), path("mm.txt"))),
    );
    let (plan, report) = run(&text, "spectrum-bad");
    let m = failure(outcome(&plan, &report, "profile"));
    assert!(m.contains("twin.of[0]") && m.contains("line scan"), "{m}");
    let m = failure(outcome(&plan, &report, "heights"));
    assert!(m.contains("height units") && m.contains("m.txt"), "{m}");
    let m = failure(outcome(&plan, &report, "lateral"));
    assert!(m.contains("lateral units") && m.contains("mm.txt"), "{m}");
    // Fields that belong to the other kind of twin are refused where they are written.
    let both = twin(&path("um.txt"));
    for (field, with) in [
        (
            "twin.hurst_band",
            both.replace("seed: 1}", "seed: 1, hurst_band: [2 um, 8 um]}"),
        ),
        (
            "twin.extrapolation",
            both.replace(
                "spectrum: measured",
                "extrapolation: power_law, grid: [8, 8], size: [1 mm, 1 mm]",
            ),
        ),
        (
            "twin.size",
            both.replace("seed: 1}", "seed: 1, grid: [8, 8]}"),
        ),
    ] {
        let e = plan_error(&format!("study: bad\nnodes:\n  t:\n{with}"));
        assert!(e.contains(field), "{field}: {e}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
