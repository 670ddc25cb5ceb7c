//! `basr workspace`: the nozzle's reachable region on the road (base frame).

use std::path::PathBuf;

use anyhow::Context;
use basr::robot::{AnyRobot, Region};
use serde_json::json;
use svg::node::element::{Circle, Line, Path, Text};
use svg::Document;

use super::{Global, Outcome};

/// Reachable region of the nozzle tip on the road.
///
/// The region is given in the base frame (origin on the base rotation axis, +y straight back along the arm's symmetry
/// axis): bounded by the extension range (two arcs) and the base safety
/// window (two straight edges). With --tilt-deg (and --yaw-deg for the fan
/// direction) the region where that tilt is also reachable: the tilt moves
/// the tip, so the region shifts, and where only one of the fan's two
/// branches (ψ with β, ψ+π with −β) has its tilt in range, the yaw joint's
/// range may leave only part of the base window. Prints the area, ranges and tip heights;
/// --json adds the boundary polygon, --svg draws it.
#[derive(clap::Args)]
#[command(
    after_help = "Examples:\n  basr workspace                       # area and ranges of the embedded BASR\n  basr workspace --svg ws.svg          # drawing of the region\n  basr workspace --tilt-deg 15 --yaw-deg 90 --json\n\nJSON: \"boundaries\" holds one polygon per part of the region (several when the\nyaw range cuts the base window); \"boundary\" is the first of them."
)]
pub struct Args {
    /// Robot description file (TOML); default: the embedded BASR.
    #[arg(long, value_name = "FILE")]
    pub robot: Option<PathBuf>,
    /// Write an SVG drawing of the region to FILE.
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,
    /// Print JSON (area, ranges, boundary polygon) on stdout.
    #[arg(long)]
    pub json: bool,
    /// Fan direction in the base frame, degrees from +x counter-clockwise.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub yaw_deg: f64,
    /// Tilt in degrees; the region where this tilt is reachable.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub tilt_deg: f64,
}

/// Degrees wrapped to (−180°, 180°]; `%` on floats is exact.
fn wrap_deg(d: f64) -> f64 {
    let w = d.rem_euclid(360.0);
    (if w > 180.0 { w - 360.0 } else { w }) + 0.0
}

/// Arc sampling of the boundary polygon: 0.1° (≤ 0.5 mm chord error at 5.4 m).
const BOUNDARY_STEP_RAD: f64 = 0.1 * std::f64::consts::PI / 180.0;

pub fn run(args: Args, global: &Global) -> anyhow::Result<Outcome> {
    if let (Some(svg), Some(robot)) = (&args.svg, &args.robot) {
        super::refuse_clashes(&[("--svg", svg)], &[("the robot file (--robot)", robot)])?;
    }
    if let Some(svg) = &args.svg {
        super::outputs::check("--svg", svg, &["svg"])?;
    }
    for (flag, v) in [("--yaw-deg", args.yaw_deg), ("--tilt-deg", args.tilt_deg)] {
        anyhow::ensure!(
            v.is_finite(),
            "{flag} must be a finite number of degrees, got {v}"
        );
    }
    let robot = match AnyRobot::load_or_default(args.robot.as_deref())? {
        AnyRobot::Basr(r) => r,
        other => {
            anyhow::ensure!(
                args.yaw_deg == 0.0 && args.tilt_deg == 0.0,
                "--yaw-deg and --tilt-deg are for BASR; the {} kind's road region is drawn at zero tilt",
                other.kind().name()
            );
            return super::workspace_kinds::run(&other, args.svg.as_deref(), args.json, global);
        }
    };
    let yaw_deg = wrap_deg(args.yaw_deg);
    let region = robot
        .region_for(yaw_deg.to_radians(), args.tilt_deg.to_radians())
        .with_context(|| {
            format!(
                "no tip position is reachable with fan {yaw_deg}° and tilt {}°",
                args.tilt_deg
            )
        })?;
    let boundaries = region.boundaries(BOUNDARY_STEP_RAD);
    if let Some(path) = &args.svg {
        let doc = draw(&region, &boundaries);
        basr::io::write_atomic(path, doc.to_string().as_bytes())?;
        if !global.quiet {
            super::outputs::after_commit(format!("wrote {}", path.display()));
        }
    }
    let inner = region.extension_m[0].hypot(region.a2_m);
    let outer = region.extension_m[1].hypot(region.a2_m);
    if args.json {
        let out = json!({
            "robot": robot.name,
            "robot_sha256": robot.sha256(),
            "yaw_rad": region.yaw_rad,
            "tilt_rad": region.tilt_rad,
            "area_m2": region.area_m2(),
            "base_rot_rad": region.base_rot_rad,
            "sectors_rad": region.sectors_rad,
            "extension_m": region.extension_m,
            "radius_m": [inner, outer],
            "shift_m": region.shift_m,
            "z_range_m": region.z_range_m,
            "boundary": boundaries[0],
            "boundaries": boundaries,
        });
        basr::io::print_stdout(&(serde_json::to_string_pretty(&out)? + "\n"))?;
    } else if !global.quiet {
        note!(
            "{}: reachable tip region on the road (base frame), tilt {:.2}°, fan {:.2}°",
            robot.name,
            args.tilt_deg,
            yaw_deg
        );
        note!("  area          {:.3} m²", region.area_m2());
        note!(
            "  base window   {:.4} .. {:.4} rad ({:.2}° .. {:.2}°)",
            region.base_rot_rad[0],
            region.base_rot_rad[1],
            region.base_rot_rad[0].to_degrees(),
            region.base_rot_rad[1].to_degrees()
        );
        if region.sectors_rad != [region.base_rot_rad] {
            let parts: Vec<String> = region
                .sectors_rad
                .iter()
                .map(|s| {
                    format!(
                        "{:.4} .. {:.4} rad ({:.2}° .. {:.2}°)",
                        s[0],
                        s[1],
                        s[0].to_degrees(),
                        s[1].to_degrees()
                    )
                })
                .collect();
            note!(
                "  fan reaches   {} only: elsewhere the yaw joint's range cannot turn it there with the tilt in range",
                parts.join(", ")
            );
        }
        note!(
            "  extension     {:.4} .. {:.4} m (tip radius {:.4} .. {:.4} m)",
            region.extension_m[0],
            region.extension_m[1],
            inner,
            outer
        );
        note!(
            "  tip height    {:.4} .. {:.4} m",
            region.z_range_m[0],
            region.z_range_m[1]
        );
        if region.shift_m != [0.0, 0.0] {
            note!(
                "  tilt shifts the region by ({:.4}, {:.4}) m",
                region.shift_m[0],
                region.shift_m[1]
            );
        }
    }
    Ok(Outcome::Success)
}

