//! Font files: parsing and validation must refuse, never panic on, any text.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = basr_shape::font::Font::from_toml_str(text, "fuzz");
        let _ = basr_shape::font::check_source(text, "fuzz");
    }
});
