//! Marking files: parsing and placing must refuse, never panic on, any text.
#![no_main]
use basr_shape::layout::{place, GlyphBox, Marking, Overrides};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        if let Ok(m) = Marking::from_toml(text, "fuzz", &Overrides::default()) {
            let _ = place(&m, |c| c.is_ascii_alphanumeric().then_some(GlyphBox::GRID));
        }
        let _ = basr_shape::layout::check_marking_source(text, "fuzz");
    }
});