/// SVG of the region: base frame with +y up the page, 100 px per metre.
fn draw(region: &Region, boundaries: &[Vec<[f64; 2]>]) -> Document {
    let scale = 100.0;
    let (mut x0, mut x1, mut y0, mut y1) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for p in boundaries.iter().flatten() {
        x0 = x0.min(p[0]);
        x1 = x1.max(p[0]);
        y0 = y0.min(p[1]);
        y1 = y1.max(p[1]);
    }
    let pad = 0.5;
    let (w, h) = ((x1 - x0 + 2.0 * pad) * scale, (y1 - y0 + 2.0 * pad) * scale);
    let px = |x: f64| (x - x0 + pad) * scale;
    let py = |y: f64| (y1 + pad - y) * scale;
    let mut d = String::new();
    for boundary in boundaries {
        for (i, p) in boundary.iter().enumerate() {
            d.push_str(&format!(
                "{}{:.2},{:.2} ",
                if i == 0 { "M" } else { "L" },
                px(p[0]),
                py(p[1])
            ));
        }
        d.push_str("Z ");
    }
    let area = Path::new()
        .set("d", d)
        .set("fill", "#cfe3f7")
        .set("stroke", "#1f5f99")
        .set("stroke-width", 2);
    let axis_x = Line::new()
        .set("x1", px(x0 - pad))
        .set("y1", py(0.0))
        .set("x2", px(x1 + pad))
        .set("y2", py(0.0))
        .set("stroke", "#888")
        .set("stroke-width", 1);
    let axis_y = Line::new()
        .set("x1", px(0.0))
        .set("y1", py(y0 - pad))
        .set("x2", px(0.0))
        .set("y2", py(y1 + pad))
        .set("stroke", "#888")
        .set("stroke-width", 1);
    let base = Circle::new()
        .set("cx", px(0.0))
        .set("cy", py(0.0))
        .set("r", 5)
        .set("fill", "#333");
    let label = Text::new(format!(
        "reachable tip region: {:.2} m², tilt {:.1}°",
        region.area_m2(),
        region.tilt_rad.to_degrees()
    ))
    .set("x", 10)
    .set("y", 20)
    .set("font-family", "sans-serif")
    .set("font-size", 14);
    let text = |x: f64, y: f64, t: &str| {
        Text::new(t.to_string())
            .set("x", x)
            .set("y", y)
            .set("font-family", "sans-serif")
            .set("font-size", 12)
    };
    // A 1 m scale bar in the lower left corner.
    let bar = Line::new()
        .set("x1", 10)
        .set("y1", h - 15.0)
        .set("x2", 10.0 + scale)
        .set("y2", h - 15.0)
        .set("stroke", "#333")
        .set("stroke-width", 3);
    Document::new()
        .set("viewBox", (0, 0, w.ceil(), h.ceil()))
        .set("width", w.ceil())
        .set("height", h.ceil())
        .add(area)
        .add(axis_x)
        .add(axis_y)
        .add(base)
        .add(label)
        .add(bar)
        .add(text(10.0, h - 22.0, "1 m"))
        .add(text(px(x1 + pad) - 30.0, py(0.0) - 6.0, "x_B"))
        .add(text(px(0.0) + 6.0, 34.0, "y_B"))
        .add(text(px(0.0) + 8.0, py(0.0) - 8.0, "base axis"))
}
