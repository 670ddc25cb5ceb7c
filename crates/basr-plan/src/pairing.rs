//! Which point of one edge a rung joins to which point of the other, where
//! equal arc-length steps (001 fig. 2.8) would turn the fan faster than the
//! yaw joint can follow at painting speed.
//!
//! In a bowl's quarter (B, P, R, 3) the two edges' straight runs next to
//! the shared rung differ (the inner edge's is 1 grid unit, the outer's 2),
//! so equal arc-length rungs lean 45° at the start of the straight run and
//! turn square only at the shared rung: 0.8 rad over 0.15 m, faster than
//! the fan can turn at film speed. The turn limit then holds the fan off
//! the shared rung, in opposite directions from the two strokes that meet
//! there, and the footprints cross (docs/planner.md, "What is left in the
//! bowls"). Here such a stroke's rungs are chosen as a shortest path over
//! pairs of fine edge points instead: a rung costs its lean against the
//! direction the nozzle travels (square rungs in a straight band) and a
//! turn faster than the budget; each step moves both ends forward by one
//! to three fine steps (no rung pivots about one of its ends, where the
//! film would go as 1/r), and a wide rung far from the equal arc-length
//! pairing costs (the tilt's balance is at its limit there already).

use kurbo::{Point, Vec2};

use basr_robot::kinematics::wrap_pi;
use basr_shape::font::Stroke;

use super::knots::TiltMethod;
use super::rungs::Rung;
use super::tilt;
use super::tuning::Pairing;

/// What the fan can turn while painting, for choosing rungs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TurnBudget {
    /// speed × width of the film law (m²/s, 001 eq. 2.6).
    pub k_m2ps: f64,
    /// Narrowest band the fan paints (m): narrower rungs are paced by it.
    pub min_width_m: f64,
    /// Turn rate the fan may take while painting (rad/s, `tuning::Rates::turn_share`
    /// of the yaw joint's limit).
    pub max_rate_rps: f64,
    /// The nozzle height's follow; None for a kind without a vertical joint.
    pub height: Option<HeightFollow>,
    /// The tilt's follow; None for a kind that paints untilted.
    pub tilt: Option<TiltFollow>,
    /// The search's tuning.
    pub tuning: Pairing,
}

/// How fast the nozzle height may change while painting.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeightFollow {
    /// Nozzle height per metre of fan width: the height law's slope (001
    /// eq. 2.5 for the geometric law, c1 for a calibrated one).
    pub dz_dw: f64,
    /// Speed (m/s) the height may take (`rate::height_follow`).
    pub max_speed_mps: f64,
}

/// How fast the quadrilateral tilt may change while painting.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TiltFollow {
    /// Full fan angle α (001 eq. 2.17).
    pub fan_angle_rad: f64,
    /// Largest tilt either way.
    pub max_tilt_rad: f64,
    /// Speed (rad/s) the tilt may take (`rate::tilt_follow`).
    pub max_speed_rps: f64,
}

impl TurnBudget {
    /// Fan turn rate (rad/s) of a step that turns `dpsi` over `ds` of
    /// travel with rungs `w` wide, at the film law's speed.
    fn rate(&self, dpsi: f64, ds: f64, w: f64) -> f64 {
        let v = self.k_m2ps / w.max(self.min_width_m);
        dpsi.abs() * v / ds.max(1e-6)
    }
}

/// Most fine points per edge. assumed: bounds the search (≈ 0.15 M states)
/// for long strokes; a bowl quarter at 8 ft needs ≈ 340.
const MAX_FINE: usize = 400;

/// The highest fan turn rate (rad/s) equal arc-length rungs would ask for
/// at film speed.
pub fn worst_rate(rungs: &[(Point, Point)], budget: &TurnBudget) -> f64 {
    rungs
        .windows(2)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            let dpsi = wrap_pi((b.1 - b.0).atan2() - (a.1 - a.0).atan2());
            let ds = (b.0.midpoint(b.1) - a.0.midpoint(a.1)).hypot();
            let wid = 0.5 * ((a.1 - a.0).hypot() + (b.1 - b.0).hypot());
            budget.rate(dpsi, ds, wid)
        })
        .fold(0.0, f64::max)
}

