//! Reachable region of the nozzle tip on the road, in the base frame.
//!
//! The yaw axis point W(θ1, R) = (R − i·a2)·e^{iθ1} sweeps, over the base
//! window [θa, θb] and the extension range [R0, R1], a region bounded by two
//! circular arcs (R = R0, R = R1: |W| = √(R² + a2²)) and two straight
//! segments (θ1 = θa, θb: lines parallel to e^{iθ1}, offset by a2): the
//! "envelope segments and toroidal covers" of 2R+P workspaces (seed 002 §3)
//! cut by the road plane. The map is one-to-one with Jacobian R, so the area
//! is (θb − θa)·(R1² − R0²)/2. A tilt β moves the tip by the four-bar's
//! offset along the fan, which shifts the whole region.
//!
//! A fan direction ψ is painted by two branches: (ψ, β) and (ψ+π, −β)
//! (SPEC §2). A branch counts only where its tilt is in range and its yaw
//! joint ψ_branch − θ1 has a turn inside the yaw range; the region is the
//! base-window sectors where some branch does. At zero tilt (or any tilt
//! whose negation is also in range) both branches count, and a yaw span of
//! at least π (validated) makes every θ1 work; an asymmetric tilt range
//! leaves one branch, and a yaw span under 2π then cuts the window.

use std::f64::consts::{PI, TAU};

use serde::Serialize;

use super::{kinematics::wrap_pi, JointLimit, Robot, Unreachable};

