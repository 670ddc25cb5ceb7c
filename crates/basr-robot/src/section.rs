//! The workspace of any kind, found from its kinematics: the cross-section
//! the reference point sweeps in the (r, z) half-plane (θ1 turns it round
//! the base axis), with seed 002's ring and void, and the region the tip
//! reaches on the road at a painting height.
//!
//! Both are rasters: the section from forward kinematics over a fine grid
//! of the two section joints within their limits, the road region from
//! inverse kinematics cell by cell with each row's edges refined by
//! bisection to 1 mm. 002's algebraic boundary (src/robot/envelope.rs)
//! bounds the telescopic section for full joint rotations; limits cut it,
//! which the raster shows.

use serde::Serialize;

use super::kind::ArmKind;
use super::NozzlePose;

/// The cross-section of the reference point's workspace.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Section {
    /// Cell size (m).
    pub cell_m: f64,
    /// Lower-left corner of cell (0, 0) in (r, z).
    pub origin_m: [f64; 2],
    pub cols: usize,
    pub rows: usize,
    /// Row-major occupancy (row = z index).
    #[serde(skip)]
    pub filled: Vec<bool>,
    pub area_m2: f64,
    /// 002: the section keeps off the base axis, so the workspace is a
    /// ring round it (a hole along the axis).
    pub ring: bool,
    /// 002: holes inside the section (voids of the solid of revolution).
    pub voids: usize,
    pub r_range_m: [f64; 2],
    pub z_range_m: [f64; 2],
}

/// Section cells per metre: 2 cm.
const SECTION_CELL_M: f64 = 0.02;

impl Section {
    pub fn of(arm: &dyn ArmKind) -> Section {
        let [i, j] = arm.section_joints();
        let lim = arm.limits();
        let mut q = arm.rest();
        q[0] = 0.0;
        let n = 900;
        let mut pts = Vec::with_capacity((n + 1) * (n + 1));
        for a in 0..=n {
            q[i] = lim[i].min + (lim[i].max - lim[i].min) * a as f64 / n as f64;
            for b in 0..=n {
                q[j] = lim[j].min + (lim[j].max - lim[j].min) * b as f64 / n as f64;
                let p = arm.reference_point(&q);
                pts.push([p[0].hypot(p[1]), p[2]]);
            }
        }
        Section::from_points(&pts, SECTION_CELL_M)
    }

    fn from_points(pts: &[[f64; 2]], cell: f64) -> Section {
        let (mut r1, mut z0, mut z1) = (0.0f64, f64::INFINITY, f64::NEG_INFINITY);
        let mut r0 = f64::INFINITY;
        for p in pts {
            r0 = r0.min(p[0]);
            r1 = r1.max(p[0]);
            z0 = z0.min(p[1]);
            z1 = z1.max(p[1]);
        }
        // One empty cell of border all round, and the axis (r = 0) inside.
        let origin = [-cell, z0 - cell];
        let cols = ((r1 - origin[0]) / cell).ceil() as usize + 2;
        let rows = ((z1 - origin[1]) / cell).ceil() as usize + 2;
        let mut filled = vec![false; cols * rows];
        for p in pts {
            let c = ((p[0] - origin[0]) / cell) as usize;
            let r = ((p[1] - origin[1]) / cell) as usize;
            filled[r * cols + c.min(cols - 1)] = true;
        }
        let count = filled.iter().filter(|&&f| f).count();
        let mut s = Section {
            cell_m: cell,
            origin_m: origin,
            cols,
            rows,
            filled,
            area_m2: count as f64 * cell * cell,
            ring: r0 > 2.0 * cell,
            voids: 0,
            r_range_m: [r0, r1],
            z_range_m: [z0, z1],
        };
        s.voids = s.count_voids();
        s
    }

    /// Empty regions not connected to the border (4-connected flood fill).
    /// Regions of a cell or two are sampling gaps, not voids.
    fn count_voids(&self) -> usize {
        let (w, h) = (self.cols, self.rows);
        let mut seen = self.filled.clone();
        let mut voids = 0;
        let mut stack = Vec::new();
        let mut fill = |start: usize, seen: &mut Vec<bool>| -> (usize, bool) {
            let mut size = 0;
            let mut border = false;
            stack.push(start);
            seen[start] = true;
            while let Some(k) = stack.pop() {
                size += 1;
                let (x, y) = (k % w, k / w);
                if x == 0 || y == 0 || x + 1 == w || y + 1 == h {
                    border = true;
                }
                let mut go = |nk: usize| {
                    if !seen[nk] {
                        seen[nk] = true;
                        stack.push(nk);
                    }
                };
                if x > 0 {
                    go(k - 1);
                }
                if x + 1 < w {
                    go(k + 1);
                }
                if y > 0 {
                    go(k - w);
                }
                if y + 1 < h {
                    go(k + w);
                }
            }
            (size, border)
        };
        for k in 0..w * h {
            if !seen[k] {
                let (size, border) = fill(k, &mut seen);
                if !border && size > 4 {
                    voids += 1;
                }
            }
        }
        voids
    }

    pub fn filled_at(&self, col: usize, row: usize) -> bool {
        self.filled[row * self.cols + col]
    }
}

