//! Every resolved field of every node kind enters its key: changing one field of a study changes
//! the key of the node that holds it (and of its dependants), so a changed input never reuses a
//! stale cache entry. Each case edits one field of a base study.

use std::path::Path;

use asperity::engine::plan::Plan;
use asperity::engine::study::Study;
use asperity::nodes::TribologyNode;

const BASE: &str = r#"
study: keys
nodes:
  s:
    surface:
      synthetic: {grid: [32, 32], size: [0.1 mm, 0.1 mm], sq: 1 um, hurst: 0.8,
                  correlation_length: 20 um, seed: 1}
  m:
    surface:
      file: {path: m.txt, form_degree: 1}
  t:
    surface:
      twin: {of: [m.txt], sq: measured, grid: [32, 32], size: [0.1 mm, 0.1 mm], seed: 1}
  u:
    surface:
      twin: {of: [m.txt], spectrum: measured, sq: measured, seed: 1}
  c:
    contact:
      lower: s
      lower_material: s235jr
      nominal_pressures: [10 MPa, 20 MPa]
      fields: true
  f:
    friction:
      lower: s
      lower_material: s235jr
      nominal_pressures: [20 MPa]
  p:
    friction:
      method: per_spot
      model: full_stick
      contact: c
      lower_material: s235jr
  j:
    friction:
      model: junction_shear
      contact: c
      lower_material: s235jr
"#;

/// (node whose key must change, text in BASE, its replacement).
const CASES: &[(&str, &str, &str)] = &[
    ("s", "grid: [32, 32]", "grid: [32, 48]"),
    ("s", "size: [0.1 mm, 0.1 mm]", "size: [0.1 mm, 0.2 mm]"),
    ("s", "sq: 1 um", "sq: 2 um"),
    ("s", "hurst: 0.8", "hurst: 0.7"),
    (
        "s",
        "correlation_length: 20 um",
        "correlation_length: 25 um",
    ),
    ("s", "seed: 1}", "seed: 2}"),
    (
        "s",
        "seed: 1}",
        "seed: 1, anisotropy: {ratio: 2, angle: 0 deg}}",
    ),
    ("s", "seed: 1}", "seed: 1, short_wavelength_cutoff: 5 um}"),
    ("m", "path: m.txt", "path: n.txt"),
    ("m", "form_degree: 1", "form_degree: 2"),
    ("m", "form_degree: 1}", "form_degree: 1, s_filter: 2 um}"),
    ("m", "form_degree: 1}", "form_degree: 1, l_filter: 20 um}"),
    (
        "m",
        "form_degree: 1}",
        "form_degree: 1, crop: [0, 0, 16, 16]}",
    ),
    ("m", "form_degree: 1}", "form_degree: 1, decimate: [2, 2]}"),
    (
        "m",
        "form_degree: 1}",
        "form_degree: 1, fill_missing: true}",
    ),
    ("m", "form_degree: 1}", "form_degree: 1, pixel_size: 1 um}"),
    (
        "m",
        "form_degree: 1}",
        "form_degree: 1, pixel_size: 2 um, override_file_spacing: true}",
    ),
    ("t", "of: [m.txt]", "of: [n.txt]"),
    ("t", "of: [m.txt], sq", "of: [m.txt], spectrum: measured, sq"),
    ("u", "spectrum: measured", "spectrum: measured, extrapolation: power_law"),
    ("u", "spectrum: measured", "spectrum: measured, grid: [8, 8], size: [32 um, 32 um]"),
    ("u", "sq: measured, seed: 1}", "sq: measured, seed: 2}"),
    ("t", "of: [m.txt]", "of: [m.txt, n.txt]"),
    ("t", "sq: measured", "sq: 1 um"),
    ("t", "grid: [32, 32], size: [0.1 mm, 0.1 mm], seed: 1}", "grid: [32, 64], size: [0.1 mm, 0.1 mm], seed: 1}"),
    ("t", "size: [0.1 mm, 0.1 mm], seed: 1}", "size: [0.1 mm, 0.2 mm], seed: 1}"),
    ("t", "[0.1 mm, 0.1 mm], seed: 1}", "[0.1 mm, 0.1 mm], seed: 2}"),
    (
        "t",
        "seed: 1}
  u:",
        "seed: 1, short_wavelength_cutoff: 5 um}
  u:",
    ),
    (
        "t",
        "seed: 1}
  u:",
        "seed: 1, hurst_band: [2 um, 8 um]}
  u:",
    ),
    (
        "t",
        "seed: 1}
  u:",
        "seed: 1, preprocess: {form_degree: 2}}
  u:",
    ),
    (
        "t",
        "seed: 1}
  u:",
        "seed: 1, preprocess: {l_filter: 20 um}}
  u:",
    ),
    (
        "t",
        "seed: 1}
  u:",
        "seed: 1, preprocess: {fill_missing: false}}
  u:",
    ),
    ("c", "[10 MPa, 20 MPa]", "[10 MPa, 30 MPa]"),
    ("c", "fields: true", "fields: true\n      periodic: false"),
    ("c", "fields: true", "fields: true\n      tolerance: 1e-4"),
    (
        "c",
        "fields: true",
        "fields: true\n      flow_pressure: 1 GPa",
    ),
    (
        "c",
        "lower_material: s235jr\n      nominal_pressures: [10",
        "lower_material: {name: s235jr, flow_pressure: 3 GPa}\n      nominal_pressures: [10",
    ),
    (
        "f",
        "nominal_pressures: [20 MPa]",
        "nominal_pressures: [15 MPa]",
    ),
    ("f", "[20 MPa]", "[20 MPa]\n      adhesion_energy: 0.2 N/m"),
    (
        "f",
        "[20 MPa]",
        "[20 MPa]\n      equilibrium_distance: 0.2 nm",
    ),
    ("f", "[20 MPa]", "[20 MPa]\n      nominal_area: 1e-8"),
    (
        "f",
        "[20 MPa]",
        "[20 MPa]\n      model: {kogut_etsion: {static_friction_form: clipped}}",
    ),
    ("f", "[20 MPa]", "[20 MPa]\n      model: chang_etsion_bogy"),
    ("p", "model: full_stick", "model: junction_shear"),
    ("p", "model: full_stick", "model: kogut_etsion"),
    (
        "p",
        "model: full_stick",
        "model: {full_stick: {a: 0.3, b: 0.35}}",
    ),
    (
        "p",
        "model: full_stick",
        "model: full_stick\n      spot_connectivity: 8",
    ),
    (
        "p",
        "model: full_stick",
        "model: full_stick\n      spots_table: true",
    ),
    ("p", "method: per_spot", "method: per_summit"),
    (
        "f",
        "lower_material: s235jr\n      nominal_pressures: [20",
        "lower_material: {name: s235jr, hardness: 3 GPa}\n      nominal_pressures: [20",
    ),
    (
        "p",
        "contact: c\n      lower_material: s235jr",
        "contact: c\n      lower_material: {name: s235jr, yield_strength: 500 MPa}",
    ),
    (
        "j",
        "junction_shear\n      contact: c\n      lower_material: s235jr",
        "junction_shear\n      contact: c\n      lower_material: {name: s235jr, shear_strength: 300 MPa}",
    ),
    (
        "j",
        "model: junction_shear",
        "model: {junction_shear: {interface_factor: 0.5}}",
    ),
];

