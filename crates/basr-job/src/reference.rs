//! Reference points: corners of the marking a crew chalks at a stop so
//! that `basr fit` can measure where the truck really stopped
//! (docs/site.md). Three per stop, as far apart as the stop's own strokes
//! allow: the triangle they span fixes the stop's heading and the road's
//! plane best.

use serde::Serialize;

use super::Job;

/// One point to chalk: a corner of a stroke's outline.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ReferencePoint {
    /// `near-left`, `near-right` or `far` (as the approaching driver sees
    /// the marking).
    pub name: String,
    /// Road frame (m).
    pub road_m: [f64; 2],
}

/// The reference points of stop `index` (counted from 0): among the
/// outline points of the strokes painted from it, the nearest-left
/// (least x + y), the nearest-right (greatest x − y) and the farthest
/// (greatest y). Empty when the stop paints nothing.
pub fn reference_points(job: &Job, index: usize) -> Vec<ReferencePoint> {
    let s = &job.samples;
    let mut painted = std::collections::BTreeSet::new();
    for i in 0..s.len() {
        if s.station[i] as usize == index && s.paint[i] == 1 && s.stroke[i] >= 0 {
            painted.insert(s.stroke[i] as usize);
        }
    }
    let pts: Vec<[f64; 2]> = job
        .layout
        .glyphs
        .iter()
        .flat_map(|g| &g.strokes)
        .enumerate()
        .filter(|(k, _)| painted.contains(k))
        .flat_map(|(_, st)| st.left.iter().chain(&st.right).copied())
        .collect();
    let pick = |key: &dyn Fn(&[f64; 2]) -> f64| {
        pts.iter()
            .copied()
            .reduce(|a, b| if key(&b) > key(&a) { b } else { a })
    };
    let mut out = vec![];
    for (name, key) in [
        (
            "near-left",
            &(|p: &[f64; 2]| -(p[0] + p[1])) as &dyn Fn(&[f64; 2]) -> f64,
        ),
        ("near-right", &|p: &[f64; 2]| p[0] - p[1]),
        ("far", &|p: &[f64; 2]| p[1]),
    ] {
        if let Some(p) = pick(key) {
            if !out.iter().any(|r: &ReferencePoint| r.road_m == p) {
                out.push(ReferencePoint {
                    name: name.into(),
                    road_m: p,
                });
            }
        }
    }
    out
}
