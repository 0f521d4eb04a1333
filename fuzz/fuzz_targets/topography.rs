//! Fuzzes every topography reader: the first byte picks the file extension (so formats without
//! magic bytes are reached too), the rest is the file. `Ok` or a `ReadError`, never a panic.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;

const EXTENSIONS: [&str; 23] = [
    "dat", "opd", "spm", "gsf", "gwy", "al3d", "zon", "x3p", "sdf", "sur", "npy", "plu", "txt",
    "csv", "tmd", "bcrf", "ibw", "tiff", "top", "stp", "hfm", "nc", "h5",
];

fuzz_target!(|data: &[u8]| {
    let Some((&pick, bytes)) = data.split_first() else {
        return;
    };
    let ext = EXTENSIONS[usize::from(pick) % EXTENSIONS.len()];
    let name = format!("fuzz.{ext}");
    let _ = asperity_numerics::surface::io::parse_topography(Path::new(&name), bytes);
});
