//! Fuzzes one topography reader of the registry (`FUZZ_READER=<name>`), or every reader (the
//! first byte picks one) when the variable is unset; see `asperity_fuzz::read_with_reader`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| asperity_fuzz::read_with_reader(data));
