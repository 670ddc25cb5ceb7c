//! The tilt four-bar (Roberts straight-line linkage driven by a ball screw):
//! exact loop-equation solution tilt ↔ nut position, nozzle-tip translation,
//! and the seed's closed forms (000 appendix B §2.6, appendix C §2.1.4).
//!
//! Mechanism plane: `u` horizontal along the fan's +ψ direction, `v` up; the
//! origin is the midpoint of the ground link, which is the nut's centre
//! position and lies on the end-effector's yaw axis. The ground pivots are
//! A = (−g/2, 0) and D = (g/2, 0); both rockers have length r; the coupler
//! (length c) hangs below the ground link. The coupler point P (the ball
//! screw's connection) is the apex of the isosceles triangle on the coupler
//! with PB = PC = r (Roberts: triangles ABP and CDP are isosceles, 000 app. C
//! §2.1.7); with g = 2c it sits on the ground line in the centre position and
//! moves along it in an almost straight line. The nozzle is fixed to the
//! coupler, its tip `t` below the coupler's midpoint, so that at zero tilt the
//! tip lies on the yaw axis. The tilt β is the coupler's rotation,
//! counter-clockwise in (u, v): β > 0 points the nozzle towards +ψ (SPEC §2).

use serde::{Deserialize, Serialize};

/// Geometry of the tilt linkage (lengths in metres).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FourBar {
    /// Ground link: distance between the two rocker pivots on the end-effector.
    pub ground_m: f64,
    /// Coupler (platform) link between the two lower rocker joints.
    pub coupler_m: f64,
    /// Rocker (side) links, both equal (symmetric tilt).
    pub rocker_m: f64,
    /// Nozzle tip distance below the coupler's midpoint.
    pub tip_below_coupler_m: f64,
}

/// Where the coupler is for one tilt: its midpoint and angle in (u, v).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CouplerPose {
    pub mid: [f64; 2],
    pub angle_rad: f64,
}

/// The two ways the linkage can be assembled for a given coupler angle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Assembly {
    /// Coupler below the ground link: how BASR is built.
    Below = 0,
    /// Coupler mirrored above the ground link (needs disassembly to reach).
    Above = 1,
}

fn rot(a: f64, p: [f64; 2]) -> [f64; 2] {
    let (s, c) = a.sin_cos();
    [c * p[0] - s * p[1], s * p[0] + c * p[1]]
}

impl FourBar {
    /// Height of the coupler point P above the coupler's midpoint (Roberts'
    /// isosceles triangle with legs equal to the rocker).
    pub fn p_height_m(&self) -> f64 {
        (self.rocker_m.powi(2) - (0.5 * self.coupler_m).powi(2)).sqrt()
    }

    /// Coupler pose for tilt `beta` in the given assembly mode, or `None`
    /// when the loop cannot close. Loop equation (000 app. B eq. 2.48, app. C
    /// eq. 2.1): A + r·e^{iφ} + c·e^{iβ} + r·e^{iθ3} = D. With
    /// w = A − D + c·e^{iβ}, |w + r·e^{iφ}| = r gives
    /// cos(φ − arg w) = −|w|/(2r), whose two roots are the assembly modes.
    pub fn solve(&self, beta: f64, mode: Assembly) -> Option<CouplerPose> {
        let (r, c, g) = (self.rocker_m, self.coupler_m, self.ground_m);
        let (sb, cb) = beta.sin_cos();
        let w = [-g + c * cb, c * sb];
        let rho = w[0].hypot(w[1]);
        let k = -rho / (2.0 * r);
        if !(-1.0..=1.0).contains(&k) || !k.is_finite() {
            return None;
        }
        let omega = w[1].atan2(w[0]);
        let phi = match mode {
            Assembly::Below => omega + k.acos(),
            Assembly::Above => omega - k.acos(),
        };
        let b = [-0.5 * g + r * phi.cos(), r * phi.sin()];
        let mid = [b[0] + 0.5 * c * cb, b[1] + 0.5 * c * sb];
        Some(CouplerPose {
            mid,
            angle_rad: beta,
        })
    }

    /// A point given in the coupler frame (x along B→C, y up at zero tilt,
    /// origin at the coupler midpoint), in (u, v) for tilt `beta`.
    fn coupler_point(&self, beta: f64, local: [f64; 2]) -> Option<[f64; 2]> {
        let pose = self.solve(beta, Assembly::Below)?;
        let p = rot(pose.angle_rad, local);
        Some([pose.mid[0] + p[0], pose.mid[1] + p[1]])
    }

    /// Coupler point P (the nut connection) in (u, v) for tilt `beta`.
    pub fn p_point(&self, beta: f64) -> Option<[f64; 2]> {
        self.coupler_point(beta, [0.0, self.p_height_m()])
    }

