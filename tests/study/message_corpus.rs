//! Every message a user sees for a corpus of failing inputs reads as a sentence: not empty, no
//! Debug text of internal types (`Nodes { nodes: 250001 }`, `Some(`, `::`, escaped quotes) and
//! no clause said twice ("missing magic: missing magic"). The corpus: the broken studies of
//! `tests/studies/bad/`, the quickstart with each line deleted, studies that used to fail late
//! or with the wrong cause, and damaged topography files (the fixtures of `tests/data` truncated
//! or overwritten, and headers of other formats without their required fields), read through
//! the public API and printed as the command line prints them (the error and its causes).

use std::path::{Path, PathBuf};

use asperity::engine::plan::Plan;
use asperity::engine::study::{Study, StudyError};
use asperity::nodes::TribologyNode;
use asperity::surface::io::read_topography;

/// Text that only Debug formatting of Rust values produces.
const DEBUG_SHAPES: [&str; 8] = ["{ ", " }", "Some(", "None", "Ok(", "Err(", "::", "\\\""];

/// Fewer messages than this means a part of the corpus went missing.
const MIN_MESSAGES: usize = 150;

fn manifest_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// What is wrong with `message`, if anything.
fn defects(message: &str) -> Vec<String> {
    let mut found = Vec::new();
    if message.trim().is_empty() {
        found.push(String::from("empty message"));
    }
    for shape in DEBUG_SHAPES {
        if message.contains(shape) {
            found.push(format!("Debug text '{shape}'"));
        }
    }
    let mut seen: Vec<&str> = Vec::new();
    for clause in message
        .split(": ")
        .flat_map(|part| part.split("; "))
        .map(str::trim)
        .filter(|c| !c.is_empty())
    {
        if seen.contains(&clause) {
            found.push(format!("clause '{clause}' said twice"));
        }
        seen.push(clause);
    }
    found
}

/// The message of a study error without the quoted source line (which shows the user's YAML).
fn study_message(error: &StudyError) -> String {
    format!("{}: {}", error.context, error.message)
}

/// Validates as `asperity validate` does; the message of the error, or `None` if it validates.
fn validation_message(path: &Path, text: &str) -> Option<String> {
    let result = Study::<TribologyNode>::from_source(path, text.to_string())
        .and_then(|study| Plan::build(&study).map(|_| ()));
    result.err().map(|e| study_message(&e))
}

