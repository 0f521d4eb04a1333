//! Fuzzes the Digital Surf MNT reader (compound file, tag-length-value tree, zlib blocks) on
//! arbitrary bytes (see `asperity_fuzz::read_as`).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| asperity_fuzz::read_as("mnt", data));
