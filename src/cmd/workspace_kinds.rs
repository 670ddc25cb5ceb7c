//! `basr workspace` for the telescopic and articulated kinds: the
//! cross-section of the wrist's workspace (seed 002: ring, voids, and for
//! the telescopic kind eq. 1's cover tori and eq. 5's envelope) and the
//! region the tip reaches on the road at the middle painting height.

use basr::plot::{self, palette, Frame};
use basr::robot::section::{RoadRegion, Section};
use basr::robot::{AnyRobot, ArmKind};
use serde_json::json;
use svg::node::element::{Circle, Group, Path, Rectangle};
use svg::Document;

use super::{Global, Outcome};

/// Curves of seed 002's algebraic boundary (telescopic only), base frame
/// (r, z): the two cover tori (d_min, d_max over a full turn of θ2) and the
/// envelope points over the stroke.
struct Algebraic {
    covers: Vec<Vec<[f64; 2]>>,
    envelope: Vec<[f64; 2]>,
}

fn algebraic(robot: &AnyRobot) -> Option<Algebraic> {
    let AnyRobot::Telescopic(t) = robot else {
        return None;
    };
    let k = t.dh();
    let h1 = t.arm.base_height_m;
    let l = &t.joints.stroke_m;
    let covers = [l.min, l.max]
        .iter()
        .map(|&d| {
            (0..=720)
                .map(|i| {
                    let p = k.point(0.0, i as f64 * std::f64::consts::TAU / 720.0, d);
                    [p[0].hypot(p[1]), p[2] + h1]
                })
                .collect()
        })
        .collect();
    let envelope = (0..=400)
        .flat_map(|i| k.envelope_points(l.min + (l.max - l.min) * i as f64 / 400.0))
        .map(|[r, z]| [r, z + h1])
        .collect();
    Some(Algebraic { covers, envelope })
}

pub fn run(
    robot: &AnyRobot,
    svg_path: Option<&std::path::Path>,
    json_out: bool,
    global: &Global,
) -> anyhow::Result<Outcome> {
    let arm = robot.arm();
    let section = Section::of(arm);
    let [lo, hi] = arm.tip_heights_m();
    let height = 0.5 * (lo + hi);
    let road = RoadRegion::of(arm, height, section.r_range_m[1] + 0.5);
    let alg = algebraic(robot);
    if let Some(path) = svg_path {
        let doc = draw(arm, &section, &road, alg.as_ref());
        basr::io::write_atomic(path, doc.to_string().as_bytes())?;
        if !global.quiet {
            note!("wrote {}", path.display());
        }
    }
    if json_out {
        let out = json!({
            "robot": arm.name(),
            "kind": arm.kind().name(),
            "robot_sha256": robot.sha256(),
            "section": section,
            "road": road,
            "envelope_points": alg.as_ref().map(|a| a.envelope.len()),
        });
        basr::io::print_stdout(&(serde_json::to_string_pretty(&out)? + "\n"))?;
    } else if !global.quiet {
        note!(
            "{} ({} arm): workspace of the wrist point (seed 002) and of the tip on the road",
            arm.name(),
            arm.kind().name()
        );
        note!(
            "  section       {:.3} m² in (r, z): r {:.3} .. {:.3} m, z {:.3} .. {:.3} m",
            section.area_m2,
            section.r_range_m[0],
            section.r_range_m[1],
            section.z_range_m[0],
            section.z_range_m[1]
        );
        note!(
            "  ring          {} (002: the section {} the base axis)",
            if section.ring { "yes" } else { "no" },
            if section.ring { "keeps off" } else { "reaches" }
        );
        note!("  voids         {}", section.voids);
        if let Some(a) = &alg {
            note!(
                "  envelope      {} points of eq. 1 + eq. 5 over the stroke",
                a.envelope.len()
            );
        }
        note!(
            "  road region   {:.3} m² at tip height {:.3} m (zero tilt, fan along and across x_B)",
            road.area_m2,
            height
        );
    }
    Ok(Outcome::Success)
}

