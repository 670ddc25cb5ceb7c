//! Reference points: corners of the marking a crew chalks at a stop so
//! that `basr fit` can measure where the truck really stopped
//! (docs/site.md). Three per stop, as far apart as the stop's own strokes
//! allow: the triangle they span fixes the stop's heading and the road's
//! plane best.

use serde::Serialize;

use super::{Job, PlacedStroke};

/// A point on the line's other side is listed when it lies at least this
/// share as far from the line as the furthest one. assumed: a quarter; a
/// nearer one adds a point to chalk for little spread.
const SECOND_SIDE: f64 = 0.25;

/// One point to chalk: a corner of a stroke's outline.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ReferencePoint {
    /// `A` to `D`, nearest the approaching driver first.
    pub name: String,
    /// Road frame (m).
    pub road_m: [f64; 2],
}

/// The outlines (`layout.glyphs`' strokes) of the strokes the job paints
/// from stop `index` (counted from 0), in stroke order.
pub fn stop_strokes(job: &Job, index: usize) -> Vec<&PlacedStroke> {
    strokes_by_stop(job)
        .into_iter()
        .nth(index)
        .unwrap_or_default()
}

/// [`stop_strokes`] of every stop, from one pass over the job's rows.
pub fn strokes_by_stop(job: &Job) -> Vec<Vec<&PlacedStroke>> {
    let s = &job.samples;
    let mut painted = vec![std::collections::BTreeSet::new(); job.stations.len()];
    for i in 0..s.len() {
        if s.paint[i] == 1 && s.stroke[i] >= 0 {
            if let Some(set) = painted.get_mut(s.station[i] as usize) {
                set.insert(s.stroke[i] as usize);
            }
        }
    }
    let all: Vec<&PlacedStroke> = job.layout.glyphs.iter().flat_map(|g| &g.strokes).collect();
    painted
        .iter()
        .map(|set| set.iter().filter_map(|&k| all.get(k).copied()).collect())
        .collect()
}

/// How far (m) road point `p` lies from `strokes` (a stop's, from
/// [`strokes_by_stop`]): none inside one, else the distance to the nearest
/// point of their outlines; `None` for no strokes. Whether a measured point
/// is one of a stop's does not depend on where the truck stood (a fitted
/// stop paints the same marking).
pub fn distance_to_strokes(strokes: &[&PlacedStroke], p: [f64; 2]) -> Option<f64> {
    let dist = |a: [f64; 2]| (a[0] - p[0]).hypot(a[1] - p[1]);
    strokes
        .iter()
        .map(|st| {
            // the outline: one edge out, the other back
            let ring: Vec<[f64; 2]> = st
                .left
                .iter()
                .chain(st.right.iter().rev())
                .copied()
                .collect();
            if inside(&ring, p) {
                0.0
            } else {
                ring.iter().map(|&a| dist(a)).fold(f64::INFINITY, f64::min)
            }
        })
        .reduce(f64::min)
}

/// Whether `p` lies inside the closed polygon `ring` (even–odd rule).
fn inside(ring: &[[f64; 2]], p: [f64; 2]) -> bool {
    let mut c = false;
    for (i, a) in ring.iter().enumerate() {
        let b = ring[(i + 1) % ring.len()];
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if p[0] < x {
                c = !c;
            }
        }
    }
    c
}

/// The reference points of stop `index` (counted from 0): among the
/// outline points of the strokes painted from it, the two furthest apart
/// and the furthest from the line through them on each side, so the
/// points span as much of the stop's strokes as they can (they fix the
/// stop's heading, and the road's plane, best): three or four, named `A`
/// to `D` nearest the driver first. Empty when the stop paints nothing;
/// fewer than three when its outline has fewer distinct points.
pub fn reference_points(job: &Job, index: usize) -> Vec<ReferencePoint> {
    let pts: Vec<[f64; 2]> = stop_strokes(job, index)
        .into_iter()
        .flat_map(|st| st.left.iter().chain(&st.right).copied())
        .collect();
    let dist = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
    // The furthest pair (first found on ties: deterministic).
    let mut pair: Option<(usize, usize, f64)> = None;
    for i in 0..pts.len() {
        for j in i + 1..pts.len() {
            let d = dist(pts[i], pts[j]);
            if pair.is_none_or(|(_, _, b)| d > b) {
                pair = Some((i, j, d));
            }
        }
    }
    let Some((i, j, d)) = pair.filter(|p| p.2 > 0.0) else {
        return pts
            .first()
            .map(|&p| {
                vec![ReferencePoint {
                    name: "point".into(),
                    road_m: p,
                }]
            })
            .unwrap_or_default();
    };
    let (a, b) = (pts[i], pts[j]);
    // Signed distance from the line a → b (left of it positive).
    let side = |p: [f64; 2]| ((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])) / d;
    let furthest = |sign: f64| {
        pts.iter()
            .copied()
            .map(|p| (p, sign * side(p)))
            .filter(|&(_, h)| h > 0.0)
            .reduce(|x, y| if y.1 > x.1 { y } else { x })
    };
    let mut chosen = vec![a, b];
    // The furthest point each side of the line: a quadrilateral over the
    // stop's strokes, so the fitted plane is interpolated under them, not
    // extrapolated. One side only where the other adds little.
    let sides: Vec<([f64; 2], f64)> = [1.0, -1.0].into_iter().filter_map(furthest).collect();
    let widest = sides.iter().map(|s| s.1).fold(0.0, f64::max);
    chosen.extend(
        sides
            .iter()
            .filter(|s| s.1 >= SECOND_SIDE * widest)
            .map(|s| s.0),
    );
    // Nearest the driver first (the order the crew walks them), then left
    // to right; named A, B, C, D in that order (the picture numbers them
    // alike), their places said in words beside them.
    chosen.sort_by(|x, y| x[1].total_cmp(&y[1]).then(x[0].total_cmp(&y[0])));
    let out: Vec<ReferencePoint> = chosen
        .into_iter()
        .zip(["A", "B", "C", "D"])
        .map(|(p, name)| ReferencePoint {
            name: name.into(),
            road_m: p,
        })
        .collect();
    out
}

#[cfg(test)]
mod tests {
    use super::inside;

    /// The even–odd test over a square and a concave outline (a U, as a
    /// bowl's stroke is), points inside, outside and in the notch.
    #[test]
    fn inside_tells_the_outline_s_inside_from_its_notch() {
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert!(inside(&square, [0.5, 0.5]));
        assert!(!inside(&square, [1.5, 0.5]));
        assert!(!inside(&square, [0.5, -0.1]));
        let u = [
            [0.0, 0.0],
            [3.0, 0.0],
            [3.0, 3.0],
            [2.0, 3.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [1.0, 3.0],
            [0.0, 3.0],
        ];
        assert!(inside(&u, [0.5, 2.0]));
        assert!(inside(&u, [1.5, 0.5]));
        assert!(!inside(&u, [1.5, 2.0]), "the notch is outside");
    }
}
