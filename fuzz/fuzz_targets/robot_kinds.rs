//! Robot descriptions of every kind (BASR, telescopic, articulated): any
//! text to `AnyRobot::from_toml_str` and `robot::check_source`; a parsed
//! robot's forward kinematics, inverse kinematics of that pose and encoder
//! counts at the middle of its ranges. Must never panic.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let _ = basr_robot::check_source(text, "fuzz");
    if let Ok(robot) = basr_robot::AnyRobot::from_toml_str(text, "fuzz") {
        let q = robot.limits().map(|l| 0.5 * (l.min + l.max));
        let pose = robot.fk(&q);
        let _ = robot.ik(&pose);
        let _ = robot.encoders(&q);
        let _ = robot.problems();
    }
});
