//! Robot descriptions: parsing, validation and a kinematics call must never
//! panic, whatever the text.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        if let Ok(robot) = basr_robot::Robot::from_toml_str(text, "fuzz") {
            let _ = robot.to_toml_string();
            let _ = robot.reach_margin(0.0, 3.0);
        }
        let _ = basr_robot::check_source(text, "fuzz");
    }
});