/// The reachable region for one fan direction and tilt (or zero tilt).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Region {
    /// Fan direction ψ_B the region is for (`None`: any, at zero tilt).
    pub yaw_rad: Option<f64>,
    pub tilt_rad: f64,
    /// Base window [θa, θb].
    pub base_rot_rad: [f64; 2],
    /// The parts of the base window where the fan can be turned to the
    /// direction asked (one of its branches in range): sorted, disjoint,
    /// never empty. The whole window unless the yaw range cuts it.
    pub sectors_rad: Vec<[f64; 2]>,
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
        r >= self.extension_m[0]
            && r <= self.extension_m[1]
            && self.sectors_rad.iter().any(|s| t >= s[0] && t <= s[1])
    }

    /// Signed distance (m) from (x, y) to the region's boundary: > 0 inside,
    /// < 0 outside. Exact: the minimum over the two arcs and two segments.
    pub fn margin(&self, x: f64, y: f64) -> f64 {
        if !(x.is_finite() && y.is_finite()) {
            return f64::NEG_INFINITY;
        }
        let p = [x - self.shift_m[0], y - self.shift_m[1]];
        let [r0, r1] = self.extension_m;
        let a2 = self.a2_m;
        // The sectors are disjoint, so the region's boundary is the union of
        // theirs: the distance to it is the least distance to any of them.
        let mut d = f64::INFINITY;
        for &[ta, tb] in &self.sectors_rad {
            d = d.min(seg_dist(p, self.w(ta, r0), self.w(ta, r1)));
            d = d.min(seg_dist(p, self.w(tb, r0), self.w(tb, r1)));
            for r in [r0, r1] {
                let rho = r.hypot(a2);
                d = d.min(arc_dist(p, rho, ta - a2.atan2(r), tb - ta));
            }
        }
        if self.contains(x, y) {
            d
        } else {
            -d
        }
    }

    /// Area of the region (m²).
    pub fn area_m2(&self) -> f64 {
        let [r0, r1] = self.extension_m;
        let sweep: f64 = self.sectors_rad.iter().map(|s| s[1] - s[0]).sum();
        sweep * (r1 * r1 - r0 * r0) / 2.0
    }

    /// Closed boundary polygon of the first sector (the whole region unless
    /// the yaw range cuts it; see [`Region::boundaries`]).
    pub fn boundary(&self, step_rad: f64) -> Vec<[f64; 2]> {
        self.boundaries(step_rad).swap_remove(0)
    }

    /// One closed boundary polygon per sector (counter-clockwise, first
    /// point not repeated), arcs sampled every `step_rad` at most.
    pub fn boundaries(&self, step_rad: f64) -> Vec<Vec<[f64; 2]>> {
        let mut out: Vec<_> = self
            .sectors_rad
            .iter()
            .map(|&s| self.sector_boundary(s, step_rad))
            .collect();
        if out.is_empty() {
            out.push(vec![]);
        }
        out
    }

    fn sector_boundary(&self, [ta, tb]: [f64; 2], step_rad: f64) -> Vec<[f64; 2]> {
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
    /// Reachable region of the tip at zero tilt (any fan direction: both
    /// fan branches have tilt 0, and the yaw span of at least π turns one of
    /// them to any direction at every θ1).
    pub fn region(&self) -> Region {
        let l = &self.limits;
        let top = self.end_effector.tip_height_top_m;
        let window = [l.base_rot_rad.min, l.base_rot_rad.max];
        Region {
            yaw_rad: None,
            tilt_rad: 0.0,
            base_rot_rad: window,
            sectors_rad: vec![window],
            extension_m: [l.extension_m.min, l.extension_m.max],
            a2_m: self.arm.a2_m,
            shift_m: [0.0, 0.0],
            z_range_m: [top - l.vertical_m.max, top - l.vertical_m.min],
        }
    }

    /// Region where the tip can be with fan direction `yaw_rad` (base frame)
    /// and tilt `tilt_rad`, by either fan branch; Err names the binding
    /// limit (as [`Robot::ik`] would) when no branch reaches anywhere.
    pub fn region_for(&self, yaw_rad: f64, tilt_rad: f64) -> Result<Region, Unreachable> {
        for (name, v) in [("yaw_rad", yaw_rad), ("tilt_rad", tilt_rad)] {
            if !v.is_finite() {
                return Err(Unreachable::not_finite(name, v));
            }
        }
        let tl = &self.limits.tilt_rad;
        let mut r = self.region();
        let window = r.base_rot_rad;
        let mut sectors = Vec::new();
        let mut placed = false;
        let mut closest: Option<Unreachable> = None;
        let mut note = |u: Unreachable| {
            if closest.as_ref().is_none_or(|c| u.severity() < c.severity()) {
                closest = Some(u);
            }
        };
        for flip in [false, true] {
            let (psi, beta) = if flip {
                (yaw_rad + PI, 0.0 - tilt_rad)
            } else {
                (yaw_rad, tilt_rad)
            };
            let off = match self.end_effector.fourbar.tip_offset(beta) {
                Some(o) if tl.contains(beta) => o,
                _ => {
                    note(Unreachable {
                        flipped: flip,
                        ..Unreachable::of("tilt_rad", tl, beta)
                    });
                    continue;
                }
            };
            let found = yaw_sectors(window, psi, &self.limits.ee_yaw_rad);
            if found.is_empty() {
                note(Unreachable {
                    flipped: flip,
                    ..nearest_yaw(window, psi, &self.limits.ee_yaw_rad)
                });
                continue;
            }
            sectors.extend(found);
            // The linkage is mirror-symmetric (equal rockers, tip on its
            // midline), so −β moves the tip by the mirrored offset: along
            // ψ+π that is the same point as β along ψ. Either branch gives
            // the region's shift.
            if !placed {
                let (s, c) = psi.sin_cos();
                r.shift_m = [off[0] * c, off[0] * s];
                r.z_range_m = [r.z_range_m[0] + off[1], r.z_range_m[1] + off[1]];
                placed = true;
            }
        }
        if sectors.is_empty() {
            // Both branches were noted above.
            return Err(closest.unwrap_or_else(|| Unreachable::of("tilt_rad", tl, tilt_rad)));
        }
        r.yaw_rad = Some(yaw_rad);
        r.tilt_rad = tilt_rad;
        r.sectors_rad = merge(sectors);
        Ok(r)
    }

    /// Signed distance (m) from the base-frame road point (x, y) to the
    /// boundary of the tip's reachable region at zero tilt: > 0 inside.
    pub fn reach_margin(&self, x_b: f64, y_b: f64) -> f64 {
        self.region().margin(x_b, y_b)
    }
}

