#![no_main]
//! Fuzz target: `hedra_doc::fuzz::usd` (the loader plus sanity checks).
//!
//! `usd_from_path` runs the USD crate on a thread of its own and reports a
//! panic there as an unreadable file; only panics elsewhere (and aborts,
//! hangs, memory blow-ups) are crashes here.

libfuzzer_sys::fuzz_target!(
    init: {
        let crash = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if std::thread::current().name() != Some("usd import") {
                crash(info)
            }
        }));
    },
    |data: &[u8]| hedra_doc::fuzz::usd(data)
);
