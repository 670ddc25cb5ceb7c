//! The controller's trajectory generator and frames: the road ↔ base frame
//! of a station, the B-spline through the job's rows, joint references held
//! within their ranges, and the tilt four-bar's inverse by table.

/// Station pose helpers: base frame ↔ road frame (SPEC §2).
#[derive(Clone, Copy, Debug)]
pub(super) struct Pose {
    x: f64,
    y: f64,
    c: f64,
    s: f64,
}

impl Pose {
    pub(super) fn new(st: &basr_job::Station) -> Pose {
        let (s, c) = (st.heading_rad - std::f64::consts::FRAC_PI_2).sin_cos();
        Pose {
            x: st.x_m,
            y: st.y_m,
            c,
            s,
        }
    }
    pub(super) fn to_road(self, b: [f64; 2]) -> [f64; 2] {
        [
            self.x + self.c * b[0] - self.s * b[1],
            self.y + self.s * b[0] + self.c * b[1],
        ]
    }
    pub(super) fn to_base(self, r: [f64; 2]) -> [f64; 2] {
        let (dx, dy) = (r[0] - self.x, r[1] - self.y);
        [self.c * dx + self.s * dy, -self.s * dx + self.c * dy]
    }
}

/// Uniform cubic B-spline through a uniformly sampled column: value, first
/// and second time derivatives at `t` (the controller's trajectory
/// generator between the job's setpoints). C² — its acceleration is
/// continuous, where a Catmull-Rom curve's jumps at every row (31 Hz on a
/// 32 ms job) shook the end-effector linkage's 9 Hz mode: STOP's worst sjct
/// error 4.75 → 3.8 mm, 40-plant p95 9.2 → 8.5 mm. It passes within
/// h²·a/6 of the rows (0.1 mm at 0.6 m/s² and 32 ms) and, each point a
/// convex blend of four rows, never beyond the rows' range (a row on a
/// joint limit is not overshot).
pub(super) fn curve(v: &[f64], dt: f64, t: f64) -> [f64; 3] {
    let n = v.len();
    if n == 1 {
        return [v[0], 0.0, 0.0];
    }
    let sidx = (t / dt).max(0.0);
    // truncation is the floor of a number ≥ 0 (without libm's call)
    let i = (sidx as usize).min(n - 2);
    let u = (sidx - i as f64).clamp(0.0, 1.0);
    let p0 = v[i.saturating_sub(1)];
    let p1 = v[i];
    let p2 = v[i + 1];
    let p3 = v[(i + 2).min(n - 1)];
    let w = 1.0 - u;
    [
        (w * w * w * p0
            + (3.0 * u * u * u - 6.0 * u * u + 4.0) * p1
            + (-3.0 * u * u * u + 3.0 * u * u + 3.0 * u + 1.0) * p2
            + u * u * u * p3)
            / 6.0,
        (-w * w * p0
            + (3.0 * u * u - 4.0 * u) * p1
            + (-3.0 * u * u + 2.0 * u + 1.0) * p2
            + u * u * p3)
            / (2.0 * dt),
        (w * p0 + (3.0 * u - 2.0) * p1 + (1.0 - 3.0 * u) * p2 + u * p3) / (dt * dt),
    ]
}

/// A joint reference held within the joint's range `lo..=hi`, at rest on
/// the limit. The B-spline does not pass its rows' range (the Catmull-Rom
/// curve before it overshot a row on a limit by up to 7.4 % of the next
/// step); this keeps a row just past a limit by rounding, or a job edited
/// past it, from driving the arm into its end stop.
pub(super) fn within(r: [f64; 3], lo: f64, hi: f64) -> [f64; 3] {
    if r[0] < lo {
        [lo, 0.0, 0.0]
    } else if r[0] > hi {
        [hi, 0.0, 0.0]
    } else {
        r
    }
}

/// Tilt from ball-nut travel by a table of the four-bar's exact nut(β):
/// the robot's own inverse is a root search, too slow for every 5 ms tick.
pub(super) struct NutTable {
    nut: Vec<f64>,
    beta: Vec<f64>,
}

