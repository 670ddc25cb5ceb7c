//! Marking scenes with shape items: the input is a scene's TOML, a NUL
//! byte, then the SVG every shape item of the scene reads. The scene goes
//! through `layout::check_marking_source_with` (what `basr check` runs),
//! each shape item imported from that SVG at the size the item asks, for
//! the embedded robot's fan. Must never panic.
#![no_main]
use basr_shape::layout::{ShapeItemError, ShapeSize, ShapeStrokes};
use basr_shape::{Bands, Size};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let (scene, svg) = text.split_once('\0').unwrap_or((text, ""));
    let robot = basr_robot::AnyRobot::load_or_default(None).expect("embedded robot");
    let bands = Bands::of(&robot);
    let shapes = |_: &std::path::Path, size: ShapeSize| -> Result<ShapeStrokes, ShapeItemError> {
        let size = match size {
            ShapeSize::HeightM(h) => Size::HeightM(h),
            ShapeSize::WidthM(w) => Size::WidthM(w),
        };
        let outline = basr_shape::read_str(svg, "svg", "fuzz.svg")?;
        let mut all = basr_shape::import_outline(&outline, size, &bands)?;
        let first = all.swap_remove(0);
        Ok(ShapeStrokes {
            strokes: first.decomposition.strokes,
            width_m: first.width_m,
            height_m: first.height_m,
        })
    };
    let _ = basr_shape::layout::check_marking_source_with(scene, "fuzz.toml", &shapes);
});