fn bad_studies() -> Vec<(String, String)> {
    let dir = manifest_dir().join("tests/studies/bad");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("tests/studies/bad")
        .map(|entry| entry.expect("directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "yaml"))
        .collect();
    files.sort();
    files
        .into_iter()
        .map(|path| {
            let text = std::fs::read_to_string(&path).expect("readable corpus file");
            (path.display().to_string(), text)
        })
        .collect()
}

/// A study of one synthetic surface with `fields` in its `synthetic:` mapping.
fn synthetic_study(fields: &str) -> String {
    format!(
        "study: s\nnodes:\n  s:\n    surface:\n      synthetic: {{grid: [16, 16], size: [0.125 mm, \
         0.125 mm], hurst: 0.8, correlation_length: 20 um, seed: 1, {fields}}}\n"
    )
}

/// Studies named in issue #31 that validated and then failed late or named the wrong cause.
fn late_failures() -> Vec<(String, String)> {
    let contact = |tolerance: &str| {
        format!(
            "study: t\nnodes:\n  s:\n    surface:\n      synthetic: {{grid: [16, 16], size: \
             [0.125 mm, 0.125 mm], sq: 1 um, hurst: 0.8, correlation_length: 20 um, seed: 1}}\n  \
             c:\n    contact:\n      lower: s\n      lower_material: s235jr\n      \
             nominal_pressures: [20 MPa]\n      tolerance: {tolerance}\n"
        )
    };
    vec![
        (String::from("sq 1e308 um"), synthetic_study("sq: 1e308 um")),
        (String::from("sq 1e-300 m"), synthetic_study("sq: 1e-300 m")),
        (String::from("tolerance 1e-16"), contact("1e-16")),
        (String::from("tolerance 1e-300"), contact("1e-300")),
        (
            String::from("256-character study name"),
            synthetic_study("sq: 1 um").replace("study: s", &format!("study: {}", "a".repeat(256))),
        ),
    ]
}

/// Damaged copies of the reader fixtures and headers without their required fields, in `dir`.
fn damaged_files(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    let mut fixtures: Vec<PathBuf> = std::fs::read_dir(manifest_dir().join("tests/data"))
        .expect("tests/data")
        .map(|entry| entry.expect("directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "sdf" || e == "x3p"))
        .collect();
    fixtures.sort();
    for fixture in fixtures {
        let bytes = std::fs::read(&fixture).expect("readable fixture");
        let stem = fixture.file_stem().and_then(|s| s.to_str()).expect("stem");
        let ext = fixture.extension().and_then(|s| s.to_str()).expect("ext");
        let mut overwritten = bytes.clone();
        for b in overwritten.iter_mut().skip(8).take(64) {
            *b = b'#';
        }
        let variants = [
            ("half", bytes[..bytes.len() / 2].to_vec()),
            ("tenth", bytes[..bytes.len() / 10].to_vec()),
            ("head", bytes[..bytes.len().min(16)].to_vec()),
            ("empty", Vec::new()),
            ("overwritten", overwritten),
        ];
        for (name, content) in variants {
            let path = dir.join(format!("{stem}-{name}.{ext}"));
            std::fs::write(&path, content).expect("write damaged file");
            files.push(path);
        }
    }
    let headers: [(&str, &[u8]); 3] = [
        ("not-alicona.al3d", b"this is not an AL3D file at all"),
        (
            "no-scan-size.spm",
            b"\\*File list\r\n\\*Ciao image list\r\n\\Data offset: 0\r\n\\Data length: 32\r\n\
              \\Bytes/pixel: 2\r\n\\Samps/line: 4\r\n\
              \\Number of lines: 4\r\n\\@2:Z scale: V 1.0 nm\r\n\\@2:Image Data: S [ZSensor] \"Height Sensor\"\r\n\
              \\*File list end\r\n",
        ),
        ("garbage.unknown", b"\x00\x01\x02 no format"),
    ];
    for (name, content) in headers {
        let path = dir.join(name);
        std::fs::write(&path, content).expect("write damaged file");
        files.push(path);
    }
    files
}

#[test]
fn every_message_of_the_failure_corpus_reads_once_and_without_debug_text() {
    let mut messages: Vec<(String, String)> = Vec::new();
    let mut failures = Vec::new();
    let studies = bad_studies().into_iter().chain(late_failures());
    for (name, text) in studies {
        match validation_message(Path::new("study.yaml"), &text) {
            Some(message) => messages.push((name, message)),
            None => failures.push(format!("{name}: validates, but it must fail")),
        }
    }
    let quickstart = manifest_dir().join("studies/quickstart.yaml");
    let text = std::fs::read_to_string(&quickstart).expect("studies/quickstart.yaml");
    let lines: Vec<&str> = text.lines().collect();
    for i in 0..lines.len() {
        let mut deleted = lines.clone();
        deleted.remove(i);
        if let Some(message) = validation_message(&quickstart, &deleted.join("\n")) {
            messages.push((format!("quickstart without line {}", i + 1), message));
        }
    }
    let dir = std::env::temp_dir().join(format!("asperity-messages-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch folder");
    for path in damaged_files(&dir) {
        if let Err(e) = read_topography(&path) {
            // As the command line prints it: the error and its causes.
            let message = format!("{:#}", anyhow::Error::from(e));
            messages.push((path.display().to_string(), message));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    assert!(
        messages.len() >= MIN_MESSAGES,
        "only {} messages in the corpus (expected at least {MIN_MESSAGES})",
        messages.len()
    );
    for (name, message) in &messages {
        for defect in defects(message) {
            failures.push(format!("{name}: {defect}:\n{message}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// The named late failures now fail at validation with the true cause.
#[test]
fn late_failures_name_their_cause_at_validation() {
    let expected = [
        ("sq 1e308 um", "synthetic.sq: 1e302 m is out of range"),
        ("sq 1e-300 m", "synthetic.sq: 1e-300 m is out of range"),
        ("tolerance 1e-16", "tolerance: 1e-16 is out of range"),
        ("tolerance 1e-300", "tolerance: 1e-300 is out of range"),
        (
            "256-character study name",
            "study names are at most 191 bytes",
        ),
    ];
    for ((name, text), (expected_name, part)) in late_failures().into_iter().zip(expected) {
        assert_eq!(name, expected_name);
        let message = validation_message(Path::new("study.yaml"), &text)
            .unwrap_or_else(|| panic!("{name}: validates"));
        assert!(message.contains(part), "{name}: '{part}' not in: {message}");
        assert!(!message.contains("flat"), "{name}: {message}");
    }
}

#[test]
fn the_defect_check_finds_what_it_looks_for() {
    assert!(defects("budget breached: Nodes { nodes: 250001 }").len() >= 2);
    assert!(!defects(
        "x.al3d (AL3D): missing `AliconaImaging` magic: missing `AliconaImaging` magic"
    )
    .is_empty());
    assert!(!defects("").is_empty());
    assert!(!defects("unknown Some(3)").is_empty());
    assert!(defects("nodes.s.surface.synthetic.sq: 1 m is out of range; use 1 um").is_empty());
}
