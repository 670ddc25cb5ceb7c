//! `simulate --svg`: the desired and actual nozzle paths on the road with the
//! error magnified, and the error over time against the tolerance.

use std::fmt::Write as _;

use svg::node::element::{Line, Path, Rectangle, Text};
use svg::Document;

use super::report::{Report, TraceRow};

/// Plot size (px).
const W: f64 = 900.0;
const MAP_H: f64 = 700.0;
const TIME_H: f64 = 220.0;
const PAD: f64 = 50.0;

/// Error magnification: the largest error drawn as ≈2 % of the plot's span,
/// rounded down to 1, 2 or 5 × 10ⁿ and at least 1.
fn magnification(max_err: f64, span: f64) -> f64 {
    if max_err <= 0.0 {
        return 1.0;
    }
    let raw = (0.02 * span / max_err).max(1.0);
    let p = 10f64.powf(raw.log10().floor());
    let m = [5.0, 2.0, 1.0]
        .into_iter()
        .find(|&f| f * p <= raw)
        .unwrap_or(1.0);
    m * p
}

fn polyline(pts: impl Iterator<Item = (f64, f64)>) -> String {
    let mut d = String::new();
    for (i, (x, y)) in pts.enumerate() {
        let _ = write!(d, "{}{:.2},{:.2} ", if i == 0 { "M" } else { "L" }, x, y);
    }
    d
}

/// Draw `trace` (one row per control tick) as an SVG document.
pub fn render(trace: &[TraceRow], report: &Report) -> String {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for r in trace {
        x0 = x0.min(r.x_desired_m);
        x1 = x1.max(r.x_desired_m);
        y0 = y0.min(r.y_desired_m);
        y1 = y1.max(r.y_desired_m);
    }
    if trace.is_empty() {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    let span = (x1 - x0).max(y1 - y0).max(1e-3);
    let scale = (W - 2.0 * PAD).min(MAP_H - 2.0 * PAD) / span;
    let map = |x: f64, y: f64| (PAD + (x - x0) * scale, MAP_H - PAD - (y - y0) * scale);
    let mag = magnification(report.max_error_all_m, span);

    let mut doc = Document::new()
        .set("viewBox", (0, 0, W, MAP_H + TIME_H + PAD))
        .set("width", W)
        .set("height", MAP_H + TIME_H + PAD)
        .add(
            Rectangle::new()
                .set("width", "100%")
                .set("height", "100%")
                .set("fill", "white"),
        );

    // paths: split into painting runs so air moves are drawn faintly
    let mut runs: Vec<(bool, Vec<&TraceRow>)> = Vec::new();
    for r in trace {
        let p = r.paint != 0;
        match runs.last_mut() {
            Some((q, v)) if *q == p => v.push(r),
            _ => runs.push((p, vec![r])),
        }
    }
    for (p, rows) in &runs {
        let des = polyline(rows.iter().map(|r| map(r.x_desired_m, r.y_desired_m)));
        let act = polyline(rows.iter().map(|r| {
            map(
                r.x_desired_m + mag * (r.x_m - r.x_desired_m),
                r.y_desired_m + mag * (r.y_m - r.y_desired_m),
            )
        }));
        let (wd, op) = if *p { (1.5, 1.0) } else { (0.6, 0.35) };
        doc = doc
            .add(
                Path::new()
                    .set("d", des)
                    .set("fill", "none")
                    .set("stroke", "#1f77b4")
                    .set("stroke-width", wd)
                    .set("opacity", op),
            )
            .add(
                Path::new()
                    .set("d", act)
                    .set("fill", "none")
                    .set("stroke", "#d62728")
                    .set("stroke-width", wd)
                    .set("opacity", op),
            );
    }
    let title = format!(
        "basr simulate ({}): {} — max {:.2} mm, RMS {:.2} mm while painting; blue desired, red actual with error ×{}",
        report.controller,
        report.verdict.to_uppercase(),
        report.max_error_m * 1e3,
        report.rms_error_m * 1e3,
        mag
    );
    doc = doc.add(
        Text::new(title)
            .set("x", PAD)
            .set("y", 25)
            .set("font-size", 14)
            .set("font-family", "sans-serif"),
    );

    // error over time
    let top = MAP_H + 10.0;
    let t_end = trace.last().map_or(1.0, |r| r.t_s).max(1e-3);
    let e_max = report.max_error_all_m.max(report.tolerance_m) * 1.1;
    let tmap = |t: f64, e: f64| {
        (
            PAD + t / t_end * (W - 2.0 * PAD),
            top + TIME_H - e / e_max * TIME_H,
        )
    };
    doc = doc.add(
        Rectangle::new()
            .set("x", PAD)
            .set("y", top)
            .set("width", W - 2.0 * PAD)
            .set("height", TIME_H)
            .set("fill", "none")
            .set("stroke", "#888"),
    );
    // painting spans shaded
    for (p, rows) in &runs {
        if *p {
            let (a, _) = tmap(rows[0].t_s, 0.0);
            let (b, _) = tmap(rows[rows.len() - 1].t_s, 0.0);
            doc = doc.add(
                Rectangle::new()
                    .set("x", a)
                    .set("y", top)
                    .set("width", (b - a).max(0.5))
                    .set("height", TIME_H)
                    .set("fill", "#eef5ff"),
            );
        }
    }
    let (_, ty) = tmap(0.0, report.tolerance_m);
    doc = doc
        .add(Line::new().set("x1", PAD).set("x2", W - PAD).set("y1", ty).set("y2", ty).set("stroke", "#2ca02c").set("stroke-dasharray", "6,4"))
        .add(Path::new().set("d", polyline(trace.iter().map(|r| tmap(r.t_s, r.error_m)))).set("fill", "none").set("stroke", "#d62728").set("stroke-width", 1))
        .add(
            Text::new(format!(
                "nozzle error (0–{:.2} mm) over {:.1} s; dashed: tolerance {:.2} mm; shaded: painting",
                e_max * 1e3,
                t_end,
                report.tolerance_m * 1e3
            ))
            .set("x", PAD)
            .set("y", top + TIME_H + 25.0)
            .set("font-size", 12)
            .set("font-family", "sans-serif"),
        );
    doc.to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn magnification_is_round_and_at_least_one() {
        assert_eq!(magnification(0.001, 2.0), 20.0);
        assert_eq!(magnification(1.0, 2.0), 1.0);
        assert_eq!(magnification(0.0, 2.0), 1.0);
        assert_eq!(magnification(0.0003, 3.0), 200.0);
    }
}
