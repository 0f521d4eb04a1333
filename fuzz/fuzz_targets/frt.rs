//! Fuzzes the FRT MicroProf reader on arbitrary bytes (see `asperity_fuzz::read_as`).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| asperity_fuzz::read_as("frt", data));
