//! Fuzzes the X3P reader: arbitrary bytes must give `Ok` or a `ReadError`, never a panic,
//! a hang or an allocation beyond the deflate-ratio bound.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = asperity_numerics::surface::io::parse_topography(Path::new("fuzz.x3p"), data);
});
