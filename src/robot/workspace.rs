//! Reachable region of the nozzle tip on the road, in the base frame.
//!
//! The yaw axis point W(θ1, R) = (R − i·a2)·e^{iθ1} sweeps, over the base
//! window [θa, θb] and the extension range [R0, R1], a region bounded by two
//! circular arcs (R = R0, R = R1: |W| = √(R² + a2²)) and two straight
//! segments (θ1 = θa, θb: lines parallel to e^{iθ1}, offset by a2): the
//! "envelope segments and toroidal covers" of 2R+P workspaces (seed 002 §3)
//! cut by the road plane. The map is one-to-one with Jacobian R, so the area
//! is (θb − θa)·(R1² − R0²)/2. A tilt β moves the tip by the four-bar's
//! offset along the fan, which shifts the whole region; the yaw range spans
//! at least π (validated), so every fan direction is reachable everywhere.

use std::f64::consts::TAU;

use serde::Serialize;

use super::{kinematics::wrap_pi, Robot, Unreachable};

/// The reachable region for one fan direction and tilt (or zero tilt).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Region {
    /// Fan direction ψ_B the region is for (`None`: any, at zero tilt).
    pub yaw_rad: Option<f64>,
    pub tilt_rad: f64,
    /// Base window [θa, θb].
    pub base_rot_rad: [f64; 2],
    /// Extension range [R0, R1].
    pub extension_m: [f64; 2],
    pub a2_m: f64,
    /// Translation of the region by the tilt's tip offset.
    pub shift_m: [f64; 2],
    /// Tip heights reachable with this tilt.
    pub z_range_m: [f64; 2],
}