/// Two panels: the section (r, z) and the road region (x, y), 80 px/m.
fn draw(arm: &dyn ArmKind, s: &Section, road: &RoadRegion, alg: Option<&Algebraic>) -> Document {
    let scale = 80.0;
    let pad = 60.0;
    // The section and, when drawn, 002's full-turn tori round it.
    let (mut r1, mut z0, mut z1) = (s.r_range_m[1], s.z_range_m[0].min(0.0), s.z_range_m[1]);
    for p in alg.iter().flat_map(|a| a.covers.iter().flatten()) {
        r1 = r1.max(p[0]);
        z0 = z0.min(p[1]);
        z1 = z1.max(p[1]);
    }
    let r1 = r1 + 0.3;
    let sec = Frame::new(pad, pad + 40.0, scale, [0.0, z0 - 0.3], [r1, z1 + 0.3]);
    let (mut x0, mut x1, mut y0, mut y1) = (-0.5f64, 0.5f64, -0.5f64, 0.5f64);
    for (y, spans) in &road.rows {
        y0 = y0.min(*y);
        y1 = y1.max(*y);
        for sp in spans {
            x0 = x0.min(sp[0]);
            x1 = x1.max(sp[1]);
        }
    }
    let plan = Frame::new(
        sec.left_px + sec.width_px() + 2.0 * pad,
        pad + 40.0,
        scale,
        [x0 - 0.3, y0 - 0.3],
        [x1 + 0.3, y1 + 0.3],
    );
    let w = plan.left_px + plan.width_px() + pad;
    let h = pad + 40.0 + sec.height_px().max(plan.height_px()) + pad;
    let mut cells = String::new();
    for row in 0..s.rows {
        let z = s.origin_m[1] + row as f64 * s.cell_m;
        let mut c = 0;
        while c < s.cols {
            if !s.filled_at(c, row) {
                c += 1;
                continue;
            }
            let start = c;
            while c < s.cols && s.filled_at(c, row) {
                c += 1;
            }
            let ra = s.origin_m[0] + start as f64 * s.cell_m;
            let rb = s.origin_m[0] + c as f64 * s.cell_m;
            cells.push_str(&sec.path_data(
                &[[ra, z], [rb, z], [rb, z + s.cell_m], [ra, z + s.cell_m]],
                true,
            ));
        }
    }
    let mut g = Group::new().add(
        Path::new()
            .set("d", cells)
            .set("fill", "#cfe3f7")
            .set("stroke", "none"),
    );
    // The road (z = 0) and the base axis (r = 0).
    g = g
        .add(
            Path::new()
                .set("d", sec.path_data(&[[0.0, 0.0], [r1, 0.0]], false))
                .set("stroke", palette::INK)
                .set("stroke-dasharray", "4 3"),
        )
        .add(plot::text(
            sec.px([r1, 0.0]).0 - 4.0,
            sec.px([r1, 0.0]).1 - 4.0,
            "road",
            10.0,
            "end",
        ));
    if let Some(a) = alg {
        for c in &a.covers {
            g = g.add(
                Path::new()
                    .set("d", sec.path_data(c, false))
                    .set("fill", "none")
                    .set("stroke", "#d7191c")
                    .set("stroke-width", 1.2),
            );
        }
        for p in a.envelope.iter().step_by(4) {
            let (cx, cy) = sec.px(*p);
            g = g.add(
                Circle::new()
                    .set("cx", plot::num(cx))
                    .set("cy", plot::num(cy))
                    .set("r", 1.5)
                    .set("fill", "#1a9641"),
            );
        }
    }
    g = g.add(plot::axes_named(
        &sec,
        1.0,
        "r (m) from the base axis",
        "z (m)",
    ));
    let mut spans = String::new();
    for (y, row) in &road.rows {
        for sp in row {
            let (ya, yb) = (y - 0.5 * road.row_m, y + 0.5 * road.row_m);
            spans.push_str(
                &plan.path_data(&[[sp[0], ya], [sp[1], ya], [sp[1], yb], [sp[0], yb]], true),
            );
        }
    }
    let (bx, by) = plan.px([0.0, 0.0]);
    g = g
        .add(
            Path::new()
                .set("d", spans)
                .set("fill", "#cfe3f7")
                .set("stroke", "none"),
        )
        .add(
            Circle::new()
                .set("cx", plot::num(bx))
                .set("cy", plot::num(by))
                .set("r", 4)
                .set("fill", palette::INK),
        )
        .add(plot::text(bx + 6.0, by - 6.0, "base axis", 10.0, "start"))
        .add(plot::axes(&plan, 1.0));
    let legend = if alg.is_some() {
        "blue: reached within the joint limits; red: 002 eq. 1 tori at d_min and d_max; green: eq. 1 + eq. 5 envelope"
    } else {
        "blue: reached within the joint limits"
    };
    Document::new()
        .set("viewBox", (0, 0, w.ceil(), h.ceil()))
        .set("width", w.ceil())
        .set("height", h.ceil())
        .add(
            Rectangle::new()
                .set("width", "100%")
                .set("height", "100%")
                .set("fill", "#ffffff"),
        )
        .add(plot::text(
            pad,
            24.0,
            &format!("{} ({} arm): workspace", arm.name(), arm.kind().name()),
            16.0,
            "start",
        ))
        .add(plot::text(pad, 42.0, legend, 11.0, "start"))
        .add(plot::text(
            sec.left_px,
            sec.top_px - 8.0,
            &format!(
                "wrist section: {:.2} m², ring {}, voids {}",
                s.area_m2,
                if s.ring { "yes" } else { "no" },
                s.voids
            ),
            12.0,
            "start",
        ))
        .add(plot::text(
            plan.left_px,
            plan.top_px - 8.0,
            &format!(
                "tip on the road at {:.2} m: {:.2} m² (base frame)",
                road.height_m, road.area_m2
            ),
            12.0,
            "start",
        ))
        .add(g)
}
