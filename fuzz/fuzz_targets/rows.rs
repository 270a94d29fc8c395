//! A `check rows` printout of arbitrary text.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    if let Err(e) = rasterlab::measure::check::rows::parse_rows(text) {
        assert!(!e.contains('\n'), "{e}");
    }
});
