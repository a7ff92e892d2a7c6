//! Fuzz target `scene`: see `prism_fuzz::scene`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| prism_fuzz::scene(data));
