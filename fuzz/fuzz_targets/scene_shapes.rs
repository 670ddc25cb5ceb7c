//! Marking scenes with shape items: the input is a scene's TOML, a NUL
//! byte, then the SVG every shape item of the scene reads. The scene goes
//! through `layout::check_marking_source_with` (what `basr check` runs),
//! each shape item imported from that SVG at the size the item asks, for
//! the embedded robot's fan. Must never panic.
#![no_main]
use basr::layout::{ShapeSize, ShapeStrokes};
use basr::shape::Size;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let (scene, svg) = text.split_once('\0').unwrap_or((text, ""));
    let robot = basr::robot::AnyRobot::load_or_default(None).expect("embedded robot");
    let bands = basr::plan::shapes::bands(&robot);
    let shapes = |_: &std::path::Path, size: ShapeSize| -> Result<ShapeStrokes, String> {
        let size = match size {
            ShapeSize::HeightM(h) => Size::HeightM(h),
            ShapeSize::WidthM(w) => Size::WidthM(w),
        };
        let outline = basr::shape::read_str(svg, "svg", "fuzz.svg").map_err(|e| e.to_string())?;
        let mut all =
            basr::shape::import_outline(&outline, size, &bands).map_err(|e| e.to_string())?;
        let first = all.swap_remove(0);
        Ok(ShapeStrokes {
            strokes: first.decomposition.strokes,
            width_m: first.width_m,
            height_m: first.height_m,
        })
    };
    let _ = basr::layout::check_marking_source_with(scene, "fuzz.toml", &shapes);
});
