//! Checks on built glyphs: caps, rungs, crossing edges, grid bounds, overlap.

use kurbo::Point;

use super::{Stroke, GRID_HEIGHT, GRID_WIDTH};

/// Tolerances of glyph validation, in grid units (symbols: metres).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Shortest allowed rung (opposing points must be at least this far apart).
    pub min_rung: f64,
    /// How far outside the 4 × 25 grid a stroke may reach (round letters
    /// overshoot: appendix A's S reaches y = −0.2 and 25.2).
    pub grid_margin: f64,
    /// Subdivision used to check rungs.
    pub rung_check_n: usize,
    /// Points per edge for the crossing and overlap checks.
    pub samples: usize,
    /// Row spacing of the overlap scan.
    pub scan_step: f64,
    /// Overlap area (square units) below which abutting strokes count as
    /// touching, not overlapping (polyline sampling of shared curved edges).
    pub overlap_area: f64,
    /// The drawing's frame: x from 0 to `frame[0]`, y from 0 to `frame[1]`
    /// (the 4 × 25 grid for letters); `None` checks no bounds (a symbol's
    /// extent is checked against its declared size instead).
    pub frame: Option<[f64; 2]>,
    /// What one unit is, for messages ("units", "m").
    pub unit: &'static str,
}

/// The limits `basr` applies on load.
pub const DEFAULT_LIMITS: Limits = Limits {
    // assumed: half the nominal 1-unit stroke; narrower rungs would need the
    // nozzle lower than the ≈0.10 m rung the vertical joint is sized for (SPEC §4).
    min_rung: 0.5,
    // assumed: covers the seed's 0.2-unit overshoot of round letters with room.
    grid_margin: 0.3,
    rung_check_n: 100,
    samples: 240,
    scan_step: 0.02,
    // assumed: ≈ 1 cm² at an 8 ft letter (1 unit ≈ 0.098 m).
    overlap_area: 0.01,
    frame: Some([GRID_WIDTH, GRID_HEIGHT]),
    unit: "units",
};

fn segments_cross(a0: Point, a1: Point, b0: Point, b1: Point) -> bool {
    let d = |p: Point, q: Point, r: Point| (q - p).cross(r - p);
    let (d1, d2) = (d(b0, b1, a0), d(b0, b1, a1));
    let (d3, d4) = (d(a0, a1, b0), d(a0, a1, b1));
    ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
}

fn signed_area(poly: &[Point]) -> f64 {
    let n = poly.len();
    0.5 * (0..n)
        .map(|i| poly[i].to_vec2().cross(poly[(i + 1) % n].to_vec2()))
        .sum::<f64>()
}

fn outline_of(l: &[Point], r: &[Point]) -> Vec<Point> {
    let mut pts = r.to_vec();
    pts.extend(l.iter().rev());
    pts
}

