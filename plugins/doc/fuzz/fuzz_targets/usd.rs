#![no_main]
//! Fuzz target: `hedra_doc::fuzz::usd` (the loader plus sanity checks).

libfuzzer_sys::fuzz_target!(|data: &[u8]| hedra_doc::fuzz::usd(data));
