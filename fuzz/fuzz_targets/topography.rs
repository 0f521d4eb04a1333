//! Fuzzes every topography reader: the first byte picks a file extension of the registry (so formats without
//! magic bytes are reached too), the rest is the file. `Ok` or a `ReadError`, never a panic.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&pick, bytes)) = data.split_first() else {
        return;
    };
    let extensions: Vec<&str> = asperity_numerics::surface::io::READERS
        .iter()
        .flat_map(|r| r.extensions.iter().copied())
        .collect();
    let ext = extensions[usize::from(pick) % extensions.len()];
    let name = format!("fuzz.{ext}");
    let _ = asperity_numerics::surface::io::parse_topography(Path::new(&name), bytes);
});
