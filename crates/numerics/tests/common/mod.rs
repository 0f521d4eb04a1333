//! Helpers shared by the integration tests.

#![allow(dead_code)] // each test binary uses a different subset of these helpers

use std::path::{Path, PathBuf};

/// The shared topography folder with the measured instrument files: `$ASPERITY_TEST_DATA`, else
/// the first `shared/data/topography` next to a folder above `CARGO_MANIFEST_DIR` (the main
/// checkout keeps it beside the repository, a worktree one level deeper).
/// `None` (with a printed note) when absent; a panic when absent under CI (env `CI` set),
/// where the data must be present.
pub fn data_dir() -> Option<PathBuf> {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let candidates = std::env::var_os("ASPERITY_TEST_DATA")
        .map(PathBuf::from)
        .into_iter()
        .chain(
            crate_dir
                .ancestors()
                .map(|dir| dir.join("shared/data/topography")),
        );
    for dir in candidates {
        if dir.join("SOURCES.md").is_file() {
            return Some(dir);
        }
    }
    assert!(
        std::env::var_os("CI").is_none(),
        "shared topography data not found (set ASPERITY_TEST_DATA or place it at ../shared/data/topography)"
    );
    println!("note: shared topography data not found; skipping tests that need it");
    None
}
