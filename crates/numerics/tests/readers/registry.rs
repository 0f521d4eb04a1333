//! The reader registry: one entry per format, found by name, magic bytes and extension; the
//! channel choice every reader shares.

use std::path::Path;

use asperity_numerics::surface::io::{
    detect_format, parse_topography_channel, reader_named, ParseError, ReadError, HEIGHT_CHANNEL,
    READERS,
};

/// A 2 × 2 Gwyddion Simple Field (float32 heights in metres), a single-channel format.
fn gsf() -> Vec<u8> {
    let mut b =
        b"Gwyddion Simple Field 1.0\nXRes = 2\nYRes = 2\nXReal = 1e-6\nYReal = 1e-6\n".to_vec();
    b.resize(b.len() + 4 - b.len() % 4, 0);
    for z in [1e-9f32, 2e-9, 3e-9, 5e-9] {
        b.extend(z.to_le_bytes());
    }
    b
}

#[test]
fn every_reader_is_found_by_its_name_and_its_extensions() {
    let mut names: Vec<&str> = READERS.iter().map(|r| r.name).collect();
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), READERS.len(), "reader names must be unique");
    for reader in READERS {
        assert_eq!(reader_named(reader.name).map(|r| r.name), Some(reader.name));
        assert!(!reader.extensions.is_empty(), "{}", reader.name);
        for ext in reader.extensions {
            assert_eq!(ext.to_ascii_lowercase(), *ext, "{}", reader.name);
        }
    }
    assert!(reader_named("nope").is_none());
    let gsf_by_magic = detect_format(Path::new("a.bin"), &gsf()).map(|r| r.name);
    assert_eq!(gsf_by_magic, Some("gsf"));
}

#[test]
fn a_single_channel_file_reports_its_one_channel_and_refuses_another() {
    let path = Path::new("one.gsf");
    let t = parse_topography_channel(path, &gsf(), None).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(t.channel.as_deref(), Some(HEIGHT_CHANNEL));
    assert_eq!(t.channels, [HEIGHT_CHANNEL]);
    let named = parse_topography_channel(path, &gsf(), Some("Height"));
    assert!(named.is_ok(), "{named:?}");
    let err = parse_topography_channel(path, &gsf(), Some("phase")).unwrap_err();
    match &err {
        ReadError::Parse {
            cause: ParseError::UnknownChannel { wanted, available },
            ..
        } => {
            assert_eq!(wanted, "phase");
            assert_eq!(available, &[HEIGHT_CHANNEL]);
        }
        other => panic!("{other:?}"),
    }
    let message = err.to_string();
    assert!(
        message.contains("one.gsf") && message.contains("`height`") && message.contains("channel:"),
        "{message}"
    );
}

/// The repository's root (two levels above this crate).
fn repository() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// `(format, extensions)` of each row of the table "Topography formats" of
/// docs/study-format.md.
fn documented_formats() -> Vec<(String, Vec<String>)> {
    let path = repository().join("docs/study-format.md");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let section = text
        .split("### Topography formats")
        .nth(1)
        .expect("docs/study-format.md has a section \"Topography formats\"");
    section
        .lines()
        .skip_while(|l| !l.starts_with("| format"))
        .skip(2)
        .take_while(|l| l.starts_with('|'))
        .map(|row| {
            let cells: Vec<&str> = row.split('|').map(str::trim).collect();
            let extensions = cells[2].split(',').map(|e| e.trim().to_string()).collect();
            (cells[1].trim_matches('`').to_string(), extensions)
        })
        .collect()
}

/// The format table of docs/study-format.md has one row per reader, with the reader's
/// extensions: a new reader without its row fails here, naming it.
#[test]
fn the_documented_formats_are_the_registry() {
    let documented = documented_formats();
    let mut problems = Vec::new();
    for reader in READERS {
        let extensions: Vec<String> = reader.extensions.iter().map(|e| e.to_string()).collect();
        match documented.iter().find(|(name, _)| name == reader.name) {
            None => problems.push(format!(
                "`{}` has no row; add `| `{}` | {} | … | {} |`",
                reader.name,
                reader.name,
                extensions.join(", "),
                reader.description
            )),
            Some((_, listed)) if *listed != extensions => problems.push(format!(
                "`{}` lists extensions {listed:?}, the reader {extensions:?}",
                reader.name
            )),
            Some(_) => {}
        }
    }
    for (name, _) in &documented {
        if reader_named(name).is_none() {
            problems.push(format!("the row `{name}` names no reader"));
        }
    }
    assert!(
        problems.is_empty(),
        "docs/study-format.md, \"Topography formats\":\n{}",
        problems.join("\n")
    );
}

/// The fuzz crate holds the generic targets only (`reader` takes its reader from the registry):
/// every `[[bin]]` of fuzz/Cargo.toml has its file and every file its `[[bin]]`, and no target,
/// the fuzz README or the campaign script names readers one by one.
#[test]
fn the_fuzz_targets_take_their_readers_from_the_registry() {
    let fuzz = repository().join("fuzz");
    let manifest = std::fs::read_to_string(fuzz.join("Cargo.toml")).expect("fuzz/Cargo.toml");
    let mut bins: Vec<String> = manifest
        .lines()
        .filter_map(|l| l.strip_prefix("path = \"fuzz_targets/"))
        .map(|l| l.trim_end_matches(".rs\"").to_string())
        .collect();
    bins.sort();
    let mut files: Vec<String> = std::fs::read_dir(fuzz.join("fuzz_targets"))
        .expect("fuzz/fuzz_targets")
        .map(|e| e.expect("entry").path())
        .filter_map(|p| Some(p.file_stem()?.to_str()?.to_string()))
        .collect();
    files.sort();
    assert_eq!(
        bins, files,
        "fuzz/Cargo.toml's [[bin]] paths and fuzz/fuzz_targets/"
    );
    assert_eq!(files, ["reader", "study", "topography"]);
    let names: Vec<&str> = READERS.iter().map(|r| r.name).collect();
    for doc in [
        "fuzz/README.md",
        "scripts/fuzz-campaign.sh",
        "fuzz/src/lib.rs",
    ] {
        let text = std::fs::read_to_string(repository().join(doc)).expect(doc);
        for line in text.lines() {
            let listed: Vec<&&str> = names
                .iter()
                .filter(|n| line.contains(&format!("`{n}`")) || line.contains(&format!(" {n} ")))
                .collect();
            assert!(
                listed.len() < 4,
                "{doc} lists readers by hand ({listed:?}); take them from the registry \
                 (`cargo run -p asperity-numerics --example reader_names`): {line}"
            );
        }
    }
}