/// Problems of one stroke alone.
pub fn validate_stroke(ctx: &str, s: &Stroke, lim: &Limits) -> Vec<String> {
    let mut out = vec![];
    let l = s.left.sample(lim.samples);
    let r = s.right.sample(lim.samples);
    // Opposing edges never cross (or touch away from the caps).
    'outer: for i in 0..l.len() - 1 {
        for j in 0..r.len() - 1 {
            if segments_cross(l[i], l[i + 1], r[j], r[j + 1]) {
                out.push(format!(
                    "{ctx}: its left and right edges cross near ({:.2}, {:.2}); \
                     opposing edges must stay apart",
                    l[i].x, l[i].y
                ));
                break 'outer;
            }
        }
    }
    // Rungs long enough (this includes the two caps).
    let rungs = s.rungs(lim.rung_check_n);
    if let Some((i, (a, b))) = rungs
        .iter()
        .enumerate()
        .find(|(_, (a, b))| (*b - *a).hypot() < lim.min_rung)
    {
        let what = if i == 0 {
            "its start cap".to_string()
        } else if i == rungs.len() - 1 {
            "its end cap".to_string()
        } else {
            format!("rung {i} of {}", rungs.len() - 1)
        };
        out.push(format!(
            "{ctx}: {what} from ({:.2}, {:.2}) to ({:.2}, {:.2}) is {:.3} {} long, \
             shorter than the minimum {} (degenerate stroke?)",
            a.x,
            a.y,
            b.x,
            b.y,
            (*b - *a).hypot(),
            lim.unit,
            lim.min_rung
        ));
    }
    // On the grid.
    let m = lim.grid_margin;
    let [fw, fh] = lim.frame.unwrap_or([f64::INFINITY, f64::INFINITY]);
    let off =
        |p: &&Point| lim.frame.is_some() && (p.x < -m || p.x > fw + m || p.y < -m || p.y > fh + m);
    if let Some(p) = l.iter().chain(r.iter()).find(|p| !p.is_finite() || off(p)) {
        if p.is_finite() {
            out.push(format!(
                "{ctx}: reaches ({:.2}, {:.2}), off the {} × {} grid (allowed margin {m})",
                p.x, p.y, fw, fh
            ));
        } else {
            out.push(format!(
                "{ctx}: its placed edges are not finite ({}, {}): a transform overflowed; \
                 keep the numbers near the 4 × 25 grid",
                p.x, p.y
            ));
        }
    }
    // Left on the left: the outline (right forward, left back) turns CCW.
    if out.is_empty() && signed_area(&outline_of(&l, &r)) <= 0.0 {
        out.push(format!(
            "{ctx}: its `left` edge lies on the right of the direction of travel; \
             swap `left` and `right` (or reverse both edges)"
        ));
    }
    out
}

/// Horizontal extents covered by a closed polygon on each scan row.
struct Coverage {
    y0: f64,
    step: f64,
    rows: Vec<Vec<(f64, f64)>>,
}

fn coverage(poly: &[Point], step: f64) -> Coverage {
    let ymin = poly.iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
    let ymax = poly.iter().map(|p| p.y).fold(f64::NEG_INFINITY, f64::max);
    let y0 = (ymin / step).floor() * step;
    let nrows = (((ymax - y0) / step).ceil() as usize).max(1);
    let mut xs: Vec<Vec<f64>> = vec![vec![]; nrows];
    let n = poly.len();
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        let (lo, hi) = if a.y < b.y { (a, b) } else { (b, a) };
        if hi.y == lo.y {
            continue;
        }
        // Rows whose centre y_c satisfies lo.y <= y_c < hi.y.
        let first = (((lo.y - y0) / step - 0.5).ceil().max(0.0)) as usize;
        let mut r = first;
        while r < nrows {
            let yc = y0 + (r as f64 + 0.5) * step;
            if yc >= hi.y {
                break;
            }
            if yc >= lo.y {
                let u = (yc - lo.y) / (hi.y - lo.y);
                xs[r].push(lo.x + u * (hi.x - lo.x));
            }
            r += 1;
        }
    }
    let rows = xs
        .into_iter()
        .map(|mut v| {
            v.sort_by(f64::total_cmp);
            v.chunks_exact(2).map(|c| (c[0], c[1])).collect()
        })
        .collect();
    Coverage { y0, step, rows }
}

/// Area covered by both polygons, and a point inside the overlap.
fn overlap(a: &Coverage, b: &Coverage) -> (f64, Point) {
    let mut area = 0.0;
    let mut at = Point::ORIGIN;
    let mut best = 0.0;
    for (ra, row_a) in a.rows.iter().enumerate() {
        let yc = a.y0 + (ra as f64 + 0.5) * a.step;
        let rb = ((yc - b.y0) / b.step - 0.5).round();
        if rb < 0.0 || rb as usize >= b.rows.len() {
            continue;
        }
        let row_b = &b.rows[rb as usize];
        let mut len = 0.0;
        for &(a0, a1) in row_a {
            for &(b0, b1) in row_b {
                let w = a1.min(b1) - a0.max(b0);
                if w > 0.0 {
                    len += w;
                    if w > best {
                        best = w;
                        at = Point::new(0.5 * (a1.min(b1) + a0.max(b0)), yc);
                    }
                }
            }
        }
        area += len * a.step;
    }
    (area, at)
}

