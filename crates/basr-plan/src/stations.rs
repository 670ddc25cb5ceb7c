//! Truck stations: splitting a message so every stroke is reachable from one station.
//!
//! The truck drives with the traffic (+y of the road frame) and the arm
//! paints behind it, so every station has heading −π/2 (SPEC §2) and the
//! truck visits stations in increasing y. Items (strokes or passes) are
//! taken nearest the driver first and added to the current station while
//! one base position still reaches all of them with the required margin
//! (a greedy cover along the lane, which gives the fewest stations when
//! reach is an interval along y); the station is then put where the worst
//! margin over its items is largest.

use std::collections::HashMap;
use std::f64::consts::FRAC_PI_2;

pub use super::error::StationError;
use crate::knots::Knot;
use crate::passes::Passes;
use basr_job::Station;
use basr_robot::AnyRobot;

/// Heading of every station: truck with the traffic, arm behind (SPEC §2).
pub const HEADING_RAD: f64 = -FRAC_PI_2;
/// Margin (m) every painted point keeps from the edge of the reachable
/// region; assumed: covers the tilt's offset of the tip from the yaw axis
/// (≤ 0.03 m at 15°) and leaves room for the controller's overshoot.
pub const DEFAULT_MARGIN_M: f64 = 0.05;
/// Steps of the search over the station's position along the lane (m).
const Y_COARSE_M: f64 = 0.05;
const Y_STEP_M: f64 = 0.005;
/// No arm of this class reaches further (m); bounds the search, and a group
/// taller than this is never tried as one station.
const MAX_REACH_M: f64 = 10.0;
/// Step of the search over the station's lateral position (m).
const X_STEP_M: f64 = 0.05;

/// The SPEC §4 reach of the BASR arm, used until a robot description
/// supplies its own: base rotation window, extension range and offset.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SectorReach {
    /// θ1 safety window (SPEC §4: 0.7854–2.3562 rad).
    pub theta_min: f64,
    pub theta_max: f64,
    /// Extension range (SPEC §4: 1.55 m retracted, about 5.36 m extended).
    pub r_min: f64,
    pub r_max: f64,
    /// Arm–end-effector offset (SPEC §4: 0.01 m).
    pub a2: f64,
}

impl Default for SectorReach {
    fn default() -> Self {
        SectorReach {
            theta_min: std::f64::consts::FRAC_PI_4, // SPEC §4: 0.7854
            theta_max: 3.0 * std::f64::consts::FRAC_PI_4, // SPEC §4: 2.3562
            r_min: 1.55,                            // SPEC §4
            r_max: 1.55 + 8.333 * 0.457,            // SPEC §4: 8.333 × 0.457 m stroke
            a2: 0.01,                               // SPEC §4
        }
    }
}

impl SectorReach {
    /// Signed distance-like margin (m) of a base-frame point: positive inside
    /// the reachable region, the smallest of the distances to its four edges.
    pub fn margin(&self, x_b: f64, y_b: f64) -> f64 {
        let w2 = x_b * x_b + y_b * y_b;
        // SPEC §2: W = R·u(θ) + a2·u(θ − π/2), so |W|² = R² + a2².
        let r = (w2 - self.a2 * self.a2).max(0.0).sqrt();
        let theta = y_b.atan2(x_b) + self.a2.atan2(r);
        let lateral = |d: f64| {
            if d.abs() < FRAC_PI_2 {
                r * d.sin()
            } else {
                -r - d.abs()
            }
        };
        (r - self.r_min)
            .min(self.r_max - r)
            .min(lateral(theta - self.theta_min))
            .min(lateral(self.theta_max - theta))
    }
}

/// Stations and which station paints each item.
#[derive(Clone, Debug, PartialEq)]
pub struct StationPlan {
    pub stations: Vec<Station>,
    /// `station_of[item]`: index into `stations`.
    pub station_of: Vec<usize>,
    /// Worst margin (m) of each station over its items.
    pub margin_m: Vec<f64>,
    /// The road surface the stations stand on and paint (flat unless the
    /// marking describes it or `basr fit` measured it).
    pub road: basr_job::Road,
}

