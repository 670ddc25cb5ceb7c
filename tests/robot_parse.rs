//! Robustness of robot-description parsing: damaged files never panic and
//! every problem names the file.

use basr::robot::{check_source, Robot, BASR_TOML};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// Replace the value of one `key = value` line with arbitrary text.
    #[test]
    fn damaged_values_are_reported_not_panicked(
        line_pick in any::<prop::sample::Index>(),
        junk in "[ -~]{0,12}",
    ) {
        let lines: Vec<&str> = BASR_TOML.lines().collect();
        let value_lines: Vec<usize> = lines
            .iter()
            .enumerate()
            .filter(|(_, l)| !l.trim_start().starts_with('#') && l.contains(" = "))
            .map(|(i, _)| i)
            .collect();
        let i = value_lines[line_pick.index(value_lines.len())];
        let key = lines[i].split(" = ").next().unwrap();
        let mut edited: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
        edited[i] = format!("{key} = {junk}");
        let text = edited.join("\n");
        let problems = check_source(&text, "damaged.toml");
        for p in &problems {
            prop_assert!(p.starts_with("damaged.toml"), "{p}");
        }
        if problems.is_empty() {
            // Accepted only when it still is a valid description.
            prop_assert!(Robot::from_toml_str(&text, "damaged.toml").is_ok());
        }
    }

    /// Arbitrary text never panics the parser.
    #[test]
    fn arbitrary_text_never_panics(text in "\\PC{0,200}") {
        let _ = check_source(&text, "x.toml");
        let with_arm = format!("[arm]\n{text}");
        let _ = check_source(&with_arm, "x.toml");
    }
}

#[test]
fn embedded_description_checks_clean() {
    assert!(check_source(BASR_TOML, "robots/basr.toml").is_empty());
}
