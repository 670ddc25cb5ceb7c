//! `simulate --svg`: the desired and actual nozzle paths on the road with the
//! error magnified, on metre axes, and the error over time against the
//! tolerance, on time and millimetre axes; the worst point marked on both.

use svg::node::element::{Circle, Group, Path, Rectangle};
use svg::Document;

use super::report::{Report, TraceRow};
use basr_plot::{self as plot, num, palette, Frame};

/// Page width and the plots' sizes (px).
const W: f64 = 1000.0;
const PAD: f64 = 70.0;
const MAP_W: f64 = W - 2.0 * PAD;
const MAP_MAX_H: f64 = 640.0;
const TIME_H: f64 = 220.0;
/// Legend box width (px).
const LEGEND_W: f64 = 330.0;
/// Road margin around the desired path (m).
const MAP_MARGIN_M: f64 = 0.1;

const DESIRED: &str = "#1f77b4";
/// Line widths (px) of the desired band and the actual line while painting.
const DESIRED_W: f64 = 4.0;
const ACTUAL_W: f64 = 0.9;
const ACTUAL: &str = "#d62728";
const TOLERANCE: &str = "#2ca02c";
const WORST: &str = "#000000";
const PAINTING_SHADE: &str = "#eef5ff";

/// Error magnification of the path plot, fixed so plots of different jobs
/// compare: 1 mm of error is drawn as 20 mm on the road, so the 1/4 in
/// tolerance shows as 127 mm, about a letter's stroke width at 8 ft.
/// // assumed: large enough to see millimetres on a 4 m wide plot.
pub const ERROR_MAGNIFICATION: f64 = 20.0;

fn polyline(pts: impl Iterator<Item = (f64, f64)>) -> String {
    let mut d = String::new();
    for (i, (x, y)) in pts.enumerate() {
        d.push(if i == 0 { 'M' } else { 'L' });
        d.push_str(&num(x));
        d.push(',');
        d.push_str(&num(y));
        d.push(' ');
    }
    d
}

fn path(d: String, colour: &str, width: f64, opacity: f64, dash: Option<&str>) -> Path {
    let mut p = Path::new()
        .set("d", d)
        .set("fill", "none")
        .set("stroke", colour)
        .set("stroke-width", num(width))
        .set("stroke-linejoin", "round");
    if opacity < 1.0 {
        p = p.set("opacity", num(opacity));
    }
    if let Some(dash) = dash {
        p = p.set("stroke-dasharray", dash);
    }
    p
}

fn marker(x: f64, y: f64) -> Circle {
    Circle::new()
        .set("cx", num(x))
        .set("cy", num(y))
        .set("r", 6)
        .set("fill", "none")
        .set("stroke", WORST)
        .set("stroke-width", 1.5)
}

/// Runs of consecutive rows with the same gun state.
fn runs(trace: &[TraceRow]) -> Vec<(bool, &[TraceRow])> {
    let mut out = Vec::new();
    let mut start = 0;
    for i in 1..=trace.len() {
        if i == trace.len() || (trace[i].paint != 0) != (trace[start].paint != 0) {
            if i > start {
                out.push((trace[start].paint != 0, &trace[start..i]));
            }
            start = i;
        }
    }
    out
}

/// The trace row nearest time `t`.
fn row_at(trace: &[TraceRow], t: f64) -> Option<&TraceRow> {
    let k = trace.partition_point(|r| r.t_s < t);
    let cands = [k.checked_sub(1), Some(k)];
    cands
        .into_iter()
        .flatten()
        .filter_map(|i| trace.get(i))
        .min_by(|a, b| (a.t_s - t).abs().total_cmp(&(b.t_s - t).abs()))
}

/// Ticks of 1, 2 or 5 × 10ⁿ over `lo..=hi`, about `n` of them.
fn ticks(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    let step = plot::nice_step((hi - lo) / n.max(1) as f64);
    if step.is_nan() || step <= 0.0 {
        return vec![];
    }
    let first = (lo / step).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    (first..=last.min(first + 200))
        .map(|k| k as f64 * step)
        .collect()
}

