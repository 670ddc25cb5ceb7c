//! Render an SVG to PNG with resvg, to look at alphabet sheets and plots:
//! `cargo run --example svg2png -- in.svg out.png [scale]`.

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 3 {
        return Err("usage: svg2png IN.svg OUT.png [SCALE]".into());
    }
    let scale: f32 = args.get(3).map(|s| s.parse()).transpose()?.unwrap_or(1.0);
    let data = std::fs::read(&args[1])?;
    // Built without resvg's text feature: labels are not drawn, shapes are.
    let opt = resvg::usvg::Options::default();
    let tree = resvg::usvg::Tree::from_data(&data, &opt)?;
    let size = tree
        .size()
        .to_int_size()
        .scale_by(scale)
        .ok_or("bad size")?;
    let mut pixmap =
        resvg::tiny_skia::Pixmap::new(size.width(), size.height()).ok_or("bad size")?;
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::from_scale(scale, scale),
        &mut pixmap.as_mut(),
    );
    pixmap.save_png(&args[2])?;
    Ok(())
}
