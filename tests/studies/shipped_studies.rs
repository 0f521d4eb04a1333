//! The studies shipped in `studies/` run, so they never rot: each one with the reduced-grid
//! overrides its header documents (the line after "used in CI"), through the real binary, and
//! every node of every scenario must succeed. The quickstart runs as shipped.

use std::path::{Path, PathBuf};
use std::process::Command;

use asperity::engine::output::PARAMETER_PREFIX;
use asperity::engine::study::SCENARIOS_TABLE;
use asperity::nodes::{is_known_column, is_prose_column, list_column, ListItems};
use polars::prelude::{Column, DataFrame, DataType, NamedFrom, ParquetReader, SerReader, Series};

fn studies_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("studies")
}

/// The `--set` arguments of the command on the line after the header line that mentions CI.
/// A study without one runs as shipped.
fn ci_overrides(study: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(study).unwrap();
    let lines: Vec<&str> = text.lines().take_while(|l| l.starts_with('#')).collect();
    let Some(i) = lines.iter().position(|l| l.contains("used in CI")) else {
        return Vec::new();
    };
    let command = lines
        .get(i + 1)
        .unwrap_or_else(|| panic!("{}: no command after the CI line", study.display()));
    let args = command
        .split(" --set ")
        .skip(1)
        .map(|a| a.trim().trim_matches('"').to_string())
        .collect::<Vec<_>>();
    assert!(
        !args.is_empty(),
        "{}: the CI command sets nothing: {command}",
        study.display()
    );
    args
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("asperity-shipped-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn statuses(file: &Path) -> Vec<String> {
    let df = ParquetReader::new(std::fs::File::open(file).unwrap())
        .finish()
        .unwrap();
    df.column("status")
        .unwrap()
        .str()
        .unwrap()
        .iter()
        .map(|s| s.unwrap_or("null").to_string())
        .collect()
}

#[test]
fn every_shipped_study_runs_on_its_reduced_grid() {
    let mut studies: Vec<PathBuf> = std::fs::read_dir(studies_dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "yaml"))
        .collect();
    studies.sort();
    assert!(studies.len() >= 4, "studies found: {studies:?}");
    for study in studies {
        let name = study.file_stem().unwrap().to_string_lossy().to_string();
        let dir = scratch(&name);
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_asperity"));
        cmd.arg("run").arg(&study).arg("--quiet");
        for set in ci_overrides(&study) {
            cmd.arg("--set").arg(set);
        }
        cmd.arg("--cache").arg(dir.join("cache"));
        cmd.arg("--out").arg(dir.join("out"));
        let output = cmd.output().unwrap();
        assert!(
            output.status.success(),
            "{name} failed:\n{}\n{}",
            String::from_utf8_lossy(&output.stdout),
            String::from_utf8_lossy(&output.stderr)
        );
        let scenarios = statuses(&dir.join("out/scenarios.parquet"));
        // No scenario fails. Flags are expected: ground steel at 0.56 µm pixels has a composite
        // Sdq of 0.5–0.8, beyond the half-space solution's small-slope limit (its contacts are
        // flagged, docs/study-format.md, "Validity of values"), and most of the Kogut–Etsion
        // rows' load in the shipped studies is beyond the law's fit (ω/ω_c > 6); the rules
        // themselves are tested in tests/nodes/validity.rs and tests/nodes/friction_trust.rs.
        let allowed: &[&str] = &["ok", "flagged"];
        assert!(
            scenarios.iter().all(|s| allowed.contains(&s.as_str())),
            "{name}: scenario statuses {scenarios:?}"
        );
        check_friction(&name, &dir.join("out/friction.parquet"));
        check_vocabulary(&name, &dir.join("out"));
        check_column_types(&name, &dir.join("out"));
        let _ = std::fs::remove_dir_all(&dir);
    }
}

/// Every column of every table of a run is a name of the one vocabulary with its unit suffix
/// (`asperity::nodes::is_known_column`, #41), but the names the study itself chooses: the
/// parameters and node names of `scenarios` and the summaries, the `param_` columns of the
/// per-scenario views.
fn check_vocabulary(name: &str, out: &Path) {
    let mut unknown = Vec::new();
    for entry in std::fs::read_dir(out).unwrap() {
        let path = entry.unwrap().path();
        let table = path.file_stem().unwrap().to_string_lossy().to_string();
        let study_named = table == SCENARIOS_TABLE || table.starts_with("summary_");
        if path.extension().is_none_or(|e| e != "parquet") || study_named {
            continue;
        }
        let df = ParquetReader::new(std::fs::File::open(&path).unwrap())
            .finish()
            .unwrap();
        for column in df.get_column_names() {
            if !column.starts_with(PARAMETER_PREFIX) && !is_known_column(column) {
                unknown.push(format!("{table}.{column}"));
            }
        }
    }
    assert!(
        unknown.is_empty(),
        "{name}: columns outside the vocabulary (src/vocabulary.rs): {unknown:?}"
    );
}