impl NutTable {
    pub(super) fn new(robot: &basr_robot::Robot) -> NutTable {
        let l = &robot.limits.tilt_rad;
        let span = l.min.abs().max(l.max.abs()) * 1.2;
        let n = 2000;
        let mut pts: Vec<(f64, f64)> = (0..=n)
            .filter_map(|i| {
                let b = -span + 2.0 * span * i as f64 / n as f64;
                robot.end_effector.fourbar.nut_m(b).map(|x| (x, b))
            })
            .collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        NutTable {
            nut: pts.iter().map(|p| p.0).collect(),
            beta: pts.iter().map(|p| p.1).collect(),
        }
    }

    /// β for nut travel `x` (clamped to the table; 0 without a table).
    pub(super) fn tilt(&self, x: f64) -> f64 {
        let n = self.nut.len();
        if n < 2 {
            return 0.0;
        }
        let i = self.nut.partition_point(|&v| v < x).clamp(1, n - 1);
        let (x0, x1) = (self.nut[i - 1], self.nut[i]);
        let t = if x1 > x0 {
            ((x - x0) / (x1 - x0)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        self.beta[i - 1] + t * (self.beta[i] - self.beta[i - 1])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_curve_follows_lines_exactly_and_parabolas_within_h2a_over_6() {
        let h = 0.032;
        let v: Vec<f64> = (0..10).map(|i| 0.5 + 2.0 * i as f64 * h).collect();
        for i in 1..9 {
            let r = curve(&v, h, i as f64 * h);
            assert!((r[0] - v[i]).abs() < 1e-12);
        }
        let r = curve(&v, h, 0.1);
        assert!((r[1] - 2.0).abs() < 1e-9 && r[2].abs() < 1e-6);
        // a parabola of acceleration a: offset h²·a/6 from the rows, the
        // acceleration itself exact and continuous across the rows
        let a = 0.6;
        let p: Vec<f64> = (0..10).map(|i| 0.5 * a * (i as f64 * h).powi(2)).collect();
        for k in 40..200 {
            let t = k as f64 * 0.001;
            let r = curve(&p, h, t);
            assert!(
                (r[0] - 0.5 * a * t * t - h * h * a / 6.0).abs() < 1e-12,
                "{t}"
            );
            assert!((r[2] - a).abs() < 1e-9, "{t}");
        }
    }

    #[test]
    fn rows_held_on_a_limit_are_not_overshot() {
        // held on a limit, then leaving it by 10 mm a row: a Catmull-Rom
        // curve dipped 0.74 mm below the limit before the step; the
        // B-spline, a convex blend of four rows, stays within them
        let v = [1.55, 1.55, 1.55, 1.56, 1.60];
        let lowest = (0..=128)
            .map(|k| curve(&v, 0.032, k as f64 * 0.001)[0])
            .fold(f64::INFINITY, f64::min);
        assert!(lowest >= 1.55 - 1e-12, "{lowest}");
        assert_eq!(within([1.54, 0.1, 0.2], 1.55, 5.0), [1.55, 0.0, 0.0]);
        let free = curve(&v, 0.032, 0.11);
        assert_eq!(within(free, 1.55, 5.0), free);
    }

    #[test]
    fn nut_table_inverts_the_four_bar() {
        let r = basr_robot::Robot::basr();
        let t = NutTable::new(&r);
        for b in [-0.25, -0.1, 0.0, 0.07, 0.26] {
            let x = r.end_effector.fourbar.nut_m(b).unwrap();
            assert!((t.tilt(x) - b).abs() < 1e-6, "{b}");
        }
    }

    #[test]
    fn pose_round_trips() {
        let p = Pose::new(&basr_job::Station {
            x_m: 1.0,
            y_m: 4.0,
            heading_rad: -std::f64::consts::FRAC_PI_2,
        });
        let b = [0.3, 2.0];
        let r = p.to_road(b);
        let back = p.to_base(r);
        assert!((back[0] - b[0]).abs() < 1e-12 && (back[1] - b[1]).abs() < 1e-12);
        // heading −π/2: +y_B points to −y_R
        assert!((r[1] - (4.0 - 2.0)).abs() < 1e-12);
    }
}
