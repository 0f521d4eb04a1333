//! Fuzzes the SDF reader (ASCII and binary): arbitrary bytes must give `Ok` or a `ReadError`,
//! never a panic or an allocation sized by an unchecked header.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = asperity_numerics::surface::io::parse_topography(Path::new("fuzz.sdf"), data);
});