/// No friction row of a shipped study has μ_s < 0 or a negative local-μ quantile; on the
/// ground-steel studies every row of the high-plasticity models (full stick, junction shear) lies
/// (and the measured pairs) in the range of steel-steel static friction, 0.05 to 1.5.
fn check_friction(name: &str, file: &Path) {
    if !file.exists() {
        return;
    }
    let df = ParquetReader::new(std::fs::File::open(file).unwrap())
        .finish()
        .unwrap();
    let mu: Vec<f64> = df
        .column("mu_s")
        .unwrap()
        .f64()
        .unwrap()
        .iter()
        .map(|v| v.unwrap_or(f64::NAN))
        .collect();
    let models: Vec<String> = df
        .column("model")
        .unwrap()
        .str()
        .unwrap()
        .iter()
        .map(|s| s.unwrap_or("null").to_string())
        .collect();
    assert!(mu.iter().all(|m| *m >= 0.0), "{name}: μ_s {mu:?}");
    for column in df.get_column_names() {
        if column.starts_with("local_mu") {
            let values = df.column(column).unwrap().f64().unwrap();
            assert!(
                values.iter().flatten().all(|m| m >= 0.0),
                "{name}: {column} has a negative value"
            );
        }
    }
    if ["ground-validation", "sq-parameter-study", "measured-pairs"].contains(&name) {
        for (m, model) in mu.iter().zip(&models) {
            if model == "full_stick" || model == "junction_shear" {
                assert!((0.05..=1.5).contains(m), "{name} {model}: μ_s = {m}");
            }
        }
    }
}

/// Every table of a run holds its lists as list columns, of the type the vocabulary declares
/// (`asperity::vocabulary::list_columns`), and no text column holds a list joined by commas or
/// semicolons (#41): `nominal_pressures_Pa` is `[5e6, 1e7, 2e7]`, never `"5e6,1e7,2e7"`.
fn check_column_types(name: &str, out: &Path) {
    let mut problems = Vec::new();
    for entry in std::fs::read_dir(out).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "parquet") {
            continue;
        }
        let table = path.file_stem().unwrap().to_string_lossy().to_string();
        let df = ParquetReader::new(std::fs::File::open(&path).unwrap())
            .finish()
            .unwrap();
        problems.extend(column_type_problems(&table, &df));
    }
    assert!(problems.is_empty(), "{name}: {problems:#?}");
}

/// What is wrong with the column types of `df` (table `table`): a list column the vocabulary
/// does not declare (but a list parameter the study chose: `scenarios`, `summary_*`, `param_*`),
/// a declared list column of another type, or a text column other than the prose ones
/// (`message`, …) with a value holding a comma or a semicolon.
fn column_type_problems(table: &str, df: &DataFrame) -> Vec<String> {
    let study_named = table == SCENARIOS_TABLE || table.starts_with("summary_");
    let mut problems = Vec::new();
    for column in df.columns() {
        let name = column.name().as_str();
        let parameter = study_named || name.starts_with(PARAMETER_PREFIX);
        let declared = list_column(name);
        let found = match column.dtype() {
            DataType::List(inner) => match inner.as_ref() {
                DataType::Float64 => Some(ListItems::Floats),
                DataType::String => Some(ListItems::Texts),
                other => {
                    problems.push(format!("{table}.{name}: a list of {other}"));
                    continue;
                }
            },
            _ => None,
        };
        if found != declared && !(parameter && declared.is_none()) {
            let show = |l: Option<ListItems>| l.map_or("one value per row", ListItems::name);
            problems.push(format!(
                "{table}.{name}: holds {} ({}), the vocabulary declares {}",
                show(found),
                column.dtype(),
                show(declared)
            ));
        }
        if column.dtype() == &DataType::String && !is_prose_column(name) {
            let joined = column
                .str()
                .unwrap()
                .iter()
                .flatten()
                .find(|v| v.contains([',', ';']));
            if let Some(value) = joined {
                problems.push(format!(
                    "{table}.{name}: {value:?} is a list joined as text"
                ));
            }
        }
    }
    problems
}

/// The check fails on a synthetic table with every kind of wrong column and passes the right
/// ones (prose with commas, list columns of the declared type, a list parameter).
#[test]
fn the_column_type_check_finds_joined_lists_and_wrong_list_types() {
    let text = |name: &str, v: &str| Column::from(Series::new(name.into(), [v]));
    let floats = |name: &str| {
        let list = Series::new("".into(), [5e6, 1e7]);
        Column::from(Series::new(name.into(), [list]))
    };
    let texts = |name: &str| {
        let list = Series::new("".into(), ["a, b", "c"]);
        Column::from(Series::new(name.into(), [list]))
    };
    let columns = vec![
        text("nominal_pressures_Pa", "5e6,1e7"),
        text("model", "kogut_etsion; ceb"),
        text("twin_warnings", "one; two"),
        texts("sq_m"),
        floats("twin_hurst_bands"),
        floats("mu_s"),
        text("message", "flagged: a, b; c"),
        floats("loads_N"),
        texts("twin_measured_bands"),
        texts("nodes"),
        floats("param_pressures_Pa"),
        text("status", "ok"),
    ];
    let df = DataFrame::new(1, columns).unwrap();
    assert_eq!(
        column_type_problems("friction", &df),
        [
            "friction.nominal_pressures_Pa: holds one value per row (str), the vocabulary declares float",
            "friction.nominal_pressures_Pa: \"5e6,1e7\" is a list joined as text",
            "friction.model: \"kogut_etsion; ceb\" is a list joined as text",
            "friction.twin_warnings: holds one value per row (str), the vocabulary declares text",
            "friction.twin_warnings: \"one; two\" is a list joined as text",
            "friction.sq_m: holds text (list[str]), the vocabulary declares one value per row",
            "friction.twin_hurst_bands: holds float (list[f64]), the vocabulary declares text",
            "friction.mu_s: holds float (list[f64]), the vocabulary declares one value per row",
        ]
    );
}
