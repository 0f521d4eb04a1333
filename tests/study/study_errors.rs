//! The corpus of broken study files in `tests/studies/bad/`: every file must fail validation
//! (parse + plan) with a message that names the file, the `line:column` given by its `# at:`
//! header and every `# expect:` substring. No input may panic: the corpus and mutated variants of
//! `studies/quickstart.yaml` (each line deleted, each line cut in half) must give `Ok` or `Err`.
//!
//! Header format of a corpus file (comment lines at the top, in any order):
//! ```text
//! # expect: <substring of the error message>      (one or more)
//! # at: <line>:<column>                           (omitted only when the error has no location)
//! ```

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};

use asperity::engine::plan::Plan;
use asperity::engine::study::{Study, StudyError};
use asperity::nodes::TribologyNode;

/// Fewer files than this means the corpus went missing, so the test cannot pass vacuously.
const MIN_CORPUS_FILES: usize = 20;

fn manifest_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Validation as `asperity validate` does it: parse and check the study, then plan it.
fn validate(path: &Path, text: &str) -> Result<(), StudyError> {
    let study = Study::<TribologyNode>::from_source(path, text.to_string())?;
    Plan::build(&study).map(|_| ())
}

/// Runs `validate`, turning a panic into a test failure message.
fn validate_without_panic(path: &Path, text: &str) -> Result<Result<(), StudyError>, String> {
    catch_unwind(AssertUnwindSafe(|| validate(path, text)))
        .map_err(|_| format!("validation panicked on {}:\n{text}", path.display()))
}

/// The `# expect:` substrings and the optional `# at:` location of a corpus file.
struct Expectation {
    substrings: Vec<String>,
    at: Option<String>,
}

fn expectation(text: &str) -> Expectation {
    let mut substrings = Vec::new();
    let mut at = None;
    for line in text.lines().take_while(|l| l.starts_with('#')) {
        if let Some(s) = line.strip_prefix("# expect:") {
            substrings.push(s.trim().to_string());
        } else if let Some(s) = line.strip_prefix("# at:") {
            at = Some(s.trim().to_string());
        }
    }
    Expectation { substrings, at }
}

fn corpus_files() -> Vec<PathBuf> {
    let dir = manifest_dir().join("tests/studies/bad");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("cannot list {}: {e}", dir.display()))
        .map(|entry| entry.expect("directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "yaml"))
        .collect();
    files.sort();
    files
}

#[test]
fn every_broken_study_fails_with_its_message_and_location() {
    let files = corpus_files();
    assert!(
        files.len() >= MIN_CORPUS_FILES,
        "only {} broken studies in tests/studies/bad (expected at least {MIN_CORPUS_FILES})",
        files.len()
    );
    let mut failures = Vec::new();
    for path in &files {
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .expect("UTF-8 file name");
        let text = std::fs::read_to_string(path).expect("readable corpus file");
        let expected = expectation(&text);
        if expected.substrings.is_empty() {
            failures.push(format!("{name}: has no '# expect:' header"));
            continue;
        }
        let message = match validate_without_panic(path, &text) {
            Err(panic) => {
                failures.push(panic);
                continue;
            }
            Ok(Ok(())) => {
                failures.push(format!(
                    "{name}: validated, but it is in the corpus of broken studies"
                ));
                continue;
            }
            Ok(Err(error)) => error.to_string(),
        };
        // The message starts with the file and, when known, its location: "name.yaml:12:9: …".
        let head = match &expected.at {
            Some(at) => format!("{name}:{at}: "),
            None => format!("{name}: "),
        };
        if !message.contains(&head) {
            failures.push(format!(
                "{name}: message does not name '{head}':\n{message}"
            ));
        }
        for s in &expected.substrings {
            if !message.contains(s.as_str()) {
                failures.push(format!("{name}: message lacks '{s}':\n{message}"));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

#[test]
fn quickstart_validates() {
    let path = manifest_dir().join("studies/quickstart.yaml");
    let text = std::fs::read_to_string(&path).expect("studies/quickstart.yaml");
    if let Err(e) = validate(&path, &text) {
        panic!("the quickstart study does not validate:\n{e}");
    }
}

/// Every variant of the quickstart with one line deleted or cut at half its length gives `Ok` or
/// `Err`, never a panic; the variants that fail still name the file.
#[test]
fn mutated_quickstart_never_panics() {
    let path = manifest_dir().join("studies/quickstart.yaml");
    let text = std::fs::read_to_string(&path).expect("studies/quickstart.yaml");
    let lines: Vec<&str> = text.lines().collect();
    let mut variants = Vec::new();
    for i in 0..lines.len() {
        let mut deleted = lines.clone();
        deleted.remove(i);
        variants.push(deleted.join("\n"));
        let half: String = lines[i]
            .chars()
            .take(lines[i].chars().count() / 2)
            .collect();
        let mut truncated = lines.clone();
        truncated[i] = &half;
        variants.push(truncated.join("\n"));
    }
    let mut failures = Vec::new();
    let mut errors = 0;
    for variant in &variants {
        match validate_without_panic(&path, variant) {
            Err(panic) => failures.push(panic),
            Ok(Err(e)) => {
                errors += 1;
                if !e.to_string().starts_with(&path.display().to_string()) {
                    failures.push(format!("error does not start with the file name: {e}"));
                }
            }
            Ok(Ok(())) => {}
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    // Deleting `study:` or `nodes:` must fail, so some variants are errors: the test exercised them.
    assert!(errors > 0, "no mutated variant was rejected");
}
