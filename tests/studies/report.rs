//! `asperity report` end to end: a 64² synthetic pair (two Sq grades × two seeds, a contact with
//! fields at two load steps) is run through the binary, then reported. Checks that the page is
//! self-contained, has the expected plots, axis labels and decodable PNG maps, that the error
//! bars are the replicate spread, and that a friction table (as the friction node will write it)
//! is plotted when present.

use std::path::{Path, PathBuf};
use std::process::Command;

use base64::Engine;
use polars::prelude::{Column, DataFrame, ParquetReader, ParquetWriter, SerReader};

const BIN: &str = env!("CARGO_BIN_EXE_asperity");

fn asperity(args: &[&str]) -> std::process::Output {
    let out = Command::new(BIN).args(args).output().unwrap();
    assert!(
        out.status.success(),
        "asperity {args:?} failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// Runs the small study once into a fresh temporary folder: `(cache, results)`.
fn run_study(tag: &str) -> (PathBuf, PathBuf) {
    run_study_file(tag, "tests/studies/report-small.yaml")
}

/// Runs the study at `path` (relative to the repository) once into a fresh temporary folder:
/// `(cache, results)`.
fn run_study_file(tag: &str, path: &str) -> (PathBuf, PathBuf) {
    let dir = std::env::temp_dir().join(format!("asperity-report-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let (cache, results) = (dir.join("cache"), dir.join("results"));
    let study = Path::new(env!("CARGO_MANIFEST_DIR")).join(path);
    asperity(&[
        "run",
        study.to_str().unwrap(),
        "--cache",
        cache.to_str().unwrap(),
        "--out",
        results.to_str().unwrap(),
        "--quiet",
    ]);
    (cache, results)
}

fn report(cache: &Path, results: &Path, extra: &[&str]) -> String {
    let out = results.join("report.html");
    let mut args = vec![
        "report",
        results.to_str().unwrap(),
        "--cache",
        cache.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    asperity(&args);
    std::fs::read_to_string(out).unwrap()
}

fn read(path: &Path) -> DataFrame {
    ParquetReader::new(std::fs::File::open(path).unwrap())
        .finish()
        .unwrap()
}

fn floats(df: &DataFrame, column: &str) -> Vec<f64> {
    let c = df
        .column(column)
        .unwrap()
        .as_materialized_series()
        .f64()
        .unwrap()
        .clone();
    (0..c.len()).map(|i| c.get(i).unwrap()).collect()
}

fn texts(df: &DataFrame, column: &str) -> Vec<String> {
    let c = df
        .column(column)
        .unwrap()
        .as_materialized_series()
        .str()
        .unwrap()
        .clone();
    (0..c.len())
        .map(|i| c.get(i).unwrap().to_string())
        .collect()
}

/// The rows of the value table under the figure whose SVG title contains `title`.
fn value_rows(html: &str, title: &str) -> Vec<Vec<String>> {
    let start = html
        .find(title)
        .unwrap_or_else(|| panic!("no figure '{title}'"));
    let rest = &html[start..];
    let table = &rest[rest.find("<table").unwrap()..rest.find("</table>").unwrap()];
    table
        .split("<tr>")
        .skip(2)
        .map(|row| {
            row.split("<td>")
                .skip(1)
                .map(|cell| cell.split("</td>").next().unwrap().to_string())
                .collect()
        })
        .collect()
}

fn mean_std(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, var.sqrt())
}

#[test]
fn the_report_is_one_self_contained_page_with_trends_load_curves_and_maps() {
    let (cache, results) = run_study("page");
    let html = report(&cache, &results, &["--metric", "mean_separation"]);

    // Self-contained: nothing fetched from the network or from other files.
    for external in [
        "http:", "https:", "src=", "<link", "<script", "url(", "@import",
    ] {
        assert!(!html.contains(external), "the page references '{external}'");
    }
    // 3 trends (A_t,rel, θ and the requested mean separation against Sq), 2 strip plots (θ and
    // A_t,rel of every seed per Sq), 2 load curves, 2 material ratio figures (the surface nodes
    // `lower` and `upper`), 5 maps: the default picks the first seed of both Sq grades, i.e. two
    // lower surfaces, the shared upper surface once and two pressure maps.
    assert_eq!(html.matches("<svg").count(), 14);
    assert!(html.contains("Material ratio curve — surface &#39;lower&#39;"));
    let curve = value_rows(&html, "Material ratio curve — surface &#39;lower&#39;");
    assert_eq!(curve[0][0], "scenario 0", "{curve:?}");
    assert_eq!(
        curve[0].len(),
        6,
        "series and Sk, Spk, Svk, Smr1, Smr2: {curve:?}"
    );
    for label in [
        "Sq (µm)",
        "A_t,rel (true area fraction)",
        "θ (stress ratio)",
        "nominal pressure (MPa)",
        "x (µm)",
        "y (µm)",
        "height (µm)",
        "no contact",
        "error bars: ± one sample standard deviation over seed",
        "friction.parquet: not in the results folder",
    ] {
        assert!(html.contains(label), "missing '{label}'");
    }
    assert!(html.contains("pressure (GPa)") || html.contains("pressure (MPa)"));

    // Every map and colour bar is a PNG data URI that decodes.
    let uris: Vec<&str> = html
        .split("href=\"data:image/png;base64,")
        .skip(1)
        .map(|s| s.split('"').next().unwrap())
        .collect();
    assert_eq!(uris.len(), 10, "5 maps and 5 colour bars");
    for uri in uris {
        let bytes = base64::engine::general_purpose::STANDARD
            .decode(uri)
            .unwrap();
        let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
        let info = decoder.read_info().unwrap().info().clone();
        assert!(info.width >= 1 && info.height >= 16);
    }

    // The error bars are the spread over the two seeds: recompute mean and sample standard
    // deviation of the mean separation (shown in µm) for each Sq grade from the tables.
    let scenarios = read(&results.join("scenarios.parquet"));
    let contacts = read(&results.join("contacts.parquet"));
    let (sq, pair) = (floats(&scenarios, "sq_m"), texts(&scenarios, "pair_key"));
    let (keys, separation) = (
        texts(&contacts, "key"),
        floats(&contacts, "mean_separation_m"),
    );
    let rows = value_rows(&html, "mean separation vs Sq");
    assert_eq!(rows.len(), 2);
    for (grade, row) in [0.5e-6, 1.0e-6].iter().zip(&rows) {
        let values: Vec<f64> = (0..sq.len())
            .filter(|&s| sq[s] == *grade)
            .map(|s| 1e6 * separation[keys.iter().position(|k| *k == pair[s]).unwrap()])
            .collect();
        assert_eq!(values.len(), 2);
        let (mean, std) = mean_std(&values);
        assert!(std > 0.0, "the two seeds must differ");
        // The page prints four significant digits: relative rounding error ≤ 5e-4.
        let shown = |i: usize| row[i].parse::<f64>().unwrap();
        assert!((shown(2) - mean).abs() <= 5e-4 * mean, "{row:?} vs {mean}");
        assert!((shown(3) - std).abs() <= 5e-4 * std, "{row:?} vs {std}");
        assert_eq!(row[4], "2");
    }
    let _ = std::fs::remove_dir_all(results.parent().unwrap());
}

#[test]
fn a_friction_table_is_plotted_and_replicate_axes_can_be_named() {
    let (cache, results) = run_study("friction");
    // A friction table as the friction node writes it: one row per instance, linked from the
    // scenarios through a `<node>_key` column.
    let mut scenarios = read(&results.join("scenarios.parquet"));
    let pair: Vec<String> = (0..scenarios.height())
        .map(|i| format!("{i:064x}"))
        .collect();
    scenarios
        .with_column(Column::new("fric_key".into(), pair.clone()))
        .unwrap();
    let mu: Vec<f64> = (0..pair.len()).map(|i| 0.2 + 0.01 * i as f64).collect();
    let mut friction = DataFrame::new(
        pair.len(),
        vec![
            Column::new("key".into(), pair.clone()),
            Column::new("nodes".into(), vec!["fric"; pair.len()]),
            Column::new("method".into(), vec!["statistical"; pair.len()]),
            Column::new("mu_s".into(), mu.clone()),
            Column::new("status".into(), vec!["ok"; pair.len()]),
        ],
    )
    .unwrap();
    for (name, df) in [("scenarios", &mut scenarios), ("friction", &mut friction)] {
        let file = std::fs::File::create(results.join(format!("{name}.parquet"))).unwrap();
        ParquetWriter::new(file).finish(df).unwrap();
    }
    let html = report(&cache, &results, &["--maps", "0"]);
    assert!(html.contains("μ_s vs Sq — friction &#39;fric&#39; (statistical)"));
    // Scenarios 0, 1 (seeds 1, 2) have Sq = 0.5 µm: μ_s = 0.20, 0.21.
    let rows = value_rows(&html, "μ_s vs Sq");
    assert_eq!(rows[0][2], "0.205");
    assert_eq!(rows[0][3], "0.007071");
    assert_eq!(
        html.matches("<svg").count(),
        10,
        "3 trends, 3 strip plots (θ, A_t,rel, μ_s), 2 load curves and 2 material ratio curves"
    );
    // The strip plot shows every replicate's μ_s, not their mean.
    let strip = value_rows(&html, "μ_s per Sq: every replicate");
    let shown: Vec<f64> = strip.iter().map(|r| r[2].parse::<f64>().unwrap()).collect();
    assert_eq!(shown.len(), mu.len(), "{strip:?}");
    for (s, m) in shown.iter().zip(&mu) {
        assert!((s - m).abs() <= 5e-4 * m, "{s} vs {m}");
    }

    // Naming Sq the replicate axis makes seed the swept parameter.
    let html = report(&cache, &results, &["--maps", "0", "--replicate", "sq"]);
    assert!(html.contains("A_t,rel vs seed"));
    assert!(html.contains("over sq"));

    // A corrupted cache payload is detected by the cache's checksums and skipped, not drawn.
    let contact = &texts(&scenarios, "pair_key")[0];
    let npy = cache
        .join("entries/contact")
        .join(&contact[..2])
        .join(contact)
        .join("pressure.npy.zst");
    let mut bytes = std::fs::read(&npy).unwrap();
    let last = bytes.len() - 1;
    bytes[last] ^= 0xff;
    std::fs::write(&npy, bytes).unwrap();
    let html = report(&cache, &results, &["--scenario", "0"]);
    assert!(html.contains("pressure.npy.zst: checksum mismatch"));
    assert!(html.contains("Heights of surface &#39;lower&#39;"));
    assert!(!html.contains("Contact pressure of"));

    let out = Command::new(BIN)
        .args([
            "report",
            results.to_str().unwrap(),
            "--metric",
            "no_such_column",
        ])
        .args(["--cache", cache.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("unknown --metric 'no_such_column'"));
    let _ = std::fs::remove_dir_all(results.parent().unwrap());
}

/// Adds friction nodes to the results folder as the friction node writes them: one
/// `<node>_key` column per node in the scenarios table and one `friction` row per instance
/// with `method`, `model` and `mu_s` (`None`: a failed row). `scenarios`: the table as the
/// study wrote it; `nodes`: name, method, model and μ_s per scenario.
fn write_friction(
    results: &Path,
    scenarios: &DataFrame,
    nodes: &[(&str, &str, &str, Vec<Option<f64>>)],
) {
    let mut scenarios = scenarios.clone();
    let (mut keys, mut names, mut methods, mut models, mut mu) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (n, (name, method, model, values)) in nodes.iter().enumerate() {
        assert_eq!(values.len(), scenarios.height());
        let node_keys: Vec<String> = (0..values.len())
            .map(|s| format!("{n:032x}{s:032x}"))
            .collect();
        scenarios
            .with_column(Column::new(format!("{name}_key").into(), node_keys.clone()))
            .unwrap();
        keys.extend(node_keys);
        names.extend(values.iter().map(|_| name.to_string()));
        methods.extend(values.iter().map(|_| method.to_string()));
        models.extend(values.iter().map(|_| model.to_string()));
        mu.extend(values.iter().copied());
    }
    let status: Vec<&str> = mu
        .iter()
        .map(|m| if m.is_some() { "ok" } else { "failed" })
        .collect();
    let mut friction = DataFrame::new(
        keys.len(),
        vec![
            Column::new("key".into(), keys),
            Column::new("nodes".into(), names),
            Column::new("method".into(), methods),
            Column::new("model".into(), models),
            Column::new("mu_s".into(), mu),
            Column::new("status".into(), status),
        ],
    )
    .unwrap();
    for (name, df) in [("scenarios", &mut scenarios), ("friction", &mut friction)] {
        let file = std::fs::File::create(results.join(format!("{name}.parquet"))).unwrap();
        ParquetWriter::new(file).finish(df).unwrap();
    }
}

/// The `<svg>` element whose title contains `title`.
fn svg_titled<'a>(html: &'a str, title: &str) -> &'a str {
    let at = html
        .find(title)
        .unwrap_or_else(|| panic!("no figure '{title}'"));
    let start = html[..at].rfind("<svg").unwrap();
    let end = at + html[at..].find("</svg>").unwrap();
    &html[start..end]
}

#[test]
fn several_friction_nodes_share_a_mu_s_by_friction_model_figure() {
    let (cache, results) = run_study("models");
    // Scenarios 0–3: Sq 0.5, 0.5, 1, 1 µm with seeds 1, 2, 1, 2. junction_shear failed in
    // scenario 0; its μ_s is two decades below the others, so the y axis is logarithmic.
    let nodes = [
        (
            "ke_statistical",
            "statistical",
            "kogut_etsion",
            vec![Some(0.30), Some(0.32), Some(0.25), Some(0.27)],
        ),
        (
            "stick_per_spot",
            "per_spot",
            "full_stick",
            vec![Some(0.60), Some(0.62), Some(0.50), Some(0.52)],
        ),
        (
            "junction_shear",
            "per_spot",
            "junction_shear",
            vec![None, Some(0.002), Some(0.003), Some(0.004)],
        ),
    ];
    let scenarios = read(&results.join("scenarios.parquet"));
    write_friction(&results, &scenarios, &nodes);
    let html = report(&cache, &results, &["--maps", "0"]);
    let title = "μ_s by friction model vs Sq";
    assert_eq!(
        html.matches(title).count(),
        1,
        "one swept parameter, one figure"
    );
    let svg = svg_titled(&html, title);
    for (name, method, model, _) in &nodes {
        let label = format!(">{name} ({method}, {model})</text>");
        assert_eq!(
            svg.matches(&label).count(),
            1,
            "legend entry {label} in {svg}"
        );
    }
    assert_eq!(svg.matches("<polyline").count(), 3, "one line per node");
    assert!(svg.contains(">0.001<"), "a log y axis: {svg}");
    let figure = &html[html.find(title).unwrap()..];
    let caption = &figure[..figure.find("</figcaption>").unwrap()];
    assert!(caption.contains("1 missing value(s)"));
    // The failed scenario is left out: junction_shear at Sq = 0.5 µm is scenario 1 alone.
    let rows = value_rows(&html, title);
    assert_eq!(rows.len(), 6);
    let junction = rows
        .iter()
        .find(|r| r[0].starts_with("junction_shear") && r[1] == "0.5")
        .unwrap();
    assert_eq!((junction[2].as_str(), junction[4].as_str()), ("0.002", "1"));
    // The per-node figures stay.
    assert_eq!(html.matches("μ_s vs Sq — friction").count(), 3);

    // A single friction node: its own figure suffices.
    write_friction(&results, &scenarios, &nodes[..1]);
    let html = report(&cache, &results, &["--maps", "0"]);
    assert!(html.contains("μ_s vs Sq — friction &#39;ke_statistical&#39;"));
    assert!(!html.contains("by friction model"));
    let _ = std::fs::remove_dir_all(results.parent().unwrap());
}

/// The shipped twin comparison: the report pairs each measured surface with the twin made from
/// it and draws one twin-against-measured figure per quantity and friction node pair, whose
/// values table holds one row per file and twin kind with the twin's mean, std and seed count.
#[test]
fn the_twin_comparison_study_draws_measured_against_twin() {
    let (cache, results) = run_study_file("twins", "studies/twin-comparison.yaml");
    let html = report(&cache, &results, &[]);
    let start = html
        .find("<h2>Measured surfaces and their twins</h2>")
        .expect("the comparison section");
    let section = &html[start..];
    let section = &section[..section[4..].find("<h2>").map_or(section.len(), |i| i + 4)];
    // Summit radius, area fraction, stress ratio, and six friction node pairs (KE, CEB and full
    // stick statistical, full stick per summit and per spot, junction shear).
    assert_eq!(section.matches("<figcaption>").count(), 9, "{section}");
    assert!(section.contains("(per_spot, junction_shear): node &#39;twin_junction_shear&#39;"));
    // One row per file and twin kind: opd's self-affine and spectrum twins, al3d's spectrum
    // twin, each over four seeds.
    for group in [
        "opd, spectrum = self_affine",
        "opd, spectrum = measured",
        "al3d, spectrum = measured",
    ] {
        assert_eq!(
            section.matches(&format!("<td>file = {group}</td>")).count(),
            9,
            "{group}"
        );
    }
    assert_eq!(
        section.matches("<td>4</td>").count(),
        27,
        "n = 4 seeds per point"
    );
    let summary = read(&results.join("summary_per_file.parquet"));
    assert_eq!(summary.height(), 3);
    let _ = std::fs::remove_dir_all(results.parent().unwrap());
}
