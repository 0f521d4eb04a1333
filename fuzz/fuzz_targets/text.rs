//! Fuzzes the text/CSV (matrix, x y z, line scan) reader on arbitrary bytes (see `asperity_fuzz::read_as`).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| asperity_fuzz::read_as("text", data));