    /// Nozzle tip in (u, v) for tilt `beta`.
    pub fn tip_point(&self, beta: f64) -> Option<[f64; 2]> {
        self.coupler_point(beta, [0.0, -self.tip_below_coupler_m])
    }

    /// Ball-screw nut travel from its centre (m) for tilt `beta`: the
    /// horizontal motion of P (the screw lies along the ground link; the ball
    /// end joint takes P's small vertical motion, 000 app. C §2.2).
    pub fn nut_m(&self, beta: f64) -> Option<f64> {
        Some(self.p_point(beta)?[0] - self.p_point(0.0)?[0])
    }

    /// Vertical motion of P from its centre position (taken by the ball end joint).
    pub fn nut_play_m(&self, beta: f64) -> Option<f64> {
        Some(self.p_point(beta)?[1] - self.p_point(0.0)?[1])
    }

    /// Translation of the nozzle tip from its zero-tilt position:
    /// (along +ψ, up), metres.
    pub fn tip_offset(&self, beta: f64) -> Option<[f64; 2]> {
        let t = self.tip_point(beta)?;
        let t0 = self.tip_point(0.0)?;
        Some([t[0] - t0[0], t[1] - t0[1]])
    }

    /// Tilt giving nut travel `nut` (inverse of [`FourBar::nut_m`]), searched
    /// within ±`span` rad where the map is monotonic. Bisection to the last
    /// bit: robust, and cheap next to everything else per setpoint.
    pub fn tilt_from_nut(&self, nut: f64, span: f64) -> Option<f64> {
        if !(nut.is_finite() && span.is_finite() && span > 0.0) {
            return None;
        }
        let (mut lo, mut hi) = (-span, span);
        let f = |b: f64| self.nut_m(b).map(|n| n - nut);
        let (flo, fhi) = (f(lo)?, f(hi)?);
        if flo == 0.0 {
            return Some(lo);
        }
        if fhi == 0.0 {
            return Some(hi);
        }
        if flo.signum() == fhi.signum() {
            return None;
        }
        let rising = fhi > flo;
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            let fm = f(mid)?;
            if (fm < 0.0) == rising {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let (flo, fhi) = (f(lo)?.abs(), f(hi)?.abs());
        Some(if flo <= fhi { lo } else { hi })
    }

    /// Nut travel per radian of tilt at `beta` (central difference).
    pub fn nut_rate_m_per_rad(&self, beta: f64) -> Option<f64> {
        let h = 1e-6;
        Some((self.nut_m(beta + h)? - self.nut_m(beta - h)?) / (2.0 * h))
    }

    /// The seed's height compensation d3 = (r2/2)·sin θ2e (000 app. B eq.
    /// 3.16), r2 the coupler. Reported for comparison; the kinematics use the
    /// exact tip translation of [`FourBar::tip_offset`].
    pub fn seed_d3_m(&self, beta: f64) -> f64 {
        0.5 * self.coupler_m * beta.sin()
    }
}

/// Rocker angle θ1e for platform tilt θ2e, as computed in 000 appendix B
/// (appendix A program, eq. 2.55–2.56, the `+` root): the seed's linkage with
/// the coupler above the ground link, links r1, r2 (platform), r3, r4 (base).
pub fn seed_theta1e(r1: f64, r2: f64, r3: f64, r4: f64, theta2e: f64) -> Option<f64> {
    let (s2, c2) = theta2e.sin_cos();
    let base = r1 * r1 + r2 * r2 + r4 * r4 - r3 * r3 - 2.0 * r4 * r2 * c2;
    let a = base - 2.0 * r2 * r1 * c2 + 2.0 * r4 * r1;
    let b = 4.0 * r2 * r1 * s2;
    let c = base + 2.0 * r2 * r1 * c2 - 2.0 * r4 * r1;
    let disc = b * b - 4.0 * a * c; // eq. 2.56a
    if disc < 0.0 || a == 0.0 {
        // eq. 2.56b
        return None;
    }
    Some(2.0 * ((-b + disc.sqrt()) / (2.0 * a)).atan())
}

/// Straight-line motion Δx of the seed's linkage for tilt θ2e, exactly as
/// 000 appendix B's program evaluates eq. 2.57 (an approximation of the
/// coupler point's travel; [`FourBar::nut_m`] is the exact one).
pub fn seed_delta_x(r1: f64, r2: f64, r3: f64, r4: f64, theta2e: f64) -> Option<f64> {
    let t1 = seed_theta1e(r1, r2, r3, r4, theta2e)?;
    let inner = r1 * r1 - (r2 * theta2e.sin() + r1 * t1.sin()).powi(2);
    if inner < 0.0 {
        return None; // eq. 3.32
    }
    Some(
        r4 / 2.0 - r2 * theta2e.cos() + r2 / (2.0 * theta2e.cos()) + r1 * t1.sin() * theta2e.tan()
            - inner.sqrt(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 000 appendix B, "Results (Appendix B)": θ2e, θ1e, Δx for
    /// r1 = r3 = 0.9, r2 = 0.6, r4 = 1.2 (θ2e from −π/9 to π/9 by π/90).
    const APP_B: [(f64, f64, f64); 21] = [
        (-0.34907, 1.5023, -0.54599),
        (-0.31416, 1.4842, -0.49804),
        (-0.27925, 1.4638, -0.4484),
        (-0.24435, 1.4412, -0.39704),
        (-0.20944, 1.4165, -0.34402),
        (-0.17453, 1.3898, -0.28943),
        (-0.13963, 1.3611, -0.23342),
        (-0.10472, 1.3307, -0.1762),
        (-0.069813, 1.2987, -0.11802),
        (-0.034907, 1.2654, -0.059181),
        (0.0, 1.231, 2.2204e-16),
        (0.034907, 1.1957, 0.059181),
        (0.069813, 1.1598, 0.11802),
        (0.10472, 1.1235, 0.1762),
        (0.13963, 1.0872, 0.23342),
        (0.17453, 1.0509, 0.28943),
        (0.20944, 1.0151, 0.34402),
        (0.24435, 0.97971, 0.39704),
        (0.27925, 0.94505, 0.4484),
        (0.31416, 0.9112, 0.49804),
        (0.34907, 0.87828, 0.54599),
    ];

    /// Round to `sig` significant digits, as MATLAB's `format short g` prints.
    fn sig(x: f64, sig: i32) -> f64 {
        if x == 0.0 {
            return 0.0;
        }
        let e = x.abs().log10().floor() as i32;
        let f = 10f64.powi(sig - 1 - e);
        (x * f).round() / f
    }

    /// Significant digits the table prints for a value (5, MATLAB short g).
    fn printed_digits(printed: f64) -> i32 {
        let s = format!("{}", printed.abs());
        s.trim_start_matches(['0', '.'])
            .chars()
            .filter(|c| c.is_ascii_digit())
            .count() as i32
    }

    #[test]
    fn appendix_b_tables_reproduced_to_printed_digits() {
        for (i, &(t2_printed, t1_printed, dx_printed)) in APP_B.iter().enumerate() {
            // The program steps θ2e from −π/9 by π/90.
            let t2 = -std::f64::consts::PI / 9.0 + i as f64 * std::f64::consts::PI / 90.0;
            if t2_printed != 0.0 {
                assert_eq!(sig(t2, printed_digits(t2_printed)), t2_printed);
            }
            let t1 = seed_theta1e(0.9, 0.6, 0.9, 1.2, t2).unwrap();
            assert_eq!(
                sig(t1, printed_digits(t1_printed)),
                t1_printed,
                "θ1e at {t2}"
            );
            let dx = seed_delta_x(0.9, 0.6, 0.9, 1.2, t2).unwrap();
            if t2_printed == 0.0 {
                // MATLAB's −π/9 + 10·π/90 leaves 2.2e-16; both are zero to print.
                assert!(dx.abs() < 1e-12);
            } else {
                assert_eq!(
                    sig(dx, printed_digits(dx_printed)),
                    dx_printed,
                    "Δx at {t2}"
                );
            }
        }
    }

    fn seed_linkage() -> FourBar {
        FourBar {
            ground_m: 1.2,
            coupler_m: 0.6,
            rocker_m: 0.9,
            tip_below_coupler_m: 0.0,
        }
    }

    #[test]
    fn exact_loop_agrees_with_seed_rocker_angle() {
        // The seed's linkage is ours mirrored (coupler above): its rocker
        // angle θ1e is the mirror of φ in the Below mode.
        let fb = seed_linkage();
        for &(t2, _, _) in &APP_B {
            let t1 = seed_theta1e(0.9, 0.6, 0.9, 1.2, t2).unwrap();
            let pose = fb.solve(-t2, Assembly::Below).unwrap();
            // B = mid − (c/2)e^{iβ}; φ = angle of B − A.
            let b = [
                pose.mid[0] - 0.3 * (-t2).cos(),
                pose.mid[1] - 0.3 * (-t2).sin(),
            ];
            let phi = b[1].atan2(b[0] + 0.6);
            assert!((phi + t1).abs() < 1e-12, "{phi} vs {t1}");
        }
    }

    #[test]
    fn seed_delta_x_approximates_exact_coupler_point_travel() {
        // Eq. 2.57 is within 1.1 mm of the exact travel of P over ±20° on
        // the 1.2 m seed linkage (1.0 mm at ±16°, 0.75 mm at the ends).
        let fb = seed_linkage();
        for &(t2, _, _) in &APP_B {
            let exact = fb.nut_m(-t2).unwrap();
            let seed = seed_delta_x(0.9, 0.6, 0.9, 1.2, t2).unwrap();
            assert!((exact - seed).abs() < 1.1e-3, "{t2}: {exact} vs {seed}");
        }
    }

    pub(crate) fn basr() -> FourBar {
        FourBar {
            ground_m: 0.30,
            coupler_m: 0.15,
            rocker_m: 0.23,
            tip_below_coupler_m: 0.2174,
        }
    }

    #[test]
    fn loop_closes_in_both_modes() {
        let fb = basr();
        for i in -30..=30 {
            let beta = i as f64 * 0.01;
            for mode in [Assembly::Below, Assembly::Above] {
                let p = fb.solve(beta, mode).unwrap();
                let (s, c) = beta.sin_cos();
                let b = [p.mid[0] - 0.075 * c, p.mid[1] - 0.075 * s];
                let cc = [p.mid[0] + 0.075 * c, p.mid[1] + 0.075 * s];
                assert!(((b[0] + 0.15).hypot(b[1]) - 0.23).abs() < 1e-14);
                assert!(((cc[0] - 0.15).hypot(cc[1]) - 0.23).abs() < 1e-14);
                match mode {
                    Assembly::Below => assert!(p.mid[1] < 0.0),
                    Assembly::Above => assert!(p.mid[1] > 0.0),
                }
            }
        }
        // In the centre position P sits at the middle of the ground link.
        let p0 = fb.p_point(0.0).unwrap();
        assert!(p0[0].abs() < 1e-15 && p0[1].abs() < 1e-15);
    }

    #[test]
    fn default_nut_travel_per_degree_at_15_degrees() {
        // SPEC §4 / 000 app. C eq. 2.6: ≈ 7.3 mm of nut travel per degree.
        // The exact linkage gives 7.24 mm/deg over ±15° (chord), 7.59 at 0°.
        let fb = basr();
        let b15 = 15f64.to_radians();
        let per_deg_plus = fb.nut_m(b15).unwrap().abs() / 15.0;
        let per_deg_minus = fb.nut_m(-b15).unwrap().abs() / 15.0;
        assert!((per_deg_plus - 0.007242).abs() < 5e-6, "{per_deg_plus}");
        assert!((per_deg_plus - per_deg_minus).abs() < 1e-12);
        assert!((0.0070..=0.0076).contains(&per_deg_plus));
        // Least-squares slope over ±15° like the seed's regression (eq. 2.6).
        let n = 61;
        let (mut sxy, mut sxx) = (0.0, 0.0);
        for i in 0..n {
            let deg = -15.0 + 0.5 * i as f64;
            let y = fb.nut_m(f64::to_radians(deg)).unwrap();
            sxy += deg * y;
            sxx += deg * deg;
        }
        let slope = (sxy / sxx).abs();
        assert!((slope - 0.00737).abs() < 1e-5, "{slope}");
    }

    #[test]
    fn nut_inverse_is_exact() {
        let fb = basr();
        for i in -26..=26 {
            let beta = i as f64 * 0.01;
            let nut = fb.nut_m(beta).unwrap();
            let back = fb.tilt_from_nut(nut, 0.3).unwrap();
            assert!((back - beta).abs() < 1e-13, "{beta}: {back}");
        }
        assert!(fb.tilt_from_nut(1.0, 0.3).is_none());
    }

    #[test]
    fn tip_at_instant_centre_moves_little() {
        // With the tip at the linkage's instantaneous centre, tilting 15°
        // moves it 3.9 mm along the fan (first order cancels) and raises it
        // 15.6 mm, which the vertical joint takes; the seed's d3 estimate
        // (r2/2)·sin θ2e is 19.4 mm.
        let fb = basr();
        let off = fb.tip_offset(15f64.to_radians()).unwrap();
        assert!((off[0] - 0.0039).abs() < 1e-4, "{off:?}");
        assert!((off[1] - 0.0156).abs() < 1e-4, "{off:?}");
        let small = fb.tip_offset(0.01).unwrap();
        assert!(small[0].abs() < 1e-5, "{small:?}");
        let mirrored = fb.tip_offset(-(15f64.to_radians())).unwrap();
        assert!((off[0] + mirrored[0]).abs() < 1e-15);
        assert!((off[1] - mirrored[1]).abs() < 1e-15);
        assert!((fb.seed_d3_m(15f64.to_radians()) - 0.075 * 0.2588190451).abs() < 1e-9);
    }
}