/// Plan stations for `items` (each a set of road-frame points that must be
/// reachable from one station). `reach_margin(x_b, y_b)` is the robot's
/// margin in its base frame; the truck's axis stays inside the lane
/// (|x| ≤ `lane_half_width_m`).
pub fn plan(
    items: &[Vec<[f64; 2]>],
    lane_half_width_m: f64,
    margin_m: f64,
    reach_margin: impl Fn(f64, f64) -> f64,
) -> Result<StationPlan, StationError> {
    let ymin = |pts: &[[f64; 2]]| pts.iter().map(|p| p[1]).fold(f64::INFINITY, f64::min);
    let xmin = |pts: &[[f64; 2]]| pts.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min);
    let mut idx: Vec<usize> = (0..items.len()).collect();
    idx.sort_by(|&a, &b| {
        ymin(&items[a])
            .total_cmp(&ymin(&items[b]))
            .then(xmin(&items[a]).total_cmp(&xmin(&items[b])))
            .then(a.cmp(&b))
    });
    let mut out = StationPlan {
        stations: vec![],
        station_of: vec![0; items.len()],
        margin_m: vec![],
        road: basr_job::Road::default(),
    };
    let mut group: Vec<usize> = vec![];
    let mut best: Option<(Station, f64)> = None;
    let mut memo = Memo::default();
    for &i in &idx {
        let mut trial = group.clone();
        trial.push(i);
        // The search puts the truck at or ahead of the group's top, so a
        // group taller than any arm reaches cannot share a station: skip
        // the search (for a message's next line, 4 letter heights on, the
        // search over every lateral offset was most of the planning time).
        let pose = if margin_m >= 0.0 && memo.height_with(&group, &items[i]) > MAX_REACH_M {
            None
        } else {
            Some(best_pose(
                items,
                &trial,
                lane_half_width_m,
                margin_m,
                &reach_margin,
                &mut memo,
            ))
        };
        if let Some(pose) = pose.filter(|p| p.1 >= margin_m) {
            group = trial;
            best = Some(pose);
            continue;
        }
        // The item does not fit the current station: close it, start anew.
        if let Some((s, m)) = best.take() {
            close(&mut out, &group, s, m);
        }
        let alone = best_pose(
            items,
            &[i],
            lane_half_width_m,
            margin_m,
            &reach_margin,
            &mut memo,
        );
        if alone.1 < margin_m {
            let (x, y) = worst_point(&items[i], &alone.0, &reach_margin);
            return Err(StationError::Unreachable {
                item: i,
                x,
                y,
                short_m: margin_m - alone.1,
                margin_m,
            });
        }
        group = vec![i];
        best = Some(alone);
    }
    if let Some((s, m)) = best {
        close(&mut out, &group, s, m);
    }
    Ok(out)
}

fn close(out: &mut StationPlan, group: &[usize], s: Station, m: f64) {
    let k = out.stations.len();
    for &g in group {
        out.station_of[g] = k;
    }
    out.stations.push(s);
    out.margin_m.push(m);
}

/// The worst margins of a growing group at the poses its searches tried.
///
/// `plan` grows a station's group one item at a time and searches the
/// poses again after each; the worst margin of a group at a pose is the
/// minimum over its items, so a pose already tried needs only the items
/// added since (each search then costs one item's points, not the whole
/// group's: station planning stays linear in the number of items instead
/// of quadratic per station). Poses are keyed by their exact coordinates,
/// and `f64::min` is exact and order-free, so every figure is bit for bit
/// what a search from scratch gives.
#[derive(Default)]
struct Memo {
    /// The group the entries belong to (a prefix of every later group).
    group: Vec<usize>,
    /// Lowest and highest y over the group's points.
    y_low: f64,
    y_top: f64,
    /// Pose (x, y bits) → (worst margin over `group[..n]`, n).
    at: HashMap<(u64, u64), (f64, usize)>,
}

impl Memo {
    /// Make the memo describe `group`: kept when `group` extends the
    /// memo's group, started afresh otherwise.
    fn sync(&mut self, items: &[Vec<[f64; 2]>], group: &[usize]) {
        if !group.starts_with(&self.group) || self.group.is_empty() {
            self.group.clear();
            self.at.clear();
            self.y_low = f64::INFINITY;
            self.y_top = f64::NEG_INFINITY;
        }
        for &g in &group[self.group.len()..] {
            for p in &items[g] {
                self.y_low = self.y_low.min(p[1]);
                self.y_top = self.y_top.max(p[1]);
            }
        }
        self.group.clear();
        self.group.extend_from_slice(group);
    }

    /// Extent along the lane (m) of `group` plus the points `pts`; 0 when
    /// `group` is empty or not the synced group (nothing is known then).
    fn height_with(&self, group: &[usize], pts: &[[f64; 2]]) -> f64 {
        if group.is_empty() || group != self.group {
            return 0.0;
        }
        let lo = pts.iter().map(|p| p[1]).fold(self.y_low, f64::min);
        let hi = pts.iter().map(|p| p[1]).fold(self.y_top, f64::max);
        hi - lo
    }

