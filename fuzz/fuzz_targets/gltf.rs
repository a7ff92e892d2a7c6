//! Fuzz target `gltf`: see `prism_fuzz::gltf`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| prism_fuzz::gltf(data));