fn seg_dist(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let len2 = d[0] * d[0] + d[1] * d[1];
    let t = if len2 > 0.0 {
        (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p[0] - a[0] - t * d[0]).hypot(p[1] - a[1] - t * d[1])
}

/// Distance from `p` to the arc of radius `rho` about the origin from
/// angle `a0` counter-clockwise by `sweep` (< 2π).
fn arc_dist(p: [f64; 2], rho: f64, a0: f64, sweep: f64) -> f64 {
    let ang = p[1].atan2(p[0]);
    if (ang - a0).rem_euclid(TAU) <= sweep {
        (p[0].hypot(p[1]) - rho).abs()
    } else {
        let e0 = [rho * a0.cos(), rho * a0.sin()];
        let e1 = [rho * (a0 + sweep).cos(), rho * (a0 + sweep).sin()];
        (p[0] - e0[0])
            .hypot(p[1] - e0[1])
            .min((p[0] - e1[0]).hypot(p[1] - e1[1]))
    }
}

impl Region {
    /// Yaw axis point for (θ1, R).
    fn w(&self, theta: f64, r: f64) -> [f64; 2] {
        let (s, c) = theta.sin_cos();
        [r * c + self.a2_m * s, r * s - self.a2_m * c]
    }

    /// Whether the tip point (x, y) is inside (boundary included).
    pub fn contains(&self, x: f64, y: f64) -> bool {
        let p = [x - self.shift_m[0], y - self.shift_m[1]];
        let rr = p[0] * p[0] + p[1] * p[1] - self.a2_m * self.a2_m;
        if rr.is_nan() || rr < 0.0 {
            return false;
        }
        let r = rr.sqrt();
        let [ta, tb] = self.base_rot_rad;
        let mid = 0.5 * (ta + tb);
        let mut t = wrap_pi(p[1].atan2(p[0]) + self.a2_m.atan2(r));
        t += TAU * ((mid - t) / TAU).round();
        r >= self.extension_m[0] && r <= self.extension_m[1] && t >= ta && t <= tb
    }

    /// Signed distance (m) from (x, y) to the region's boundary: > 0 inside,
    /// < 0 outside. Exact: the minimum over the two arcs and two segments.
    pub fn margin(&self, x: f64, y: f64) -> f64 {
        if !(x.is_finite() && y.is_finite()) {
            return f64::NEG_INFINITY;
        }
        let p = [x - self.shift_m[0], y - self.shift_m[1]];
        let [ta, tb] = self.base_rot_rad;
        let [r0, r1] = self.extension_m;
        let a2 = self.a2_m;
        let mut d = seg_dist(p, self.w(ta, r0), self.w(ta, r1));
        d = d.min(seg_dist(p, self.w(tb, r0), self.w(tb, r1)));
        for r in [r0, r1] {
            let rho = r.hypot(a2);
            d = d.min(arc_dist(p, rho, ta - a2.atan2(r), tb - ta));
        }
        if self.contains(x, y) {
            d
        } else {
            -d
        }
    }

    /// Area of the region (m²).
    pub fn area_m2(&self) -> f64 {
        let [ta, tb] = self.base_rot_rad;
        let [r0, r1] = self.extension_m;
        (tb - ta) * (r1 * r1 - r0 * r0) / 2.0
    }

    /// Closed boundary polygon (counter-clockwise, first point not repeated),
    /// arcs sampled every `step_rad` at most.
    pub fn boundary(&self, step_rad: f64) -> Vec<[f64; 2]> {
        let [ta, tb] = self.base_rot_rad;
        let [r0, r1] = self.extension_m;
        let n = (((tb - ta) / step_rad.max(1e-4)).ceil() as usize).clamp(1, 100_000);
        let mut pts = Vec::with_capacity(2 * n + 2);
        for i in 0..=n {
            pts.push(self.w(ta + (tb - ta) * i as f64 / n as f64, r1));
        }
        for i in 0..=n {
            pts.push(self.w(tb - (tb - ta) * i as f64 / n as f64, r0));
        }
        for p in &mut pts {
            p[0] += self.shift_m[0];
            p[1] += self.shift_m[1];
        }
        pts
    }
}

impl Robot {
    /// Reachable region of the tip at zero tilt (any fan direction).
    pub fn region(&self) -> Region {
        let l = &self.limits;
        let top = self.end_effector.tip_height_top_m;
        Region {
            yaw_rad: None,
            tilt_rad: 0.0,
            base_rot_rad: [l.base_rot_rad.min, l.base_rot_rad.max],
            extension_m: [l.extension_m.min, l.extension_m.max],
            a2_m: self.arm.a2_m,
            shift_m: [0.0, 0.0],
            z_range_m: [top - l.vertical_m.max, top - l.vertical_m.min],
        }
    }

    /// Region where the tip can be with fan direction `yaw_rad` (base frame)
    /// and tilt `tilt_rad`; Err when the tilt itself is out of range.
    pub fn region_for(&self, yaw_rad: f64, tilt_rad: f64) -> Result<Region, Unreachable> {
        let l = &self.limits.tilt_rad;
        let off = self.end_effector.fourbar.tip_offset(tilt_rad);
        let off = match off {
            Some(o) if l.contains(tilt_rad) && yaw_rad.is_finite() => o,
            _ => {
                return Err(Unreachable {
                    joint: "tilt_rad".into(),
                    value: tilt_rad,
                    min: l.min,
                    max: l.max,
                    excess: l.excess(tilt_rad),
                })
            }
        };
        let mut r = self.region();
        r.yaw_rad = Some(yaw_rad);
        r.tilt_rad = tilt_rad;
        r.shift_m = [off[0] * yaw_rad.cos(), off[0] * yaw_rad.sin()];
        r.z_range_m = [r.z_range_m[0] + off[1], r.z_range_m[1] + off[1]];
        Ok(r)
    }

    /// Signed distance (m) from the base-frame road point (x, y) to the
    /// boundary of the tip's reachable region at zero tilt: > 0 inside.
    pub fn reach_margin(&self, x_b: f64, y_b: f64) -> f64 {
        self.region().margin(x_b, y_b)
    }
}

/// Shoelace area of a closed polygon.
pub fn polygon_area(pts: &[[f64; 2]]) -> f64 {
    let n = pts.len();
    let mut s = 0.0;
    for i in 0..n {
        let (a, b) = (pts[i], pts[(i + 1) % n]);
        s += a[0] * b[1] - b[0] * a[1];
    }
    0.5 * s
}

#[cfg(test)]
#[allow(clippy::approx_constant)] // 0.7854 is the seed's base window, not π/4
mod tests {
    use super::*;
    use crate::robot::NozzlePose;

    #[test]
    fn area_of_default_workspace() {
        let r = Robot::basr();
        let reg = r.region();
        // (2.3562 − 0.7854)·(5.3583² − 1.55²)/2.
        let want = (2.3562 - 0.7854) * (5.358333333333333f64.powi(2) - 1.55f64.powi(2)) / 2.0;
        assert!((reg.area_m2() - want).abs() < 1e-12);
        assert!((reg.area_m2() - 20.663).abs() < 1e-3, "{}", reg.area_m2());
        let poly = reg.boundary(0.0005);
        assert!((polygon_area(&poly) - want).abs() < 1e-4);
    }

    #[test]
    fn margin_matches_ik_and_distance() {
        let r = Robot::basr();
        // Straight back at 3 m: 1.45 m to the inner arc, 2.36 m to the outer.
        let m = r.reach_margin(0.0, 3.0);
        assert!(m > 1.4 && m < 1.5, "{m}");
        // Just outside the outer arc along the axis.
        let rho = 5.358333333333333f64.hypot(0.01);
        assert!((r.reach_margin(0.0, rho + 0.1) + 0.1).abs() < 1e-3);
        // Inside ⇔ IK finds joints (at a reachable height, zero tilt).
        for i in 0..40 {
            for k in 0..40 {
                let x = -6.0 + 12.0 * i as f64 / 39.0;
                let y = -1.0 + 7.0 * k as f64 / 39.0;
                let m = r.reach_margin(x, y);
                if m.abs() < 1e-6 {
                    continue;
                }
                let pose = NozzlePose {
                    x_m: x,
                    y_m: y,
                    z_m: 0.2,
                    yaw_rad: 0.3,
                    tilt_rad: 0.0,
                };
                assert_eq!(m > 0.0, r.ik(&pose).is_ok(), "({x}, {y}) margin {m}");
            }
        }
    }

    #[test]
    fn tilted_region_is_shifted_and_matches_ik() {
        let r = Robot::basr();
        let (yaw, tilt) = (0.7, 0.2);
        let reg = r.region_for(yaw, tilt).unwrap();
        let off = r.end_effector.fourbar.tip_offset(tilt).unwrap();
        assert!((reg.shift_m[0] - off[0] * yaw.cos()).abs() < 1e-15);
        let z = 0.5 * (reg.z_range_m[0] + reg.z_range_m[1]);
        for i in 0..30 {
            let x = -5.5 + 11.0 * i as f64 / 29.0;
            for y in [1.0, 1.6, 3.0, 5.3, 5.4] {
                let m = reg.margin(x, y);
                if m.abs() < 1e-6 {
                    continue;
                }
                let pose = NozzlePose {
                    x_m: x,
                    y_m: y,
                    z_m: z,
                    yaw_rad: yaw,
                    tilt_rad: tilt,
                };
                assert_eq!(m > 0.0, r.ik(&pose).is_ok(), "({x}, {y})");
            }
        }
        assert!(r.region_for(0.0, 0.5).is_err());
    }
}