    /// Worst margin over the synced group from station `s`, or, once it is
    /// known to be at most `beat` (the search only wants poses that beat
    /// that), some value between the worst margin and `beat`. Items are
    /// taken in group order, so an entry always holds an exact minimum
    /// over a prefix of the group.
    fn worst(
        &mut self,
        items: &[Vec<[f64; 2]>],
        s: &Station,
        reach_margin: &impl Fn(f64, f64) -> f64,
        beat: f64,
    ) -> f64 {
        let key = (s.x_m.to_bits(), s.y_m.to_bits());
        let (mut worst, mut done) = self.at.get(&key).copied().unwrap_or((f64::INFINITY, 0));
        while done < self.group.len() && worst > beat {
            worst = worst.min(worst_margin(
                items,
                &self.group[done..=done],
                s,
                reach_margin,
            ));
            done += 1;
        }
        self.at.insert(key, (worst, done));
        worst
    }
}

fn worst_margin(
    items: &[Vec<[f64; 2]>],
    group: &[usize],
    s: &Station,
    reach_margin: &impl Fn(f64, f64) -> f64,
) -> f64 {
    let mut worst = f64::INFINITY;
    for &g in group {
        for p in &items[g] {
            let b = s.road_to_base(*p);
            worst = worst.min(reach_margin(b[0], b[1]));
        }
    }
    worst
}

pub(crate) fn worst_point(
    pts: &[[f64; 2]],
    s: &Station,
    reach_margin: &impl Fn(f64, f64) -> f64,
) -> (f64, f64) {
    let mut worst = (f64::INFINITY, 0.0, 0.0);
    for p in pts {
        let b = s.road_to_base(*p);
        let m = reach_margin(b[0], b[1]);
        if m < worst.0 {
            worst = (m, p[0], p[1]);
        }
    }
    (worst.1, worst.2)
}

/// The station (heading −π/2) whose worst margin over `group` is largest.
/// The lane centre is tried first and kept when it gives `want_m`; a
/// lateral offset must beat it by 1 mm. Deterministic.
fn best_pose(
    items: &[Vec<[f64; 2]>],
    group: &[usize],
    lane_half_width_m: f64,
    want_m: f64,
    reach_margin: &impl Fn(f64, f64) -> f64,
    memo: &mut Memo,
) -> (Station, f64) {
    memo.sync(items, group);
    let (y_top, y_low) = (memo.y_top, memo.y_low);
    // No arm reaches further than this behind its axis (generous bound).
    let span = (y_low + MAX_REACH_M - y_top).max(0.0);
    let n_x = (lane_half_width_m / X_STEP_M).floor().max(0.0) as i64;
    let mut xs = vec![0.0];
    for k in 1..=n_x {
        xs.push(k as f64 * X_STEP_M);
        xs.push(-(k as f64) * X_STEP_M);
    }
    // `at(x, y, beat)`: the station there and its worst margin (exact when
    // above `beat`).
    let mut at = |x: f64, y: f64, beat: f64| {
        let s = Station {
            x_m: x,
            y_m: y,
            heading_rad: HEADING_RAD,
        };
        let m = memo.worst(items, &s, reach_margin, beat);
        (s, m)
    };
    let mut best = at(0.0, y_top, f64::NEG_INFINITY);
    for &x in &xs {
        // Coarse scan along the lane, then a fine one around the best.
        let mut local = at(x, y_top, f64::NEG_INFINITY);
        let n = (span / Y_COARSE_M).ceil() as usize;
        for k in 1..=n {
            let c = at(x, y_top + k as f64 * Y_COARSE_M, local.1);
            if c.1 > local.1 {
                local = c;
            }
        }
        let y0 = local.0.y_m;
        let n_fine = (Y_COARSE_M / Y_STEP_M).round() as i64;
        for k in -n_fine..=n_fine {
            let y = y0 + k as f64 * Y_STEP_M;
            if y < y_top {
                continue;
            }
            let c = at(x, y, local.1);
            if c.1 > local.1 {
                local = c;
            }
        }
        let bias = if x == 0.0 { 0.0 } else { 1e-3 };
        if local.1 > best.1 + bias {
            best = local;
        }
        if x == 0.0 && best.1 >= want_m {
            break; // the lane centre works: keep the truck there
        }
    }
    best
}

