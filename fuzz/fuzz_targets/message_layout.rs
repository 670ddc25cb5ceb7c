//! Messages typed on the command line: any string is laid out or refused.
#![no_main]
use basr_shape::layout::{place, GlyphBox, Marking, Overrides};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        if let Ok(m) = Marking::from_message(text, &Overrides::default()) {
            let _ = place(&m, |c| c.is_ascii_alphanumeric().then_some(GlyphBox::GRID));
        }
    }
});
