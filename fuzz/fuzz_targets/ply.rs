//! Fuzz target `ply`: see `prism_fuzz::ply`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| prism_fuzz::ply(data));
