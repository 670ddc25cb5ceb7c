//! Shape import: any text as an SVG (first byte even) or a DXF (odd) through
//! reading, the limits, sizing, regions and the decomposition, at 1 m tall,
//! for the embedded robot's fan. Must never panic, overflow the stack or
//! run unbounded (libFuzzer's -timeout and -rss_limit_mb catch those).
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&first, rest)) = data.split_first() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    let ext = if first % 2 == 0 { "svg" } else { "dxf" };
    let Ok(outline) = basr_shape::read_str(text, ext, "fuzz") else {
        return;
    };
    let robot = basr_robot::AnyRobot::load_or_default(None).expect("embedded robot");
    let bands = basr_shape::Bands::of(&robot);
    let _ = basr_shape::import_outline(&outline, basr_shape::Size::HeightM(1.0), &bands);
});