/// Points of one pass offered to the station planner (its knots, thinned).
const STATION_POINTS_PER_PASS: usize = 32;

/// Stations for the marking's passes: every pass reachable from one truck
/// position, the truck's axis inside the lane.
pub fn for_passes(
    passes: &Passes,
    lane_width_m: f64,
    margin_m: f64,
    robot: &AnyRobot,
) -> Result<StationPlan, StationError> {
    let region = robot.reach();
    let reach_pts: Vec<Vec<[f64; 2]>> = passes.passes.iter().map(|p| thin_tips(&p.knots)).collect();
    plan(&reach_pts, lane_width_m / 2.0, margin_m, |x, y| {
        region.margin(x, y)
    })
}

/// Up to `STATION_POINTS_PER_PASS` knot tips, both ends included.
pub(crate) fn thin_tips(knots: &[Knot]) -> Vec<[f64; 2]> {
    let n = knots.len();
    if n == 0 {
        return vec![];
    }
    let step = n.div_ceil(STATION_POINTS_PER_PASS).max(1);
    let mut v: Vec<[f64; 2]> = knots
        .iter()
        .step_by(step)
        .map(|k| [k.tip.x, k.tip.y])
        .collect();
    let last = knots[n - 1].tip;
    if (n - 1) % step != 0 {
        v.push([last.x, last.y]);
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    fn box_pts(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<[f64; 2]> {
        let mut v = vec![];
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            v.push([x0 + t * (x1 - x0), y0]);
            v.push([x0 + t * (x1 - x0), y1]);
            v.push([x0, y0 + t * (y1 - y0)]);
            v.push([x1, y0 + t * (y1 - y0)]);
        }
        v
    }

    #[test]
    fn frames_round_trip_and_behind_the_truck() {
        let s = Station {
            x_m: 0.3,
            y_m: 5.0,
            heading_rad: HEADING_RAD,
        };
        // θ1 = π/2 (straight back) at R = 2 lands 2 m behind the truck.
        let p = s.base_to_road([0.0, 2.0]);
        assert!((p[0] - 0.3).abs() < 1e-12 && (p[1] - 3.0).abs() < 1e-12);
        let b = s.road_to_base([1.0, 1.0]);
        let back = s.base_to_road(b);
        assert!((back[0] - 1.0).abs() < 1e-12 && (back[1] - 1.0).abs() < 1e-12);
    }

    #[test]
    fn sector_margin_signs() {
        let r = SectorReach::default();
        assert!(r.margin(0.0, 3.0) > 1.0);
        assert!(r.margin(0.0, 1.0) < 0.0, "inside r_min");
        assert!(r.margin(0.0, 6.0) < 0.0, "beyond r_max");
        assert!(r.margin(3.0, 1.0) < 0.0, "outside the θ1 window");
        assert!(r.margin(0.0, -3.0) < 0.0, "in front of the truck");
    }

    #[test]
    fn one_word_one_station_two_lines_two_stations() {
        let r = SectorReach::default();
        let m = |x: f64, y: f64| r.margin(x, y);
        // STOP: four letters 0.39 m wide in a 2.15 m line, 2.44 m tall.
        let mut items: Vec<Vec<[f64; 2]>> = (0..4)
            .map(|i| {
                box_pts(
                    -1.07 + 0.585 * i as f64,
                    0.0,
                    -0.68 + 0.585 * i as f64,
                    2.44,
                )
            })
            .collect();
        let p = plan(&items, 1.83, DEFAULT_MARGIN_M, m).unwrap();
        assert_eq!(p.stations.len(), 1);
        assert!(p.margin_m[0] >= DEFAULT_MARGIN_M);
        assert!(p.stations[0].y_m > 2.44, "truck ahead of the letters");
        // A second line 9.76 m further on needs its own station.
        items.push(box_pts(-1.0, 12.2, 1.0, 14.64));
        let p = plan(&items, 1.83, DEFAULT_MARGIN_M, m).unwrap();
        assert_eq!(p.stations.len(), 2);
        assert_eq!(p.station_of, vec![0, 0, 0, 0, 1]);
        assert!(p.stations[1].y_m > p.stations[0].y_m);
    }

    /// The pose search as it was before `Memo`: every pose priced from
    /// scratch over the whole group.
    fn best_pose_reference(
        items: &[Vec<[f64; 2]>],
        group: &[usize],
        lane_half_width_m: f64,
        want_m: f64,
        reach_margin: &impl Fn(f64, f64) -> f64,
    ) -> (Station, f64) {
        let pts = || group.iter().flat_map(|&g| items[g].iter());
        let y_top = pts().map(|p| p[1]).fold(f64::NEG_INFINITY, f64::max);
        let y_low = pts().map(|p| p[1]).fold(f64::INFINITY, f64::min);
        let span = (y_low + MAX_REACH_M - y_top).max(0.0);
        let n_x = (lane_half_width_m / X_STEP_M).floor().max(0.0) as i64;
        let mut xs = vec![0.0];
        for k in 1..=n_x {
            xs.push(k as f64 * X_STEP_M);
            xs.push(-(k as f64) * X_STEP_M);
        }
        let at = |x: f64, y: f64| {
            let s = Station {
                x_m: x,
                y_m: y,
                heading_rad: HEADING_RAD,
            };
            let m = worst_margin(items, group, &s, reach_margin);
            (s, m)
        };
        let mut best = at(0.0, y_top);
        for &x in &xs {
            let mut local = at(x, y_top);
            for k in 1..=(span / Y_COARSE_M).ceil() as usize {
                let c = at(x, y_top + k as f64 * Y_COARSE_M);
                if c.1 > local.1 {
                    local = c;
                }
            }
            let y0 = local.0.y_m;
            let n_fine = (Y_COARSE_M / Y_STEP_M).round() as i64;
            for k in -n_fine..=n_fine {
                let y = y0 + k as f64 * Y_STEP_M;
                if y >= y_top {
                    let c = at(x, y);
                    if c.1 > local.1 {
                        local = c;
                    }
                }
            }
            let bias = if x == 0.0 { 0.0 } else { 1e-3 };
            if local.1 > best.1 + bias {
                best = local;
            }
            if x == 0.0 && best.1 >= want_m {
                break;
            }
        }
        best
    }

    /// Thin letter-like strokes: a stem, a bar, a diagonal.
    fn stroke(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<[f64; 2]> {
        (0..=8)
            .map(|i| {
                let t = i as f64 / 8.0;
                [x0 + t * (x1 - x0), y0 + t * (y1 - y0)]
            })
            .collect()
    }

    #[test]
    fn memo_search_matches_a_search_from_scratch() {
        let region = basr_robot::Robot::basr().region();
        let sector = SectorReach::default();
        let reaches: [&dyn Fn(f64, f64) -> f64; 2] =
            [&|x, y| region.margin(x, y), &|x, y| sector.margin(x, y)];
        // Two lines of strokes; the growing group of the first line, the
        // second line's first stroke (a trial that fails), then a group
        // started afresh from that stroke.
        let mut items = vec![];
        for (line, y0) in [0.0, 12.2].into_iter().enumerate() {
            for i in 0..4 {
                let x = -1.0 + 0.6 * i as f64 + 0.1 * line as f64;
                items.push(stroke(x, y0, x, y0 + 2.44));
                items.push(stroke(x, y0 + 1.2, x + 0.4, y0 + 1.4 + 0.1 * i as f64));
            }
        }
        let first: Vec<usize> = (0..8).collect();
        for reach in reaches {
            // want 0.05: the lane centre serves; 10 m: every lateral offset
            // is searched (and pruned) too.
            for want in [DEFAULT_MARGIN_M, 10.0] {
                let mut memo = Memo::default();
                let mut groups: Vec<Vec<usize>> = (1..=8).map(|n| first[..n].to_vec()).collect();
                groups.push([&first[..], &[8]].concat());
                groups.extend((9..=12).map(|n| (8..n).collect()));
                for g in &groups {
                    let (s, m) = best_pose(&items, g, 0.6, want, &reach, &mut memo);
                    let (rs, rm) = best_pose_reference(&items, g, 0.6, want, &reach);
                    assert_eq!(
                        (s.x_m.to_bits(), s.y_m.to_bits(), m.to_bits()),
                        (rs.x_m.to_bits(), rs.y_m.to_bits(), rm.to_bits()),
                        "group {g:?}, want {want}: ({}, {}) {m} vs ({}, {}) {rm}",
                        s.x_m,
                        s.y_m,
                        rs.x_m,
                        rs.y_m
                    );
                }
            }
        }
    }

    #[test]
    fn too_tall_is_unreachable() {
        let r = SectorReach::default();
        let items = vec![box_pts(-0.2, 0.0, 0.2, 6.0)];
        let e = plan(&items, 1.83, DEFAULT_MARGIN_M, |x, y| r.margin(x, y)).unwrap_err();
        assert!(
            matches!(e, StationError::Unreachable { item: 0, .. }),
            "{e}"
        );
    }
}
