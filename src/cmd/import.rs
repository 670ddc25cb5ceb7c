//! `basr import`: an SVG or DXF outline → its decomposition into strokes,
//! written as an editable one-glyph font file that `--font` reads back.

use std::path::PathBuf;

use basr::shape::{self, Size};

use super::{Global, Outcome};

/// The size options `import` and `compile --shape` share.
#[derive(clap::Args, Clone, Debug)]
pub struct SizeArgs {
    /// Height of the shape on the road, metres unless a unit is written
    /// (0.3–10 m, like a letter; 8ft).
    #[arg(
        long,
        value_name = "H",
        conflicts_with = "shape_width_m",
        allow_hyphen_values = true,
        value_parser = basr::units::metres_value
    )]
    pub shape_height_m: Option<f64>,
    /// Width of the shape on the road, metres unless a unit is written (its
    /// height follows).
    #[arg(long, value_name = "W", allow_hyphen_values = true, value_parser = basr::units::metres_value)]
    pub shape_width_m: Option<f64>,
}

impl SizeArgs {
    pub fn size(&self) -> Size {
        match (self.shape_height_m, self.shape_width_m) {
            (Some(h), _) => Size::HeightM(h),
            (None, Some(w)) => Size::WidthM(w),
            (None, None) => Size::FileUnits,
        }
    }
}

/// Decompose a filled outline (SVG or DXF) into strokes, as an editable font file
///
/// The strokes are bands the fan paints evenly, written as a font file to
/// review, edit and compile.
///
/// Each region of the shape (an outline with its holes) is cut into bands
/// by boustrophedon sweeps (square to its long edges, along and across its
/// long axis), into convex pieces, or, around a hole, into ring-following
/// bands. The candidates are compiled and
/// previewed, best predicted first, until one paints an even film (cv ≤
/// 0.04); the most even of those measured (then the shortest paint time) is
/// kept, and the file's header says which and why. Bands wider than one pass are
/// split into parallel strokes; where the shape is narrower than the fan's
/// narrowest band the report says where and by how much.
#[derive(clap::Args)]
#[command(after_help = "\
Examples:
  basr import logo.svg --shape-height-m 2 -o logo.toml
  basr compile S --font logo.toml --letter-height 2     # paint it
  basr import arrow.dxf -o arrow.toml                    # DXF in its own units
  basr check logo.toml")]
pub struct Args {
    /// The outline: an .svg or a .dxf file.
    pub file: PathBuf,
    /// Font file to write (TOML).
    #[arg(short, long, value_name = "TOML")]
    pub output: PathBuf,
    #[command(flatten)]
    pub size: SizeArgs,
    /// Robot description file, for the fan's band widths [default: the embedded BASR].
    #[arg(long, value_name = "F")]
    pub robot: Option<PathBuf>,
    /// Print the decomposition summary as JSON on stdout.
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: Args, global: &Global) -> anyhow::Result<Outcome> {
    super::refuse_clashes(
        &[("the font file (-o)", &args.output)],
        &[("the shape file", &args.file)],
    )?;
    let robot = basr::robot::AnyRobot::load_or_default(args.robot.as_deref())?;
    let bands = basr::pipeline::shapes::bands(&robot);
    // The file must load back as it will be used (checked before it is written).
    let bar = super::progress_bar(
        !global.quiet && !args.json,
        &format!("{}: trying decompositions", args.file.display()),
    );
    let imported = basr::pipeline::shapes::import_to_file_with_progress(
        &args.file,
        args.size.size(),
        &robot,
        &args.output,
        &|done, total| {
            bar.set_length(total as u64);
            bar.set_position(done as u64);
        },
    );
    bar.finish_and_clear();
    let imported = imported?;
    let d = &imported.decomposition;
    if args.json {
        let v = serde_json::json!({
            "font": args.output.display().to_string(),
            "glyph": shape::GLYPH.to_string(),
            "width_m": imported.width_m,
            "height_m": imported.height_m,
            "area_m2": d.area_m2,
            "strokes": d.strokes.len(),
            "regions": d.regions.iter().map(|r| serde_json::json!({
                "area_m2": r.area_m2,
                "method": r.chosen.method.to_string(),
                "strokes": r.chosen.strokes,
                "predicted_s": r.chosen.time_s,
                "film_error": r.chosen.film_error,
            })).collect::<Vec<_>>(),
            "narrow": d.narrow.iter().map(|n| serde_json::json!({
                "at_m": [n.at.x, n.at.y],
                "width_m": n.width_m,
                "shortfall_m": n.shortfall_m,
                "length_m": n.length_m,
                "unpainted_m2": n.unpainted_m2,
                "overspray_m2": n.overspray_m2,
            })).collect::<Vec<_>>(),
        });
        basr::io::print_stdout(&(serde_json::to_string_pretty(&v)? + "\n"))?;
    }
    if !global.quiet {
        note!(
            "{}: {} stroke(s) for {} ({:.3} × {:.3} m, {:.3} m²)",
            args.output.display(),
            d.strokes.len(),
            args.file.display(),
            imported.width_m,
            imported.height_m,
            d.area_m2
        );
        for l in shape::report_lines(d, &bands).iter().chain(&imported.notes) {
            note!("  {l}");
        }
        note!(
            "  paint it: basr compile {} --font {} --letter-height {}",
            shape::GLYPH,
            args.output.display(),
            basr::io::show_num(imported.height_m)
        );
    }
    Ok(Outcome::Success)
}
