//! Helpers of the damaged-file tests (`damaged_files`, `lying_headers`, `header_checks`):
//! loading a file, judging what a reader made of a damaged copy, and editing copies.

use std::path::{Path, PathBuf};

use asperity_numerics::surface::io::{parse_topography, ReadError, TopographyData};

/// The bytes of `file` in the shared folder `dir`, with its path.
pub fn load(dir: &Path, file: &str) -> (PathBuf, Vec<u8>) {
    let path = dir.join(file);
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    (path, bytes)
}

/// Every file under the shared folder `root` but its documentation (`LICENSES/`, `SOURCES.md`,
/// `reference_values.json`), sorted.
pub fn shared_files(root: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    collect(root, root, &mut out);
    out
}

fn collect(root: &Path, dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.map(|e| e.path()).unwrap_or_else(|e| panic!("{e}")))
        .collect();
    entries.sort();
    for path in entries {
        let relative = path.strip_prefix(root).unwrap_or(&path);
        let documentation = relative.starts_with("LICENSES")
            || matches!(
                relative.to_str(),
                Some("SOURCES.md" | "reference_values.json")
            );
        if documentation {
            continue;
        }
        if path.is_dir() {
            collect(root, &path, out);
        } else {
            out.push(path);
        }
    }
}

/// What a reader may make of a damaged copy of `path`: an error that names the file, or a
/// consistent result (`HeightMap::new` already refuses infinite heights and bad spacings). A
/// panic fails the test at once. `Err` says what went wrong, `what` being the damage.
pub fn check_outcome(path: &Path, bytes: &[u8], what: &str) -> Result<(), String> {
    match parse_topography(path, bytes) {
        Err(ReadError::Parse { path: p, .. } | ReadError::UnknownFormat { path: p }) => {
            if p == path {
                Ok(())
            } else {
                Err(format!("{what}: the error names {}", p.display()))
            }
        }
        Err(other) => Err(format!("{what}: unexpected error kind {other}")),
        Ok(t) => match t.data {
            TopographyData::Areal(m) if m.heights().len() == m.nx() * m.ny() => Ok(()),
            TopographyData::Line(l) if l.x.len() == l.z.len() => Ok(()),
            _ => Err(format!("{what}: an inconsistent result")),
        },
    }
}

/// `Ok` when the damaged copy `bytes` of `path` fails with an error naming the file.
pub fn check_refused(path: &Path, bytes: &[u8], what: &str) -> Result<(), String> {
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    match parse_topography(path, bytes) {
        Ok(_) => Err(format!("{what}: read, must fail")),
        Err(e) if e.to_string().contains(name.as_ref()) => Ok(()),
        Err(e) => Err(format!("{what}: `{e}` does not name the file")),
    }
}

/// `count` deterministic positions below `bound` (a 64-bit LCG, Knuth's MMIX constants).
pub fn positions(seed: u64, count: usize, bound: usize) -> Vec<usize> {
    let mut state = seed;
    (0..count)
        .map(|_| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            ((state >> 33) as usize) % bound.max(1)
        })
        .collect()
}

/// `bytes` with `value` written at `at`.
pub fn patched(bytes: &[u8], at: usize, value: &[u8]) -> Vec<u8> {
    let mut b = bytes.to_vec();
    b[at..at + value.len()].copy_from_slice(value);
    b
}

/// The position of the first `needle` in `bytes`.
pub fn find(bytes: &[u8], needle: &[u8]) -> usize {
    bytes
        .windows(needle.len())
        .position(|w| w == needle)
        .unwrap_or_else(|| panic!("{:?} not found", String::from_utf8_lossy(needle)))
}

/// `bytes` with the first `from` replaced by `to` (of any length).
pub fn replaced(bytes: &[u8], from: &[u8], to: &[u8]) -> Vec<u8> {
    let at = find(bytes, from);
    [&bytes[..at], to, &bytes[at + from.len()..]].concat()
}

/// Asserts that `bytes` (a damaged copy of `path`) fails with an error naming the file and
/// holding `expected`.
#[track_caller]
pub fn expect_error(path: &Path, bytes: &[u8], expected: &str) {
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    let err = parse_topography(path, bytes)
        .map(|_| ())
        .expect_err(&format!("{}: the damaged copy must fail", path.display()));
    let text = err.to_string();
    assert!(
        text.contains(expected) && text.contains(name.as_ref()),
        "{}: `{text}` lacks `{expected}` or the file's name",
        path.display()
    );
}
