#![no_main]
//! Fuzz target: `hedra_doc::fuzz::step` (the loader plus sanity checks).

libfuzzer_sys::fuzz_target!(|data: &[u8]| hedra_doc::fuzz::step(data));