/// How many times what its joint follows the nozzle height and the
/// quadrilateral tilt (001 eq. 2.13–2.20) must change, the larger of the
/// two, along `rungs` painted at the film law's speed (001 eq. 2.6); 0
/// where neither is limited. A width under the fan's narrowest band counts
/// as that band (the nozzle stays at its lowest there).
pub fn follow_demand(rungs: &[(Point, Point)], budget: &TurnBudget) -> f64 {
    let width = |r: &(Point, Point)| (r.1 - r.0).hypot().max(budget.min_width_m);
    let step_s: Vec<f64> = rungs
        .windows(2)
        .map(|w| {
            let ds = (w[1].0.midpoint(w[1].1) - w[0].0.midpoint(w[0].1)).hypot();
            (ds * 0.5 * (width(&w[0]) + width(&w[1])) / budget.k_m2ps).max(1e-9)
        })
        .collect();
    let share = |values: &[f64], limit: f64| {
        values
            .windows(2)
            .zip(&step_s)
            .map(|(v, dt)| (v[1] - v[0]).abs() / dt / limit)
            .fold(0.0, f64::max)
    };
    let height = budget.height.map_or(0.0, |h| {
        let z: Vec<f64> = rungs.iter().map(|r| h.dz_dw * width(r)).collect();
        share(&z, h.max_speed_mps)
    });
    let tilt = budget.tilt.map_or(0.0, |t| {
        let rs: Vec<Rung> = rungs
            .iter()
            .map(|&(left, right)| Rung { left, right })
            .collect();
        let beta = tilt::tilts(
            &rs,
            TiltMethod::Quadrilateral,
            t.fan_angle_rad,
            t.max_tilt_rad,
        );
        share(&beta, t.max_speed_rps)
    });
    height.max(tilt)
}

/// Rungs of `stroke` at most `spacing_m` apart along either edge, chosen by
/// the shortest path described in the module docs; `None` where the edges'
/// lengths are too unequal for it.
pub fn matched_rungs(
    stroke: &Stroke,
    spacing_m: f64,
    budget: &TurnBudget,
) -> Option<Vec<(Point, Point)>> {
    let t = &budget.tuning;
    let (ll, lr) = (stroke.left.length(), stroke.right.length());
    if !(ll > 0.0 && lr > 0.0) || ll.max(lr) > t.max_length_ratio * ll.min(lr) {
        return None;
    }
    let max_step = t.max_step;
    let fine = |len: f64| {
        ((len * t.fine_per_spacing / spacing_m).ceil() as usize)
            .clamp(max_step, MAX_FINE.max(max_step))
    };
    let (nl, nr) = (fine(ll), fine(lr));
    let lp = stroke.left.subdivide(nl);
    let rp = stroke.right.subdivide(nr);
    let (hl, hr) = (ll / nl as f64, lr / nr as f64);
    let idx = |i: usize, j: usize| i * (nr + 1) + j;
    // Every candidate rung's midpoint, vector, width and direction, once
    // (each state's are met by up to max_step² steps in and out; two
    // atan2 per step were a third of planning a bowl): the same values the
    // step costs computed per step, so the same bits.
    let candidates: Vec<Candidate> = (0..=nl)
        .flat_map(|i| (0..=nr).map(move |j| (i, j)))
        .map(|(i, j)| Candidate::new(lp[i], rp[j]))
        .collect();
    let mut cost = vec![f64::INFINITY; (nl + 1) * (nr + 1)];
    let mut from = vec![usize::MAX; (nl + 1) * (nr + 1)];
    cost[0] = 0.0;
    for i in 0..=nl {
        for j in 0..=nr {
            let c0 = cost[idx(i, j)];
            if !c0.is_finite() {
                continue;
            }
            let r0 = &candidates[idx(i, j)];
            for a in 1..=max_step.min(nl - i) {
                for b in 1..=max_step.min(nr - j) {
                    let (i1, j1) = (i + a, j + b);
                    let k = idx(i1, j1);
                    let r1 = &candidates[k];
                    let ds = (r1.m - r0.m).hypot();
                    let w = 0.5 * (r0.width + r1.width);
                    let c = c0
                        + step_cost(r0, r1, ds, w, budget)
                        + t.w_diag
                            * off_diagonal(
                                i1 as f64 / nl as f64,
                                j1 as f64 / nr as f64,
                                ds,
                                w,
                                t.ratio_width_m,
                            );
                    if c < cost[k] {
                        cost[k] = c;
                        from[k] = idx(i, j);
                    }
                }
            }
        }
    }
    let end = idx(nl, nr);
    if !cost[end].is_finite() {
        return None;
    }
    // The path back from the far end: fine (left, right) arc lengths.
    let mut path = vec![];
    let mut k = end;
    loop {
        path.push(((k / (nr + 1)) as f64 * hl, (k % (nr + 1)) as f64 * hr));
        if k == 0 {
            break;
        }
        k = from[k];
    }
    path.reverse();
    Some(resample(stroke, &path, spacing_m))
}