/// Where the tip reaches on the road at one height, at zero tilt with the
/// fan both along and across x_B (any yaw servo spanning π turns it to any
/// direction between).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RoadRegion {
    pub height_m: f64,
    /// Row spacing (m); each row is the band y ± row_m/2.
    pub row_m: f64,
    /// (y, reachable x intervals), y increasing.
    pub rows: Vec<(f64, Vec<[f64; 2]>)>,
    pub area_m2: f64,
}

/// Road rows every 5 cm, cells every 5 cm before refinement.
const ROAD_STEP_M: f64 = 0.05;

/// Whether the tip reaches (x, y) at height z with zero tilt, for the fan
/// along and across x_B.
pub fn reaches(arm: &dyn ArmKind, x: f64, y: f64, z: f64) -> bool {
    [0.0, std::f64::consts::FRAC_PI_2].iter().all(|&yaw| {
        arm.ik(&NozzlePose {
            x_m: x,
            y_m: y,
            z_m: z,
            yaw_rad: yaw,
            tilt_rad: 0.0,
        })
        .is_ok()
    })
}

impl RoadRegion {
    pub fn of(arm: &dyn ArmKind, height_m: f64, reach_m: f64) -> RoadRegion {
        let step = ROAD_STEP_M;
        let n = (reach_m / step).ceil() as i64 + 1;
        let mut rows = Vec::new();
        let mut area = 0.0;
        for iy in -n..=n {
            let y = iy as f64 * step;
            let inside = |x: f64| reaches(arm, x, y, height_m);
            let mut spans = Vec::new();
            let mut start: Option<f64> = None;
            let mut prev_x = -(n as f64 + 1.0) * step;
            for ix in -n..=n + 1 {
                let x = ix as f64 * step;
                let now = ix <= n && inside(x);
                match (start, now) {
                    (None, true) => start = Some(refine(&inside, prev_x, x)),
                    (Some(s), false) => {
                        spans.push([s, refine(&|x| !inside(x), prev_x, x)]);
                        start = None;
                    }
                    _ => {}
                }
                prev_x = x;
            }
            area += spans.iter().map(|s| (s[1] - s[0]) * step).sum::<f64>();
            if !spans.is_empty() {
                rows.push((y, spans));
            }
        }
        RoadRegion {
            height_m,
            row_m: step,
            rows,
            area_m2: area,
        }
    }
}

/// The first x in (a, b] where `f` holds, to 1 mm (f(a) false, f(b) true).
fn refine(f: &dyn Fn(f64) -> bool, mut a: f64, mut b: f64) -> f64 {
    while b - a > 1e-3 {
        let m = 0.5 * (a + b);
        if f(m) {
            b = m;
        } else {
            a = m;
        }
    }
    0.5 * (a + b)
}

/// Distance (m) from a reachable tip position to the edge of the road
/// region at its height: the least, over 16 directions, of how far the tip
/// can move before zero tilt stops being reachable (to 1 mm, at most 2 m).
pub fn reach_margin(arm: &dyn ArmKind, x: f64, y: f64, z: f64) -> f64 {
    let mut best: f64 = 2.0;
    for k in 0..16 {
        let a = k as f64 * std::f64::consts::TAU / 16.0;
        let (s, c) = a.sin_cos();
        let out = |t: f64| !reaches(arm, x + t * c, y + t * s, z);
        if out(best) {
            best = refine(&out, 0.0, best);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kind::{ARTICULATED_TOML, TELESCOPIC_TOML};
    use crate::AnyRobot;

    /// The shipped kinds are sized for a 12 ft lane and an 8 ft letter: the
    /// tip reaches the whole lane width over the depth their descriptions
    /// claim, at both ends of the painting heights.
    #[test]
    fn shipped_kinds_cover_a_lane_across_and_a_letter_along() {
        for (text, y_range) in [
            (TELESCOPIC_TOML, [1.5, 4.3]),
            (ARTICULATED_TOML, [1.8, 4.3]),
        ] {
            let r = AnyRobot::from_toml_str(text, "shipped").unwrap();
            let arm = r.arm();
            // More than an 8 ft letter along the lane.
            assert!(y_range[1] - y_range[0] > 2.44);
            for z in arm.tip_heights_m() {
                for i in 0..=12 {
                    let x = -1.83 + 3.66 * i as f64 / 12.0;
                    for k in 0..=10 {
                        let y = y_range[0] + (y_range[1] - y_range[0]) * k as f64 / 10.0;
                        assert!(reaches(arm, x, y, z), "{}: ({x}, {y}, {z})", arm.name());
                    }
                }
            }
        }
    }

    #[test]
    fn voids_and_rings_are_found_on_a_drawn_section() {
        // An annulus off the axis: a ring with one void.
        let mut pts = Vec::new();
        for i in 0..2000 {
            let a = i as f64 * std::f64::consts::TAU / 2000.0;
            for k in 0..20 {
                let rho = 0.5 + 0.01 * k as f64;
                pts.push([2.0 + rho * a.cos(), rho * a.sin()]);
            }
        }
        let s = Section::from_points(&pts, 0.02);
        assert!(s.ring);
        assert_eq!(s.voids, 1);
        // A disc touching the axis: neither.
        let disc: Vec<[f64; 2]> = (0..200)
            .flat_map(|i| (0..200).map(move |j| [i as f64 * 0.01, j as f64 * 0.01]))
            .collect();
        let s = Section::from_points(&disc, 0.02);
        assert!(!s.ring);
        assert_eq!(s.voids, 0);
    }
}