/// Parts of the base `window` where the yaw joint can turn the fan to
/// `psi`: θ1 with ψ − θ1 + 2πk in the yaw range for some k, i.e. the arcs
/// [ψ − max, ψ − min] + 2πk. The window spans at most a turn (validated),
/// so at most three arcs meet it.
fn yaw_sectors(window: [f64; 2], psi: f64, yaw: &JointLimit) -> Vec<[f64; 2]> {
    let [ta, tb] = window;
    if yaw.max - yaw.min >= TAU {
        return vec![window];
    }
    let psi = wrap_pi(psi);
    let (lo, hi) = (psi - yaw.max, psi - yaw.min);
    let k_lo = ((ta - hi) / TAU).ceil() as i64;
    let k_hi = ((tb - lo) / TAU).floor() as i64;
    let mut out = Vec::new();
    for k in k_lo..=k_hi.min(k_lo + 3) {
        let shift = TAU * k as f64;
        let (a, b) = ((lo + shift).max(ta), (hi + shift).min(tb));
        if a <= b {
            out.push([a, b]);
        }
    }
    out
}

/// The yaw joint value nearest its range that some θ1 of the window needs
/// for fan direction `psi` (when none is in range).
fn nearest_yaw(window: [f64; 2], psi: f64, yaw: &JointLimit) -> Unreachable {
    let [ta, tb] = window;
    // Needed: [ψ − θb, ψ − θa] + 2πk; take the turn nearest the range.
    let (lo, hi) = (wrap_pi(psi) - tb, wrap_pi(psi) - ta);
    let mid = 0.5 * (yaw.min + yaw.max);
    let k0 = ((mid - 0.5 * (lo + hi)) / TAU).round() as i64;
    let mut best: Option<Unreachable> = None;
    for k in k0 - 1..=k0 + 1 {
        let shift = TAU * k as f64;
        let value = if hi + shift < yaw.min {
            hi + shift
        } else {
            lo + shift
        };
        let u = Unreachable::of("ee_yaw_rad", yaw, value);
        if best.as_ref().is_none_or(|b| u.excess < b.excess) {
            best = Some(u);
        }
    }
    best.unwrap_or_else(|| Unreachable::of("ee_yaw_rad", yaw, lo))
}

