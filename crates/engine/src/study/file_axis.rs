//! The `glob` parameter axis: every file matching a pattern, sorted, so that "every pair in
//! `scans/`" is one line of a study.
//!
//! * `{glob: "scans/*.x3p"}` — the matching paths, as the pattern writes them (relative to the
//!   study file's folder unless absolute), sorted by path; use them as `path: ${file}`.
//! * `{glob: "scans/*-upper.x3p", values: stems}` — the text the pattern's single `*` matched
//!   (`p01`, `p02`, …), sorted; use them inside strings: `path: "scans/${pair}-upper.x3p"` and
//!   `path: "scans/${pair}-lower.x3p"`.
//!
//! A pattern that matches no file is an error naming the folder searched. Directories never
//! match. Node keys hold the files' content hashes, never these paths.

use std::path::Path;

use indexmap::IndexMap;

use crate::syntax::RawValue;
use crate::value::ParamValue;

/// What a `glob` axis yields.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum GlobValues {
    Paths,
    Stems,
}

/// The values of a `{glob: pattern, values: paths|stems}` axis; patterns are relative to `base`.
pub(super) fn glob_values(
    map: &IndexMap<String, RawValue>,
    base: &Path,
) -> Result<Vec<ParamValue>, String> {
    if let Some(other) = map
        .keys()
        .find(|k| !matches!(k.as_str(), "glob" | "values"))
    {
        return Err(format!(
            "unknown key '{other}' in a glob axis; write {{glob: 'scans/*.x3p', values: paths}}"
        ));
    }
    let Some(RawValue::Text(pattern)) = map.get("glob") else {
        return Err(String::from(
            "glob takes a file pattern in quotes, e.g. {glob: 'scans/*-upper.x3p'}",
        ));
    };
    let values = match map.get("values") {
        None => GlobValues::Paths,
        Some(RawValue::Text(v)) if v == "paths" => GlobValues::Paths,
        Some(RawValue::Text(v)) if v == "stems" => GlobValues::Stems,
        Some(other) => {
            let written = match other {
                RawValue::Text(t) => format!("'{t}'"),
                _ => String::from("that"),
            };
            return Err(format!(
                "values: {written} is not a glob output; write `values: paths` (the file paths) \
                 or `values: stems` (the text the '*' matched)"
            ));
        }
    };
    let stem_of = match values {
        GlobValues::Paths => None,
        GlobValues::Stems => Some(stem_splitter(pattern)?),
    };
    let mut paths = matching_files(pattern, base)?;
    paths.sort();
    if paths.is_empty() {
        return Err(format!(
            "no file matches '{pattern}' (searched relative to {}); check the pattern and \
             the folder",
            base.display()
        ));
    }
    let mut out = Vec::with_capacity(paths.len());
    for path in paths {
        let value = match &stem_of {
            None => path,
            Some((prefix, suffix)) => path
                .strip_prefix(prefix.as_str())
                .and_then(|rest| rest.strip_suffix(suffix.as_str()))
                .map(str::to_string)
                .ok_or_else(|| format!("'{path}' does not fit the pattern '{pattern}'"))?,
        };
        out.push(ParamValue::Text(value));
    }
    if stem_of.is_some() {
        out.dedup();
    }
    Ok(out)
}

/// The text before and after the single `*` of a stem pattern.
fn stem_splitter(pattern: &str) -> Result<(String, String), String> {
    let wildcards = pattern.matches(['*', '?', '[']).count();
    match pattern.split_once('*') {
        Some((prefix, suffix)) if wildcards == 1 => Ok((prefix.to_string(), suffix.to_string())),
        _ => Err(format!(
            "values: stems needs a pattern with exactly one '*' and no other wildcard, got \
             '{pattern}'"
        )),
    }
}

/// Regular files matching `pattern`, written as the pattern writes them ('/'-separated).
fn matching_files(pattern: &str, base: &Path) -> Result<Vec<String>, String> {
    let absolute = Path::new(pattern).is_absolute();
    let full = if absolute {
        pattern.to_string()
    } else {
        let base = base.to_str().ok_or_else(|| {
            format!(
                "the study's folder {} is not valid UTF-8; give an absolute pattern",
                base.display()
            )
        })?;
        let escaped = glob::Pattern::escape(base);
        if escaped.is_empty() {
            pattern.to_string()
        } else {
            format!("{escaped}/{pattern}")
        }
    };
    let entries =
        glob::glob(&full).map_err(|e| format!("'{pattern}' is not a valid pattern: {e}"))?;
    let mut paths = Vec::new();
    for entry in entries {
        let path =
            entry.map_err(|e| format!("cannot read {}: {}", e.path().display(), e.error()))?;
        if !path.is_file() {
            continue;
        }
        let shown = if absolute {
            path.as_path()
        } else {
            path.strip_prefix(base).unwrap_or(&path)
        };
        let text = shown
            .to_str()
            .ok_or_else(|| format!("{} is not a valid UTF-8 path", shown.display()))?;
        paths.push(text.replace('\\', "/"));
    }
    Ok(paths)
}
