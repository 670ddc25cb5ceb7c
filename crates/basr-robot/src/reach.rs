//! The reach the station planner places trucks by: a signed margin (m) of
//! a tip point in the base frame, > 0 inside. BASR's is its exact region
//! (`workspace::Region`); an electric kind's is a sector of a ring round
//! the base axis, found from its inverse kinematics: the radii and tip
//! azimuths where every painting height is reached with the fan along and
//! across x_B, untilted and at its tilt limits — the intersection over the
//! sampled heights, radii and azimuths, so a point inside is reached at
//! every one of them. Points a sector keeps but the arm cannot paint (its
//! edges are not exactly radial) are refused by the joint-path stage with
//! the stroke and the joint.

use std::f64::consts::{FRAC_PI_2, PI};

use super::kind::ArmKind;
use super::workspace::Region;
use super::{JointLimit, NozzlePose};

/// Where a robot's tip reaches on the road (base frame).
#[derive(Clone, Debug, PartialEq)]
pub enum Reach {
    /// BASR's pantograph region at zero tilt.
    Region(Region),
    /// A sector of a ring: tip azimuth and distance from the base axis.
    Sector(Sector),
}

/// Tip azimuths [a0, a1] (rad, from +x_B) and distances [r0, r1] (m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sector {
    pub azimuth_rad: [f64; 2],
    pub radius_m: [f64; 2],
}

impl Reach {
    /// Signed distance-like margin (m): > 0 inside.
    pub fn margin(&self, x: f64, y: f64) -> f64 {
        match self {
            Reach::Region(r) => r.margin(x, y),
            Reach::Sector(s) => s.margin(x, y),
        }
    }

    /// A point in the middle of the reach (base frame).
    pub fn centre(&self) -> [f64; 2] {
        let (a, r) = match self {
            Reach::Region(g) => (g.base_rot_rad, g.extension_m),
            Reach::Sector(s) => (s.azimuth_rad, s.radius_m),
        };
        let (am, rm) = (0.5 * (a[0] + a[1]), 0.5 * (r[0] + r[1]));
        [rm * am.cos(), rm * am.sin()]
    }

    /// The sector an electric kind reaches (see the module).
    pub fn sector_of(arm: &dyn ArmKind, tilt: Option<JointLimit>) -> Reach {
        Reach::Sector(Sector::of(arm, tilt))
    }
}

/// Largest distance searched from the base axis (m). assumed: no road arm
/// reaches further (as the station planner's bound).
const MAX_R_M: f64 = 10.0;
/// Coarse search step before refinement (m, rad).
const STEP_M: f64 = 0.05;
const STEP_RAD: f64 = 0.01;

impl Sector {
    pub fn margin(&self, x: f64, y: f64) -> f64 {
        if !(x.is_finite() && y.is_finite()) {
            return f64::NEG_INFINITY;
        }
        let r = x.hypot(y);
        let [a0, a1] = self.azimuth_rad;
        let mid = 0.5 * (a0 + a1);
        let az = mid + super::kinematics::wrap_pi(y.atan2(x) - mid);
        // Distance to an edge ray `d` inside it (d > 0) or outside (d < 0):
        // across the ray within a quarter turn, else from its origin.
        let lateral = |d: f64| {
            if d.abs() < FRAC_PI_2 {
                r * d.sin()
            } else if d > 0.0 {
                r
            } else {
                -r - d.abs()
            }
        };
        (r - self.radius_m[0])
            .min(self.radius_m[1] - r)
            .min(lateral(az - a0))
            .min(lateral(a1 - az))
    }

    /// The sector of `arm` (see the module). Empty ([0, 0]) when the arm
    /// reaches nothing on the middle azimuth.
    pub fn of(arm: &dyn ArmKind, tilt: Option<JointLimit>) -> Sector {
        let heights = arm.tip_heights_m();
        let zs = [heights[0], 0.5 * (heights[0] + heights[1]), heights[1]];
        let tilts: Vec<f64> = match tilt {
            Some(t) => vec![0.0, t.min.max(-t.max.abs()), t.max.min(t.min.abs())],
            None => vec![0.0],
        };
        let ok = |x: f64, y: f64| zs.iter().all(|&z| reaches(arm, x, y, z, &tilts));
        let base = arm.limits()[0];
        let mid = 0.5 * (base.min + base.max);
        let at = |a: f64, r: f64| ok(r * a.cos(), r * a.sin());
        // Radii along the middle azimuth: the first reached run outward.
        let n = (MAX_R_M / STEP_M) as usize;
        let Some(i0) = (0..=n).find(|&i| at(mid, i as f64 * STEP_M)) else {
            return Sector {
                azimuth_rad: [mid, mid],
                radius_m: [0.0, 0.0],
            };
        };
        let r0 = refine(
            |r| at(mid, r),
            (i0.max(1) - 1) as f64 * STEP_M,
            i0 as f64 * STEP_M,
        );
        let i1 = (i0..=n).find(|&i| !at(mid, i as f64 * STEP_M)).unwrap_or(n);
        let r1 = refine(
            |r| !at(mid, r),
            (i1 - 1) as f64 * STEP_M,
            i1 as f64 * STEP_M,
        );
        // Azimuths either side, the narrowest over a few radii.
        let mut lo = f64::NEG_INFINITY;
        let mut hi = f64::INFINITY;
        for k in 0..=4 {
            let r = r0 + (r1 - r0) * (0.05 + 0.9 * k as f64 / 4.0);
            for side in [-1.0, 1.0] {
                let m = (PI / STEP_RAD) as usize;
                let j = (1..=m)
                    .find(|&j| !at(mid + side * j as f64 * STEP_RAD, r))
                    .unwrap_or(m);
                let edge = refine(
                    |d| !at(mid + side * d, r),
                    (j - 1) as f64 * STEP_RAD,
                    j as f64 * STEP_RAD,
                );
                if side < 0.0 {
                    lo = lo.max(mid - edge);
                } else {
                    hi = hi.min(mid + edge);
                }
            }
        }
        Sector {
            azimuth_rad: [lo, hi],
            radius_m: [r0, r1],
        }
    }
}