/// Draw `trace` (one row per control tick) as an SVG document.
pub fn render(trace: &[TraceRow], report: &Report) -> String {
    let mut lo = [f64::MAX, f64::MAX];
    let mut hi = [f64::MIN, f64::MIN];
    for r in trace {
        lo = [lo[0].min(r.x_desired_m), lo[1].min(r.y_desired_m)];
        hi = [hi[0].max(r.x_desired_m), hi[1].max(r.y_desired_m)];
    }
    if trace.is_empty() || !(lo[0].is_finite() && hi[1].is_finite()) {
        (lo, hi) = ([0.0, 0.0], [1.0, 1.0]);
    }
    let road_min = [lo[0] - MAP_MARGIN_M, lo[1] - MAP_MARGIN_M];
    let road_max = [hi[0] + MAP_MARGIN_M, hi[1] + MAP_MARGIN_M];
    let (span_x, span_y) = (road_max[0] - road_min[0], road_max[1] - road_min[1]);
    let px_per_m = (MAP_W / span_x).min(MAP_MAX_H / span_y);
    let map_top = 80.0;
    let frame = Frame::new(PAD, map_top, px_per_m, road_min, road_max);
    let mag = ERROR_MAGNIFICATION;
    let groups = runs(trace);

    let mut g = Group::new();
    let title = format!(
        "basr simulate ({}): {} — max {:.2} mm, RMS {:.2} mm while painting (tolerance {:.2} mm)",
        report.controller,
        report.verdict.name().to_uppercase(),
        report.max_error_m * 1e3,
        report.rms_error_m * 1e3,
        report.tolerance_m * 1e3,
    );
    g = g.add(plot::text(PAD, 30.0, &title, 15.0, "start").set("font-weight", "bold"));
    g = g.add(plot::text(
        PAD,
        50.0,
        &format!(
            "nozzle on the road: desired (pale blue band) and actual (red line, its error from the desired drawn ×{}); dashed: air moves",
            num(mag)
        ),
        12.0,
        "start",
    ));

    // The map: the desired path as a wide pale band, the actual as a thin
    // line over it, so both show and the actual leaves the band where its
    // (magnified) error is large.
    // About 8 ticks along the longer side, at least 3 along the shorter.
    let tick_m =
        plot::nice_step(span_x.max(span_y) / 8.0).min(plot::nice_step(span_x.min(span_y) / 3.0));
    g = g.add(plot::axes(&frame, tick_m));
    for (painting, rows) in &groups {
        let (w, op, dash) = if *painting {
            (DESIRED_W, 0.45, None)
        } else {
            (1.2, 0.35, Some("4,3"))
        };
        let des = polyline(
            rows.iter()
                .map(|r| frame.px([r.x_desired_m, r.y_desired_m])),
        );
        g = g.add(path(des, DESIRED, w, op, dash));
    }
    for (painting, rows) in &groups {
        let (w, op, dash) = if *painting {
            (ACTUAL_W, 1.0, None)
        } else {
            (0.6, 0.5, Some("4,3"))
        };
        let act = polyline(rows.iter().map(|r| {
            frame.px([
                r.x_desired_m + mag * (r.x_m - r.x_desired_m),
                r.y_desired_m + mag * (r.y_m - r.y_desired_m),
            ])
        }));
        g = g.add(path(act, ACTUAL, w, op, dash));
    }
    let w = &report.worst;
    let worst_label = format!(
        "worst while painting: {:.2} mm at t = {:.1} s, {}",
        report.max_error_m * 1e3,
        w.t_s,
        w.stroke_name()
    );
    if !trace.is_empty() {
        let (wx, wy) = frame.px([w.x_m, w.y_m]);
        g = g.add(marker(wx, wy));
    }
    // Legend: right of the map when it leaves room, else in its top right.
    let map_right = PAD + frame.width_px();
    let lx = if map_right + LEGEND_W + 40.0 <= W {
        map_right + 30.0
    } else {
        PAD + MAP_W - LEGEND_W
    };
    let ly = map_top + 14.0;
    let items: [(&str, f64, &str); 2] = [
        (DESIRED, DESIRED_W, "desired (the job's x_m, y_m)"),
        (ACTUAL, ACTUAL_W, "actual, error ×"),
    ];
    let mut legend = Group::new().add(
        Rectangle::new()
            .set("x", num(lx - 8.0))
            .set("y", num(ly - 12.0))
            .set("width", num(LEGEND_W))
            .set("height", 62)
            .set("fill", "#ffffff")
            .set("opacity", 0.85)
            .set("stroke", "#bbbbbb")
            .set("stroke-width", 0.5),
    );
    for (k, (colour, width, label)) in items.iter().enumerate() {
        let y = ly + 16.0 * k as f64;
        let label = if *colour == ACTUAL {
            format!("{label}{}", num(mag))
        } else {
            label.to_string()
        };
        let op = if *colour == DESIRED { 0.45 } else { 1.0 };
        legend = legend
            .add(plot::line(lx, y, lx + 24.0, y, colour, *width).set("opacity", num(op)))
            .add(plot::text(lx + 32.0, y + 4.0, &label, 11.0, "start"));
    }
    legend = legend.add(marker(lx + 12.0, ly + 32.0)).add(plot::text(
        lx + 32.0,
        ly + 36.0,
        &worst_label,
        11.0,
        "start",
    ));
    g = g.add(legend);

    // Error over time.
    let top = map_top + frame.height_px() + 70.0;
    let (left, right) = (PAD, W - PAD);
    let t_end = trace.last().map_or(1.0, |r| r.t_s).max(1e-3);
    let e_max_mm = (report.max_error_all_m.max(report.tolerance_m) * 1.1 * 1e3).max(1e-3);
    let tx = |t: f64| left + t / t_end * (right - left);
    let ey = |e_mm: f64| top + TIME_H - e_mm / e_max_mm * TIME_H;
    for (painting, rows) in &groups {
        if *painting {
            let (a, b) = (tx(rows[0].t_s), tx(rows[rows.len() - 1].t_s));
            g = g.add(
                Rectangle::new()
                    .set("x", num(a))
                    .set("y", num(top))
                    .set("width", num((b - a).max(0.5)))
                    .set("height", num(TIME_H))
                    .set("fill", PAINTING_SHADE),
            );
        }
    }
    g = g.add(
        Rectangle::new()
            .set("x", num(left))
            .set("y", num(top))
            .set("width", num(right - left))
            .set("height", num(TIME_H))
            .set("fill", "none")
            .set("stroke", palette::INK)
            .set("stroke-width", 0.8),
    );
    for t in ticks(0.0, t_end, 10) {
        let x = tx(t);
        g = g
            .add(plot::line(
                x,
                top + TIME_H,
                x,
                top + TIME_H + 4.0,
                palette::INK,
                0.8,
            ))
            .add(plot::text(x, top + TIME_H + 16.0, &num(t), 10.0, "middle"));
    }
    for e in ticks(0.0, e_max_mm, 5) {
        let y = ey(e);
        g = g
            .add(plot::line(left - 4.0, y, left, y, palette::INK, 0.8))
            .add(plot::line(left, y, right, y, "#dddddd", 0.5))
            .add(plot::text(left - 7.0, y + 3.5, &num(e), 10.0, "end"));
    }
    g = g
        .add(plot::text(
            (left + right) / 2.0,
            top + TIME_H + 32.0,
            "time (s); shaded: painting",
            11.0,
            "middle",
        ))
        .add(
            plot::text(
                left - 40.0,
                top + TIME_H / 2.0,
                "nozzle error (mm)",
                11.0,
                "middle",
            )
            .set(
                "transform",
                format!(
                    "rotate(-90 {} {})",
                    num(left - 40.0),
                    num(top + TIME_H / 2.0)
                ),
            ),
        );
    let tol_y = ey(report.tolerance_m * 1e3);
    g = g
        .add(plot::line(left, tol_y, right, tol_y, TOLERANCE, 1.2).set("stroke-dasharray", "6,4"))
        .add(
            plot::text(
                right - 4.0,
                tol_y - 5.0,
                &format!("tolerance {:.2} mm", report.tolerance_m * 1e3),
                10.0,
                "end",
            )
            .set("fill", TOLERANCE),
        )
        .add(path(
            polyline(trace.iter().map(|r| (tx(r.t_s), ey(r.error_m * 1e3)))),
            ACTUAL,
            0.8,
            1.0,
            None,
        ));
    if let Some(r) = row_at(trace, w.t_s) {
        let (x, y) = (tx(r.t_s), ey(r.error_m * 1e3));
        let anchor = if x > (left + right) / 2.0 {
            "end"
        } else {
            "start"
        };
        // The label above the plot on a dotted leader, clear of the curve
        // and of the tolerance's label.
        let dx = if anchor == "end" { -6.0 } else { 6.0 };
        g = g
            .add(marker(x, y))
            .add(plot::line(x, top + 4.0, x, y - 6.0, WORST, 0.8).set("stroke-dasharray", "2,2"))
            .add(plot::text(x + dx, top - 6.0, &worst_label, 11.0, anchor));
    }

    let height = top + TIME_H + 50.0;
    let doc = Document::new()
        .set("viewBox", format!("0 0 {} {}", num(W), num(height)))
        .set("width", num(W))
        .set("height", num(height))
        .add(
            Rectangle::new()
                .set("width", "100%")
                .set("height", "100%")
                .set("fill", "white"),
        )
        .add(g);
    let mut out = doc.to_string();
    out.push('\n');
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_split_on_the_gun_state() {
        let row = |paint: u8| TraceRow {
            paint,
            ..Default::default()
        };
        let t = [row(0), row(1), row(1), row(0)];
        let r = runs(&t);
        let shape: Vec<(bool, usize)> = r.iter().map(|(p, rows)| (*p, rows.len())).collect();
        assert_eq!(shape, [(false, 1), (true, 2), (false, 1)]);
    }

    #[test]
    fn ticks_are_round_and_bounded() {
        assert_eq!(ticks(0.0, 10.0, 5), [0.0, 2.0, 4.0, 6.0, 8.0, 10.0]);
        assert!(ticks(0.0, 0.0, 5).is_empty());
    }
}
