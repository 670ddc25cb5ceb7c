//! Setpoint CSVs (`basr check` of a `compile --csv` file): any text is
//! checked and its problems listed, never a panic, and a text the check
//! passes is one `basr check` recognises as a CSV (`looks_like_csv`), so a
//! sound CSV is never reported as "not a basr file".
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let found = basr_job::csv::check_source(text, "fuzz");
        let csv = basr_job::csv::looks_like_csv(text);
        assert!(
            csv || !found.is_empty(),
            "check_source passed a text looks_like_csv refuses"
        );
        if csv {
            // A lone header is no setpoint file either.
            assert!(text.lines().count() > 1 || !found.is_empty());
        }
    }
});
