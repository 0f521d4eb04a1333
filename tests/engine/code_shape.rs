//! The shape of the source that ARCHITECTURE.md and the brief ask for, checked on the text: no
//! source file grows past 600 lines, and functions fit a screen (80 lines) but for a few named
//! exceptions, each with its reason. (Import circles: `import_graph.rs`.)

use std::path::Path;

use super::architecture::rust_files;

use super::import_graph::SOURCE_ROOTS as CRATES;
use super::source_scan::{code_tokens, functions};

/// Longest source file, in lines (tests included: a file is read whole).
const MAX_FILE_LINES: usize = 600;

#[test]
fn no_source_file_is_longer_than_600_lines() {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut long = Vec::new();
    for krate in CRATES {
        for file in rust_files(&repo.join(krate)) {
            let lines = std::fs::read_to_string(&file).unwrap().lines().count();
            if lines > MAX_FILE_LINES {
                long.push(format!("{}: {lines} lines", file.display()));
            }
        }
    }
    assert!(
        long.is_empty(),
        "source files over {MAX_FILE_LINES} lines (split them by concept):\n{}",
        long.join("\n")
    );
}

/// Longest non-test function, in lines from `fn` to its closing brace.
const MAX_FUNCTION_LINES: usize = 80;

/// The functions allowed to be longer, each with its reason (file below the repository root,
/// function name, why). At most [`MAX_EXCEPTIONS`].
const LONG_FUNCTIONS: &[(&str, &str, &str)] = &[];

/// How many exceptions the house allows.
const MAX_EXCEPTIONS: usize = 10;

#[test]
fn functions_fit_a_screen_but_for_named_exceptions() {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut long = Vec::new();
    let mut seen = 0;
    for krate in CRATES {
        for file in rust_files(&repo.join(krate)) {
            let rel = file
                .strip_prefix(repo)
                .unwrap()
                .to_string_lossy()
                .to_string();
            let text = std::fs::read_to_string(&file).unwrap();
            for (name, first, last) in functions(&code_tokens(&text)) {
                seen += 1;
                let lines = last - first + 1;
                let excepted = LONG_FUNCTIONS
                    .iter()
                    .any(|(f, n, _)| *f == rel && *n == name);
                if lines > MAX_FUNCTION_LINES && !excepted {
                    long.push(format!("{rel}:{first}: fn {name}, {lines} lines"));
                }
            }
        }
    }
    assert!(seen > 1000, "only {seen} functions found");
    assert!(LONG_FUNCTIONS.len() <= MAX_EXCEPTIONS);
    assert!(
        long.is_empty(),
        "functions over {MAX_FUNCTION_LINES} lines (split them into steps that say what they \
         do, or name the exception and its reason in LONG_FUNCTIONS):\n{}",
        long.join("\n")
    );
}

#[test]
fn every_long_function_exception_is_still_long() {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    for (file, name, reason) in LONG_FUNCTIONS {
        assert!(!reason.is_empty(), "{file}: {name} needs a reason");
        let text = std::fs::read_to_string(repo.join(file))
            .unwrap_or_else(|e| panic!("{file} (a listed exception): {e}"));
        let lines = functions(&code_tokens(&text))
            .into_iter()
            .filter(|(n, _, _)| n == name)
            .map(|(_, first, last)| last - first + 1)
            .max();
        assert!(
            lines.is_some_and(|l| l > MAX_FUNCTION_LINES),
            "{file}: fn {name} is listed in LONG_FUNCTIONS but is {lines:?} lines: remove it"
        );
    }
}
