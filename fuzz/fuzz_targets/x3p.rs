//! Fuzzes the X3P (ISO 25178-72 zip container) reader on arbitrary bytes (see `asperity_fuzz::read_as`).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| asperity_fuzz::read_as("x3p", data));