/// Problems of a whole glyph: each stroke, then overlap between strokes.
pub fn validate_glyph(strokes: &[(String, Stroke)], lim: &Limits) -> Vec<String> {
    let mut out = vec![];
    for (ctx, s) in strokes {
        out.extend(validate_stroke(ctx, s, lim));
    }
    if !out.is_empty() {
        return out;
    }
    let cover: Vec<Coverage> = strokes
        .iter()
        .map(|(_, s)| coverage(&s.outline(lim.samples), lim.scan_step))
        .collect();
    for i in 0..strokes.len() {
        for j in i + 1..strokes.len() {
            let (area, at) = overlap(&cover[i], &cover[j]);
            if area > lim.overlap_area {
                out.push(format!(
                    "{}: overlaps stroke {} by about {:.4} square {} near ({:.2}, {:.2}); \
                     strokes may abut but must not paint the same area twice",
                    strokes[j].0,
                    i + 1,
                    area,
                    lim.unit,
                    at.x,
                    at.y
                ));
            }
        }
    }
    out
}

/// Overlap area between two strokes (square units), for tests and tools.
pub fn overlap_area(a: &Stroke, b: &Stroke, lim: &Limits) -> f64 {
    let ca = coverage(&a.outline(lim.samples), lim.scan_step);
    let cb = coverage(&b.outline(lim.samples), lim.scan_step);
    overlap(&ca, &cb).0
}

#[cfg(test)]
mod tests {
    use super::*;
    use basr_geom::{Edge, Segment};

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Stroke {
        // Travels up: left edge at x0, right edge at x1.
        Stroke {
            left: Edge::new(vec![Segment::line((x0, y0), (x0, y1))]).unwrap(),
            right: Edge::new(vec![Segment::line((x1, y0), (x1, y1))]).unwrap(),
        }
    }

    #[test]
    fn overlap_area_of_rectangles() {
        let a = rect(0.0, 0.0, 1.0, 25.0);
        let b = rect(0.5, 10.0, 2.0, 12.0);
        let area = overlap_area(&a, &b, &DEFAULT_LIMITS);
        assert!((area - 1.0).abs() < 0.02, "{area}");
        let c = rect(1.0, 10.0, 2.0, 12.0); // abuts a along x = 1
        assert!(overlap_area(&a, &c, &DEFAULT_LIMITS) < 1e-9);
    }

    #[test]
    fn finds_crossing_short_and_swapped() {
        let ok = rect(0.0, 0.0, 1.0, 25.0);
        assert!(validate_stroke("s", &ok, &DEFAULT_LIMITS).is_empty());
        let swapped = Stroke {
            left: ok.right.clone(),
            right: ok.left.clone(),
        };
        let p = validate_stroke("s", &swapped, &DEFAULT_LIMITS);
        assert!(p[0].contains("swap"), "{p:?}");
        let crossing = Stroke {
            left: Edge::new(vec![Segment::line((0.0, 0.0), (1.0, 25.0))]).unwrap(),
            right: Edge::new(vec![Segment::line((1.0, 0.0), (0.0, 25.0))]).unwrap(),
        };
        let p = validate_stroke("s", &crossing, &DEFAULT_LIMITS);
        assert!(p.iter().any(|m| m.contains("cross")), "{p:?}");
        let thin = rect(0.0, 0.0, 0.1, 25.0);
        let p = validate_stroke("s", &thin, &DEFAULT_LIMITS);
        assert!(p.iter().any(|m| m.contains("start cap")), "{p:?}");
        let off = rect(3.5, 0.0, 4.5, 25.0);
        let p = validate_stroke("s", &off, &DEFAULT_LIMITS);
        assert!(p.iter().any(|m| m.contains("off the")), "{p:?}");
    }
}