/// Whether the tip reaches (x, y, z) with the fan along and across x_B
/// (either way round) at each of `tilts`.
fn reaches(arm: &dyn ArmKind, x: f64, y: f64, z: f64, tilts: &[f64]) -> bool {
    tilts.iter().all(|&tilt| {
        [0.0, FRAC_PI_2, PI, -FRAC_PI_2].iter().all(|&yaw| {
            arm.ik(&NozzlePose {
                x_m: x,
                y_m: y,
                z_m: z,
                yaw_rad: yaw,
                tilt_rad: tilt,
            })
            .is_ok()
        })
    })
}

/// The first value in (a, b] where `f` holds, to 1 mm or 1 mrad (f(a)
/// false, f(b) true); returned on the side where it holds.
fn refine(f: impl Fn(f64) -> bool, mut a: f64, mut b: f64) -> f64 {
    while b - a > 1e-3 {
        let m = 0.5 * (a + b);
        if f(m) {
            b = m;
        } else {
            a = m;
        }
    }
    b
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kind::{AnyRobot, ARTICULATED_TOML, TELESCOPIC_TOML};
    use proptest::prelude::*;

    /// The shipped electric kinds and their sectors, found once.
    fn shipped() -> &'static [(AnyRobot, Sector); 2] {
        static ONCE: std::sync::OnceLock<[(AnyRobot, Sector); 2]> = std::sync::OnceLock::new();
        ONCE.get_or_init(|| {
            [TELESCOPIC_TOML, ARTICULATED_TOML].map(|text| {
                let r = AnyRobot::from_toml_str(text, "shipped").unwrap();
                let Reach::Sector(s) = r.reach() else {
                    unreachable!("an electric kind's reach is a sector")
                };
                (r, s)
            })
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]
        /// A point the sector keeps 5 cm inside (the station planner's
        /// default margin) is reached at any painting height, fan direction
        /// and tilt within the limits, not only at the sampled ones.
        #[test]
        fn a_point_inside_is_reached_at_any_height_fan_and_tilt(
            kind in 0usize..2, u in 0.0f64..1.0, v in 0.0f64..1.0,
            h in 0.0f64..1.0, yaw in -3.2f64..3.2, b in -1.0f64..1.0,
        ) {
            let (r, s) = &shipped()[kind];
            let az = s.azimuth_rad[0] + u * (s.azimuth_rad[1] - s.azimuth_rad[0]);
            let rad = s.radius_m[0] + v * (s.radius_m[1] - s.radius_m[0]);
            let (x, y) = (rad * az.cos(), rad * az.sin());
            prop_assume!(s.margin(x, y) > 0.05);
            let [z0, z1] = r.tip_heights_m();
            let tilt = r.tilt_limit().map_or(0.0, |t| if b > 0.0 { b * t.max } else { -b * t.min });
            let pose = NozzlePose { x_m: x, y_m: y, z_m: z0 + h * (z1 - z0), yaw_rad: yaw, tilt_rad: tilt };
            prop_assert!(r.ik(&pose).is_ok(), "{}: {pose:?} in {s:?}", r.name());
        }
    }

    /// Every point the sector keeps 5 cm inside is reached at every painting
    /// height; the shipped arms' sectors cover a 12 ft lane over more than
    /// an 8 ft letter (the station planner then needs one station for an
    /// 8 ft word).
    #[test]
    fn sector_points_are_reached_and_cover_a_lane() {
        for text in [TELESCOPIC_TOML, ARTICULATED_TOML] {
            let r = AnyRobot::from_toml_str(text, "shipped").unwrap();
            let Reach::Sector(s) = r.reach() else {
                panic!("an electric kind's reach is a sector")
            };
            let tilts = match r.tilt_limit() {
                Some(t) => vec![0.0, t.min, t.max],
                None => vec![0.0],
            };
            let mut kept = 0;
            for i in -40..=40 {
                for j in 0..=60 {
                    let (x, y) = (i as f64 * 0.1, j as f64 * 0.1);
                    if s.margin(x, y) > 0.05 {
                        kept += 1;
                        for z in r.tip_heights_m() {
                            assert!(reaches(r.arm(), x, y, z, &tilts), "{s:?}: ({x}, {y}, {z})");
                        }
                    }
                }
            }
            assert!(kept > 100, "{s:?}");
            // The lane across at 2.0 and 4.2 m behind the base.
            for y in [2.0, 4.2] {
                for x in [-1.83, 0.0, 1.83] {
                    assert!(s.margin(x, y) > 0.0, "{}: {s:?} ({x}, {y})", r.name());
                }
            }
        }
    }
}