/// Sorted union of intervals; touching ones (to rounding, 1e-12 rad) join.
fn merge(mut v: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    v.sort_by(|a, b| a[0].total_cmp(&b[0]));
    let mut out: Vec<[f64; 2]> = Vec::with_capacity(v.len());
    for s in v {
        match out.last_mut() {
            Some(last) if s[0] <= last[1] + 1e-12 => last[1] = last[1].max(s[1]),
            _ => out.push(s),
        }
    }
    out
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
    use crate::NozzlePose;

    #[test]
    fn area_of_default_workspace() {
        let r = Robot::basr();
        let reg = r.region();
        // (2.3562 − 0.7854)·(5.3054² − 1.55²)/2 (R short of the end stop
        // by the stroke margin).
        let want = (2.3562 - 0.7854) * (5.305416666666667f64.powi(2) - 1.55f64.powi(2)) / 2.0;
        assert!((reg.area_m2() - want).abs() < 1e-12);
        assert!((reg.area_m2() - 20.220).abs() < 1e-3, "{}", reg.area_m2());
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
        let rho = 5.305416666666667f64.hypot(0.01);
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

    /// BASR with the yaw joint limited to ±`yaw` rad and the tilt range
    /// made asymmetric, −0.1 .. 0.2618 rad: then a fan direction may be
    /// painted by one branch only.
    fn asymmetric(yaw: f64) -> Robot {
        let t = crate::BASR_TOML
            .replacen(
                "min = -6.283185307179586\nmax = 6.283185307179586",
                &format!("min = -{yaw}\nmax = {yaw}"),
                1,
            )
            .replacen("min = -0.2617993877991494\nmax", "min = -0.1\nmax", 1);
        let r = Robot::from_toml_str(&t, "asymmetric").unwrap();
        assert_eq!(r.limits.ee_yaw_rad.max, yaw);
        assert_eq!(r.limits.tilt_rad.min, -0.1);
        r
    }

    /// Inside the region ⇔ IK finds joints, over a grid of road points.
    fn agrees_with_ik(r: &Robot, yaw: f64, tilt: f64) -> usize {
        let reg = r.region_for(yaw, tilt).unwrap();
        let z = 0.5 * (reg.z_range_m[0] + reg.z_range_m[1]);
        let mut inside = 0;
        for i in 0..45 {
            for k in 0..45 {
                let x = -5.6 + 11.2 * i as f64 / 44.0;
                let y = -0.5 + 6.0 * k as f64 / 44.0;
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
                let ik = r.ik(&pose);
                assert_eq!(
                    m > 0.0,
                    ik.is_ok(),
                    "yaw {yaw} tilt {tilt} ({x}, {y}) {ik:?}"
                );
                assert_eq!(m > 0.0, reg.contains(x, y));
                inside += usize::from(m > 0.0);
            }
        }
        inside
    }

    #[test]
    fn one_branch_regions_match_ik() {
        let full = Robot::basr().region().area_m2();
        let r = asymmetric(1.6);
        // 11.5° is out of range flipped (−11.5° < −0.1 rad): one branch.
        // Fan 180°: the yaw joint π − θ1 ≤ 1.6 needs θ1 ≥ π − 1.6.
        let reg = r.region_for(PI, 11.5f64.to_radians()).unwrap();
        assert_eq!(reg.sectors_rad.len(), 1);
        assert!((reg.sectors_rad[0][0] - (PI - 1.6)).abs() < 1e-12);
        assert!(reg.area_m2() < 0.6 * full);
        for (yaw, tilt) in [
            (PI, 11.5f64.to_radians()),
            (0.0, 11.5f64.to_radians()),
            (0.0, -10f64.to_radians()),
            (1.0, 3f64.to_radians()),
            (PI / 2.0, 11.5f64.to_radians()),
            (-2.5, 0.0),
        ] {
            assert!(agrees_with_ik(&r, yaw, tilt) > 0, "{yaw} {tilt}");
        }
        // Fan 270° at 11.5°: as asked the yaw joint would need ≈ ±135°,
        // flipped the tilt would be −11.5°: nowhere.
        let e = r.region_for(1.5 * PI, 11.5f64.to_radians()).unwrap_err();
        assert!(e.joint == "ee_yaw_rad" || (e.joint == "tilt_rad" && e.flipped));
        // A yaw range with a gap inside the base window cuts it in two.
        let r = asymmetric(2.5);
        let reg = r.region_for(-PI / 2.0, 11.5f64.to_radians()).unwrap();
        assert_eq!(reg.sectors_rad.len(), 2, "{:?}", reg.sectors_rad);
        assert_eq!(reg.boundaries(0.01).len(), 2);
        let sweep = reg.sectors_rad[0][1] - reg.sectors_rad[0][0] + reg.sectors_rad[1][1]
            - reg.sectors_rad[1][0];
        assert!((sweep - (2.3562 - 0.7854 - (TAU - 5.0))).abs() < 1e-9);
        assert!(agrees_with_ik(&r, -PI / 2.0, 11.5f64.to_radians()) > 0);
        // Both branches in range (|β| ≤ 0.1): the whole window.
        let reg = r.region_for(-PI / 2.0, 0.05).unwrap();
        assert!((reg.area_m2() - full).abs() < 1e-12);
    }

    #[test]
    fn the_linkage_is_mirror_symmetric() {
        // region_for relies on it: −β moves the tip by the mirrored offset.
        let f = &Robot::basr().end_effector.fourbar;
        for b in [0.05, 0.1, 0.2, 0.26] {
            let (p, m) = (f.tip_offset(b).unwrap(), f.tip_offset(-b).unwrap());
            assert!((p[0] + m[0]).abs() < 1e-15 && (p[1] - m[1]).abs() < 1e-15);
        }
    }
}