/// A candidate rung between a left and a right edge point: its midpoint,
/// left → right vector, width and direction.
struct Candidate {
    m: Point,
    d: Vec2,
    width: f64,
    psi: f64,
}

impl Candidate {
    fn new(left: Point, right: Point) -> Candidate {
        let d = right - left;
        Candidate {
            m: left.midpoint(right),
            d,
            width: d.hypot(),
            psi: d.atan2(),
        }
    }
}

/// How far a rung's ends are from the equal arc-length pairing (shares of
/// their edges `fl`, `fr`), weighted by the width squared and the travel:
/// wide rungs keep to equal arc-length (where a rung turning about a point
/// near one end lays film ∝ 1/r across it, the tilt's balance is already at
/// its limit in a bowl), narrow ones may leave it to stand square. `ds`:
/// the step's travel between midpoints; `w`: the two rungs' mean width.
fn off_diagonal(fl: f64, fr: f64, ds: f64, w: f64, ratio_width_m: f64) -> f64 {
    let wide = (w / ratio_width_m).powi(2);
    ds * wide * (fr - fl).powi(2)
}

/// Cost of the step from rung `r0` to rung `r1`, `ds` apart (between
/// midpoints), of mean width `w`.
fn step_cost(r0: &Candidate, r1: &Candidate, ds: f64, w: f64, budget: &TurnBudget) -> f64 {
    let travel = r1.m - r0.m;
    let ds = ds.max(1e-6);
    let dpsi = wrap_pi(r1.psi - r0.psi);
    let t = &budget.tuning;
    let over = (budget.rate(dpsi, ds, w) / budget.max_rate_rps - t.turn_free).max(0.0);
    // Lean: the rung's component along the travel (0 when square).
    let dir = (r0.d + r1.d).normalize();
    let lean = dir.dot(travel / ds);
    ds * (t.w_turn * over * over + t.w_lean * lean * lean)
}

