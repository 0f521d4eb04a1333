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
