//! The surface node's functional parameters and material ratio table, and a twin that finds its
//! Hurst band, through the engine.

use crate::nodes_common::{column, float, outcomes, run, text};
use asperity::engine::value::{Field, Value};

/// A synthetic Gaussian surface: its row carries the functional and volume parameters, and its
/// `material_ratio` table the curve every 1 % from the highest point (Sp above the mean) to the
/// lowest (Sv below), never rising; Sk/Sq near the Gaussian 2.57 (within 15 %: 256² points of a
/// surface with a 16 µm roll-off on 0.5 mm hold ~ 10³ independent patches, a few % sampling error).
#[test]
fn a_surface_row_has_the_functional_parameters_and_the_curve() {
    let (plan, report) = run(
        r#"
study: functional
nodes:
  s:
    surface:
      synthetic: {grid: [256, 256], size: [0.5 mm, 0.5 mm], sq: 1 um, hurst: 0.8,
                  correlation_length: 16 um, seed: 3}
"#,
        "functional",
    );
    let s = outcomes(&plan, &report, "surface")[0];
    assert_eq!(s.label(), "ok", "{:?}", s.status);
    let sq = float(s, "sq");
    let sk = float(s, "sk");
    assert!(
        (sk / sq - 2.574).abs() < 0.15 * 2.574,
        "Sk/Sq = {}",
        sk / sq
    );
    for name in [
        "spk",
        "svk",
        "sxp",
        "vmp_m3_per_m2",
        "vmc_m3_per_m2",
        "vvc_m3_per_m2",
    ] {
        assert!(float(s, name) > 0.0, "{name}");
    }
    let (smr1, smr2) = (float(s, "smr1_percent"), float(s, "smr2_percent"));
    assert!(0.0 < smr1 && smr1 < smr2 && smr2 < 100.0, "{smr1} {smr2}");
    let ratio = column(s, "material_ratio", "material_ratio_percent");
    let height = column(s, "material_ratio", "height");
    assert_eq!(ratio.len(), 101);
    assert_eq!((ratio[0], ratio[100]), (0.0, 100.0));
    assert!((height[0] - float(s, "sp")).abs() < 1e-12 * sq.max(1.0));
    assert!((height[100] + float(s, "sv")).abs() < 1e-12 * sq.max(1.0));
    assert!(height.windows(2).all(|w| w[0] >= w[1]));
}

/// The shipped Wyko crop (studies/data): without `hurst_band` the twin finds its band and says
/// so in its row; `hurst_band: auto` is the same search, a given band is reported as such.
#[test]
fn a_twin_without_hurst_band_reports_the_band_it_found() {
    let data = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("studies/data/twin-comparison/opd.txt")
        .display()
        .to_string();
    let twin = |band: &str| {
        format!(
            "      twin: {{of: [\"{data}\"], preprocess: {{form_degree: 2, l_filter: 5 um}},{band}
              sq: measured, grid: [256, 256], size: [50.4 um, 50.4 um], seed: 1}}\n"
        )
    };
    let study = format!(
        "study: band\nnodes:\n  found:\n    surface:\n{}  auto:\n    surface:\n{}  given:\n    surface:\n{}",
        twin(""),
        twin(" hurst_band: auto,"),
        twin(" hurst_band: [0.6 um, 2.4 um],")
    );
    let (plan, report) = run(&study, "band");
    let twins = outcomes(&plan, &report, "surface");
    assert_eq!(
        twins.len(),
        2,
        "`auto` and no field are one instance (one key)"
    );
    assert!(twins.iter().all(|t| t.label() == "ok"), "{twins:?}");
    let by_source = |source: &str| {
        *twins
            .iter()
            .find(|t| text(t, "twin_hurst_band_source") == source)
            .unwrap_or_else(|| panic!("no twin whose band source is {source}"))
    };
    let (found, given) = (by_source("found"), by_source("study"));
    match found.metrics.iter().find(|f| f.name == "twin_hurst_bands") {
        Some(Field {
            value: Value::Texts(bands),
            ..
        }) => assert!(
            bands.len() == 1 && bands[0].starts_with("opd.txt: 0.6"),
            "{bands:?}"
        ),
        other => panic!("twin_hurst_bands: {other:?}"),
    }
    let (short, long) = (
        float(found, "twin_hurst_band_short"),
        float(found, "twin_hurst_band_long"),
    );
    assert!(short >= 2.0 * 0.197e-6 && long <= 5e-6 && long / short >= 10f64.powf(0.5));
    assert_eq!(float(given, "twin_hurst_band_short"), 0.6e-6);
}
