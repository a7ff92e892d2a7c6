//! Fuzz target `obj`: see `prism_fuzz::obj`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| prism_fuzz::obj(data));