fn keys(dir: &Path, text: &str) -> Vec<(String, String)> {
    let path = dir.join("keys.yaml");
    std::fs::write(&path, text).unwrap();
    let study = Study::<TribologyNode>::load(&path).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let plan = Plan::build(&study).unwrap_or_else(|e| panic!("{e}\n{text}"));
    plan.node_names
        .iter()
        .enumerate()
        .map(|(n, name)| {
            let instance = plan.scenario_nodes[0][n];
            (name.clone(), plan.nodes[instance].key.to_hex())
        })
        .collect()
}

/// A calibrated 32² text surface.
fn write_surface(path: &Path, seed: f64) {
    let mut text = String::from("# Width: 32 µm\n# Height: 32 µm\n# Value units: m\n");
    for iy in 0..32 {
        let row: Vec<String> = (0..32)
            .map(|ix| format!("{:e}", 1e-7 * (seed * f64::from(ix) + f64::from(iy)).sin()))
            .collect();
        text.push_str(&(row.join("\t") + "\n"));
    }
    std::fs::write(path, text).unwrap();
}

#[test]
fn changing_any_resolved_field_changes_the_key() {
    let dir = std::env::temp_dir().join(format!("asperity-keys-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    write_surface(&dir.join("m.txt"), 0.3);
    write_surface(&dir.join("n.txt"), 0.4);
    let base = keys(&dir, BASE);
    let key_of = |keys: &[(String, String)], node: &str| {
        keys.iter()
            .find(|(n, _)| n == node)
            .map(|(_, k)| k.clone())
            .unwrap()
    };
    let mut unchanged = Vec::new();
    for (node, from, to) in CASES {
        assert!(
            BASE.contains(from),
            "case text not in the base study: {from}"
        );
        let edited = keys(&dir, &BASE.replacen(from, to, 1));
        if key_of(&edited, node) == key_of(&base, node) {
            unchanged.push(format!("{node}: {from} -> {to}"));
        }
        // Dependants follow their upstream.
        if *node == "s" {
            for dependant in ["c", "f", "p", "j"] {
                assert_ne!(key_of(&edited, dependant), key_of(&base, dependant), "{to}");
            }
        }
    }
    assert!(
        unchanged.is_empty(),
        "keys unchanged by:\n{}",
        unchanged.join("\n")
    );
    // The same text gives the same keys (the comparison above is not vacuous).
    assert_eq!(keys(&dir, BASE), base);
    let _ = std::fs::remove_dir_all(&dir);
}
