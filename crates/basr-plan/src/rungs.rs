//! Rungs: segments across a stroke joining opposing points of its two
//! edges at equal arc-length steps (001 fig. 2.8), the first stage after
//! the placed strokes.

use kurbo::Point;

use super::pairing::{self, TurnBudget};
use super::placed::PlacedStrokes;

/// One rung: a segment across the stroke joining opposing edge points (road frame, m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rung {
    pub left: Point,
    pub right: Point,
}

impl Rung {
    /// Midpoint: where the untilted nozzle sits (001 §2.4).
    pub fn mid(&self) -> Point {
        self.left.midpoint(self.right)
    }
    /// Rung length: the stroke width to paint.
    pub fn width(&self) -> f64 {
        (self.right - self.left).hypot()
    }
    /// Fan direction ψ, eq. 2.4 (atan2, so the full circle).
    pub fn yaw(&self) -> f64 {
        (self.right - self.left).atan2()
    }
}

/// The rungs of every placed stroke, in stroke order.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct StrokeRungs {
    /// `rungs[stroke]`: its n + 1 rungs, n the fewest equal steps no longer
    /// than the spacing along the longer edge.
    pub rungs: Vec<Vec<Rung>>,
}

/// Subdivide every stroke so consecutive rungs are at most `spacing_m` apart
/// along its longer edge (at least one step). With a `budget`, a stroke
/// whose equal arc-length rungs would turn the fan faster than it can at
/// painting speed gets matched rungs instead (`pairing`), unless those ask
/// the height or the tilt to change faster than their joints follow
/// (the budget's `tuning::Pairing::max_follow`).
pub fn rungs(strokes: &PlacedStrokes, spacing_m: f64, budget: Option<&TurnBudget>) -> StrokeRungs {
    use rayon::prelude::*;
    StrokeRungs {
        // each stroke's rungs are its own: found in parallel, in order
        rungs: strokes
            .strokes
            .par_iter()
            .map(|ps| {
                let st = &ps.stroke;
                let len = st.left.length().max(st.right.length());
                let n = ((len / spacing_m).ceil() as usize).max(1);
                let mut pairs = st.rungs(n);
                if let Some(b) = budget {
                    if pairing::worst_rate(&pairs, b) > b.max_rate_rps {
                        if let Some(m) = pairing::matched_rungs(st, spacing_m, b) {
                            // Kept unless the height or the tilt they ask
                            // for outruns its joint (the arrow's tips at 3 m).
                            let ask = pairing::follow_demand(&m, b);
                            if ask <= b.tuning.max_follow
                                || ask <= pairing::follow_demand(&pairs, b)
                            {
                                pairs = m;
                            }
                        }
                    }
                }
                pairs
                    .into_iter()
                    .map(|(left, right)| Rung { left, right })
                    .collect()
            })
            .collect(),
    }
}
