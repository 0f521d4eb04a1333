//! The body of the `reader` fuzz target: the bytes go to one reader of the registry
//! (`asperity_numerics::surface::io::READERS`), whatever their magic bytes say, so every input
//! reaches it. The environment variable `FUZZ_READER` names the reader (as `Reader::name`
//! spells it, e.g. `FUZZ_READER=x3p`); without it the first byte picks one of every reader and
//! the rest is the file.

use std::sync::OnceLock;

use asperity_numerics::surface::io::{reader_named, Reader, READERS};

/// Environment variable naming the reader to fuzz.
pub const READER_VARIABLE: &str = "FUZZ_READER";

/// The reader `FUZZ_READER` names, `None` when it is unset. A name that is no reader ends the
/// process (exit 2) with the list of names: a misspelt campaign must not fuzz nothing.
fn chosen_reader() -> Option<&'static Reader> {
    static CHOSEN: OnceLock<Option<&'static Reader>> = OnceLock::new();
    *CHOSEN.get_or_init(|| {
        let name = std::env::var(READER_VARIABLE).ok()?;
        let reader = reader_named(&name);
        if reader.is_none() {
            let names: Vec<&str> = READERS.iter().map(|r| r.name).collect();
            eprintln!(
                "{READER_VARIABLE}={name} names no reader; readers: {}",
                names.join(", ")
            );
            std::process::exit(2);
        }
        reader
    })
}

/// Parses `data` with the chosen reader (or the one its first byte picks): `Ok` or a
/// `ParseError`, never a panic; libFuzzer's `-rss_limit_mb` and `-timeout` catch unbounded
/// allocation or work.
pub fn read_with_reader(data: &[u8]) {
    let (reader, bytes) = match chosen_reader() {
        Some(reader) => (reader, data),
        None => {
            let Some((&pick, rest)) = data.split_first() else {
                return;
            };
            (&READERS[usize::from(pick) % READERS.len()], rest)
        }
    };
    let _ = reader.parse(bytes, None);
}