/// Rungs at equal steps of the path's edge travel (the larger of the two
/// edges' advance), at most `spacing_m` apart on either edge.
fn resample(stroke: &Stroke, path: &[(f64, f64)], spacing_m: f64) -> Vec<(Point, Point)> {
    let mut u = vec![0.0];
    for w in path.windows(2) {
        let d = (w[1].0 - w[0].0).max(w[1].1 - w[0].1);
        u.push(u.last().unwrap() + d);
    }
    let total = *u.last().unwrap();
    let n = ((total / spacing_m).ceil() as usize).max(1);
    let mut at = Vec::with_capacity(n + 1);
    let mut seg = 0;
    for m in 0..=n {
        let target = total * m as f64 / n as f64;
        while seg + 2 < u.len() && u[seg + 1] < target {
            seg += 1;
        }
        let span = (u[seg + 1] - u[seg]).max(1e-15);
        let f = ((target - u[seg]) / span).clamp(0.0, 1.0);
        let (a, b) = (path[seg], path[seg + 1]);
        at.push((a.0 + f * (b.0 - a.0), a.1 + f * (b.1 - a.1)));
    }
    // The caps exactly as the font gives them; between, points by length.
    let point = |e: &basr_geom::Edge, m: usize, s: f64| match m {
        0 => e.start(),
        m if m == n => e.end(),
        _ => e.point_at_length(s),
    };
    let out: Vec<(Point, Point)> = at
        .iter()
        .enumerate()
        .map(|(m, &(sl, sr))| (point(&stroke.left, m, sl), point(&stroke.right, m, sr)))
        .collect();
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use basr_shape::font::Font;
    use kurbo::Affine;

    /// BASR's budget: k of SPEC §4, its 97 mm narrowest fan, 0.85 × 30°/s.
    const BUDGET: TurnBudget = TurnBudget {
        k_m2ps: 0.4e-3 / 60.0 * 0.9 / 0.38e-3,
        min_width_m: 0.097,
        max_rate_rps: crate::tuning::Tuning::DEFAULT.rates.turn_share * 0.5235987755982988,
        height: None,
        tilt: None,
        tuning: crate::tuning::Tuning::DEFAULT.pairing,
    };

    /// P's upper bowl quarter at 8 ft (a grid unit of 2.4384 m / 25).
    fn p_quarter() -> Stroke {
        let s = &Font::embedded().glyph('P').unwrap().strokes[1];
        s.transformed(&Affine::scale(2.4384 / 25.0))
    }

    #[test]
    fn a_bowl_quarter_gets_square_rungs_at_its_narrow_end() {
        let st = p_quarter();
        let spacing = 0.02;
        let n = (st.left.length().max(st.right.length()) / spacing).ceil() as usize;
        let equal = st.rungs(n);
        assert!(worst_rate(&equal, &BUDGET) > BUDGET.max_rate_rps);
        let m = matched_rungs(&st, spacing, &BUDGET).unwrap();
        // Caps kept; steps within the spacing on both edges; monotone.
        assert_eq!(m[0], equal[0]);
        assert_eq!(*m.last().unwrap(), *equal.last().unwrap());
        for w in m.windows(2) {
            assert!((w[1].0 - w[0].0).hypot() <= spacing * 1.0001);
            assert!((w[1].1 - w[0].1).hypot() <= spacing * 1.0001);
        }
        // Over the last 40 mm the rungs lean off the square shared rung
        // less than equal arc-length rungs do (measured 0.13 against 0.20).
        let yaw = |r: &(Point, Point)| (r.1 - r.0).atan2();
        let end = yaw(m.last().unwrap());
        let near_end = |rs: &[(Point, Point)]| {
            rs.iter()
                .filter(|r| (r.0 - rs.last().unwrap().0).hypot() <= 0.04)
                .map(|r| wrap_pi(yaw(r) - end).abs())
                .fold(0.0, f64::max)
        };
        let (now, before) = (near_end(&m), near_end(&equal));
        assert!(before > 0.15 && now < 0.8 * before, "{now} {before}");
        // And the fan is asked to turn less fast than before.
        assert!(worst_rate(&m, &BUDGET) < worst_rate(&equal, &BUDGET));
    }

    /// BASR's budget with the height's and the tilt's follow (SPEC §4:
    /// 15°/s tilt joint under its 0.11 m/s ball nut, × 0.8; the vertical
    /// joint's speed × 0.8).
    fn followed() -> TurnBudget {
        let robot = basr_robot::AnyRobot::load_or_default(None).unwrap();
        crate::passes::turn_budget(&robot, &crate::tuning::Tuning::DEFAULT)
    }

    #[test]
    fn a_bowl_quarter_keeps_its_matched_rungs_within_the_follow() {
        let b = followed();
        assert!(b.height.is_some() && b.tilt.is_some());
        let st = p_quarter();
        let m = matched_rungs(&st, 0.02, &b).unwrap();
        let ask = follow_demand(&m, &b);
        // Over the follow, but within what the rate limits spread.
        assert!(
            ask > 1.0 && ask <= crate::tuning::Tuning::DEFAULT.pairing.max_follow,
            "{ask}"
        );
    }

    #[test]
    fn the_demand_grows_with_a_faster_tilt_and_is_zero_unlimited() {
        let b = followed();
        let st = p_quarter();
        let m = matched_rungs(&st, 0.02, &b).unwrap();
        let slow = TurnBudget {
            tilt: b.tilt.map(|t| TiltFollow {
                max_speed_rps: 0.5 * t.max_speed_rps,
                ..t
            }),
            ..b
        };
        assert!(follow_demand(&m, &slow) > 1.9 * follow_demand(&m, &b) - 1e-9);
        assert_eq!(follow_demand(&m, &BUDGET), 0.0);
    }

    #[test]
    fn very_unequal_edges_keep_equal_arc_length() {
        let s = &Font::embedded().glyph('I').unwrap().strokes[0];
        let mut st = s.clone();
        st.right = st.right.transformed(&Affine::scale_non_uniform(1.0, 3.0));
        assert!(matched_rungs(&st, 0.02, &BUDGET).is_none());
        // the ratio is the tuning's: P's quarter, whose edges differ, is
        // matched at the default and left to equal arc-length at 1
        let p = p_quarter();
        assert!(matched_rungs(&p, 0.02, &BUDGET).is_some());
        let strict = TurnBudget {
            tuning: Pairing {
                max_length_ratio: 1.0,
                ..BUDGET.tuning
            },
            ..BUDGET
        };
        assert!(matched_rungs(&p, 0.02, &strict).is_none());
    }
}
