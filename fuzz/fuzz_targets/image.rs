//! Fuzz target `image`: see `prism_fuzz::image`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| prism_fuzz::image(data));
