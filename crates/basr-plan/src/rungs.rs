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
    rungs_of(strokes, spacing_m, budget, &|_| true)
}

/// [`rungs`] of the strokes `only` names, none for the others: some
/// strokes planned again under another paint law (the strokes over an
/// uneven road, `passes::passes_of`) without the rest.
pub fn rungs_of(
    strokes: &PlacedStrokes,
    spacing_m: f64,
    budget: Option<&TurnBudget>,
    only: &(dyn Fn(usize) -> bool + Sync),
) -> StrokeRungs {
    use rayon::prelude::*;
    StrokeRungs {
        // each stroke's rungs are its own: found in parallel, in order
        rungs: strokes
            .strokes
            .par_iter()
            .enumerate()
            .map(|(sid, ps)| {
                if !only(sid) {
                    return vec![];
                }
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

/// Every rung's ends drawn in along the rung from an edge the rung meets
/// obliquely, by `hold_m` (m) × |cos| of the angle between the rung and
/// the edge's tangent there: nothing where the rung stands square to the
/// edge, `hold_m` where it ran along it (`CompileRequest::hold_ends`).
///
/// Why: the fan's sheet has a depth square to the fan's line (the
/// preview's σ, `basr_robot::paint_law::SHEET_DEPTH_SIGMA_M`). Where the
/// fan meets an edge square, that depth runs along the edge; where a rung
/// meets it obliquely (equally spaced points on an inner and an outer edge
/// that turn at different rates: the ends of O's sides, C's terminals),
/// the depth carries paint across it, a band of constant width whose share
/// of the letter's paint grows as the letter shrinks (docs/planner.md,
/// "Small letters: ends held in"). The edge's tangent at a rung's end is
/// the chord between its neighbours on that edge (one-sided at the
/// stroke's ends). An end is never drawn in by more than a tenth of the
/// rung (a stroke's tapering end, a few millimetres across).
pub fn held(rungs: StrokeRungs, hold_m: f64) -> StrokeRungs {
    StrokeRungs {
        rungs: rungs
            .rungs
            .into_iter()
            .map(|stroke| held_stroke(&stroke, hold_m))
            .collect(),
    }
}

fn held_stroke(stroke: &[Rung], hold_m: f64) -> Vec<Rung> {
    let n = stroke.len();
    if n < 2 {
        return stroke.to_vec();
    }
    // unit tangent of one edge at rung k, from its neighbours
    let tangent = |k: usize, end: fn(&Rung) -> Point| {
        let d = end(&stroke[(k + 1).min(n - 1)]) - end(&stroke[k.saturating_sub(1)]);
        let l = d.hypot();
        if l > 1e-12 {
            d / l
        } else {
            d
        }
    };
    stroke
        .iter()
        .enumerate()
        .map(|(k, r)| {
            let d = r.right - r.left;
            let w = d.hypot();
            if w <= 1e-9 {
                return *r;
            }
            let u = d / w;
            let cap = 0.1 * w;
            let left = (hold_m * u.dot(tangent(k, |r| r.left)).abs()).min(cap);
            let right = (hold_m * u.dot(tangent(k, |r| r.right)).abs()).min(cap);
            Rung {
                left: r.left + u * left,
                right: r.right - u * right,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rung(l: (f64, f64), r: (f64, f64)) -> Rung {
        Rung {
            left: Point::new(l.0, l.1),
            right: Point::new(r.0, r.1),
        }
    }

    /// Rungs square to straight edges keep their ends; where an edge
    /// runs oblique to the rungs, that end moves in along the rung by the
    /// hold × |cos| of the angle, the other end as its own edge says, and
    /// never by more than a tenth of the rung.
    #[test]
    fn ends_move_in_by_the_hold_times_the_edges_obliquity() {
        // a straight stroke 0.1 m wide along +y: rungs along +x
        let square: Vec<Rung> = (0..4)
            .map(|k| rung((0.0, 0.1 * k as f64), (0.1, 0.1 * k as f64)))
            .collect();
        let h = held(
            StrokeRungs {
                rungs: vec![square.clone()],
            },
            0.002,
        );
        assert_eq!(h.rungs[0], square);
        // the right edge leans 45° (x = 0.1 + y), the left stays square
        let leaning: Vec<Rung> = (0..4)
            .map(|k| {
                let y = 0.1 * k as f64;
                rung((0.0, y), (0.1 + y, y))
            })
            .collect();
        let h = held(
            StrokeRungs {
                rungs: vec![leaning.clone()],
            },
            0.002,
        );
        for (hr, r) in h.rungs[0].iter().zip(&leaning) {
            assert!((hr.left - r.left).hypot() < 1e-15, "{hr:?}");
            let moved = r.right.x - hr.right.x;
            assert!((moved - 0.002 * 0.5f64.sqrt()).abs() < 1e-12, "{moved}");
            assert_eq!(hr.right.y, r.right.y);
        }
        // a hold larger than a tenth of the rung is capped there
        let h = held(
            StrokeRungs {
                rungs: vec![leaning.clone()],
            },
            1.0,
        );
        let w = leaning[0].width();
        assert!((leaning[0].right.x - h.rungs[0][0].right.x - 0.1 * w).abs() < 1e-12);
    }
}
