//! The road surface under a job (docs/site.md): the cross slope and crown a
//! marking file describes, and the plane `basr fit` measured under a stop.
//!
//! Heights are in metres, in the road frame (z up, zero at the road surface
//! at the marking's anchor) or in a stop's base frame (zero at the road
//! surface under the arm's axis). The truck stands on the road: its frame
//! leans with the surface under the arm's axis, so what the arm must follow
//! is the surface relative to that plane (a crown between the axis and the
//! marking, or a plane `fit` measured). A fitted plane is measured in the
//! arm's own frame, so whatever the truck's lean, it is the surface the arm
//! sees.
//!
//! A flat road is the default and is not written into the job, so a job on
//! a flat road has the bytes it had before roads were described.

use serde::{Deserialize, Serialize};

use super::Station;

/// The road's surface under a job.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Road {
    /// Fall of the surface per metre towards the driver's right (+x of the
    /// road frame), m/m (a 2 % cross slope is 0.02). Negative: it rises.
    #[serde(default)]
    pub cross_slope: f64,
    /// A crown line along the traffic at this road x (m): the slope changes
    /// sign there and the road falls away on both sides.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub crown_x_m: Option<f64>,
    /// Planes measured under stops (`basr fit`), which replace the slope
    /// and crown for the marking painted from that stop.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub planes: Vec<StopPlane>,
}

/// The road surface under one stop as a plane in that stop's base frame:
/// `z = z_m + dz_dx · x + dz_dy · y` (metres, base-frame x and y).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StopPlane {
    /// The stop, counted from 1 as on the job sheet.
    pub stop: usize,
    pub z_m: f64,
    pub dz_dx: f64,
    pub dz_dy: f64,
}

impl StopPlane {
    /// Height of the plane (base frame) at a base-frame point.
    pub fn z_at(&self, b: [f64; 2]) -> f64 {
        self.z_m + self.dz_dx * b[0] + self.dz_dy * b[1]
    }
}

/// Where the nozzle must be for a fan that, on a flat road, would stand at
/// `tip` with height `height_m` and tilt `tilt_rad` along `yaw_rad`: on
/// this surface, the same fan relative to the surface (same footprint,
/// same height over it, same lean against it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OnSurface {
    /// The nozzle's road-frame x, y.
    pub xy: [f64; 2],
    /// The nozzle's height in the stop's base frame (m).
    pub base_z_m: f64,
    /// Tilt to command (rad): the planned tilt plus the surface's rise
    /// along the fan.
    pub tilt_rad: f64,
}

/// A nozzle pose turned into the flat-road pose that lays the same film
/// on this surface (what preview and simulate measure).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Relative {
    /// The foot of the perpendicular from the nozzle to the surface, in the
    /// road frame's x, y.
    pub xy: [f64; 2],
    /// The nozzle's distance from the surface along that perpendicular.
    pub height_m: f64,
    /// The tilt against the surface's normal.
    pub tilt_rad: f64,
}

impl Road {
    /// True on a flat road with no fitted plane (the default).
    pub fn is_flat(&self) -> bool {
        self.cross_slope == 0.0 && self.crown_x_m.is_none() && self.planes.is_empty()
    }

    /// The described (cross slope and crown) surface's road-frame height at
    /// road point `p`; zero at the anchor's x.
    pub fn model_z(&self, p: [f64; 2]) -> f64 {
        match self.crown_x_m {
            None => -self.cross_slope * p[0],
            Some(c) => -self.cross_slope * ((p[0] - c).abs() - c.abs()),
        }
    }

    /// Road-frame height of the base frame's origin of `station`: the
    /// described surface under the arm's axis (the truck stands on it).
    pub fn origin_z(&self, station: &Station) -> f64 {
        self.model_z([station.x_m, station.y_m])
    }

    /// The plane fitted under stop `index` (counted from 0), if any.
    pub fn plane(&self, index: usize) -> Option<&StopPlane> {
        self.planes.iter().find(|p| p.stop == index + 1)
    }

    /// The described surface's fall per metre towards +x at road x `x`
    /// (the mean of both sides on the crown line).
    fn fall_at(&self, x: f64) -> f64 {
        match self.crown_x_m {
            Some(c) if x > c => self.cross_slope,
            Some(c) if x < c => -self.cross_slope,
            Some(_) => 0.0,
            None => self.cross_slope,
        }
    }

    /// Height of the surface under road point `p`, in the base frame of
    /// stop `index` at `station`. The truck stands on the described
    /// surface, its frame leaning with the surface under the arm's axis
    /// (lean below 7°: heights along its axis are taken as vertical), so a
    /// uniform cross slope is flat in the arm's frame and a crown between
    /// the axis and the point is not; a fitted plane is the arm's own
    /// measurement.
    pub fn base_z(&self, index: usize, station: &Station, p: [f64; 2]) -> f64 {
        match self.plane(index) {
            Some(plane) => plane.z_at(station.road_to_base(p)),
            None => {
                let lean = -self.fall_at(station.x_m) * (p[0] - station.x_m);
                self.model_z(p) - self.origin_z(station) - lean
            }
        }
    }

    /// The surface's rise (m/m) going along road direction `yaw_rad` from
    /// road point `p`, as stop `index` sees it: the central difference over
    /// ±1 mm, which is the mean of the two sides on a crown line.
    pub fn rise_along(&self, index: usize, station: &Station, p: [f64; 2], yaw_rad: f64) -> f64 {
        // assumed: 1 mm, far below the fan's width and above rounding.
        const H: f64 = 1e-3;
        let u = [yaw_rad.cos(), yaw_rad.sin()];
        let at = |s: f64| self.base_z(index, station, [p[0] + s * u[0], p[1] + s * u[1]]);
        (at(H) - at(-H)) / (2.0 * H)
    }

    /// Where the nozzle goes so that its fan lands on this surface as the
    /// plan's fan (tip `tip`, height `height_m` and tilt `tilt_rad` along
    /// `yaw_rad`) lands on a flat road. A surface rising by the angle α
    /// along the fan turns the fan's frame by α: the nozzle leans α more,
    /// stands `height_m / cos α` above the surface and `height_m · sin α`
    /// back along the fan from the perpendicular foot, which is the tip.
    pub fn place(
        &self,
        index: usize,
        station: &Station,
        tip: [f64; 2],
        yaw_rad: f64,
        height_m: f64,
        tilt_rad: f64,
    ) -> OnSurface {
        if self.is_flat() {
            return OnSurface {
                xy: tip,
                base_z_m: height_m,
                tilt_rad,
            };
        }
        let alpha = snap(self.rise_along(index, station, tip, yaw_rad)).atan();
        let back = height_m * alpha.sin();
        let xy = [tip[0] - back * yaw_rad.cos(), tip[1] - back * yaw_rad.sin()];
        OnSurface {
            xy,
            base_z_m: snap(self.base_z(index, station, xy)) + height_m / alpha.cos(),
            tilt_rad: tilt_rad + alpha,
        }
    }

    /// The inverse of [`Road::place`] for a nozzle of stop `index` at road
    /// `xy` and road-frame height `z_road` with fan `yaw_rad`, `tilt_rad`:
    /// the flat-road pose laying the same film.
    pub fn relative(
        &self,
        index: usize,
        station: &Station,
        xy: [f64; 2],
        z_road: f64,
        yaw_rad: f64,
        tilt_rad: f64,
    ) -> Relative {
        if self.is_flat() {
            return Relative {
                xy,
                height_m: z_road,
                tilt_rad,
            };
        }
        let vertical = z_road - self.origin_z(station) - snap(self.base_z(index, station, xy));
        let alpha = snap(self.rise_along(index, station, xy, yaw_rad)).atan();
        let ahead = vertical * alpha.sin() * alpha.cos();
        Relative {
            xy: [xy[0] + ahead * yaw_rad.cos(), xy[1] + ahead * yaw_rad.sin()],
            height_m: vertical * alpha.cos(),
            tilt_rad: tilt_rad - alpha,
        }
    }

    /// What is wrong with this description, if anything (a job's `road`
    /// is checked like a marking file's `[road]`).
    pub fn problem(&self, stops: usize) -> Option<String> {
        if !self.cross_slope.is_finite() || self.cross_slope.abs() > MAX_CROSS_SLOPE {
            let (pct, max) = basr_io::show_apart(self.cross_slope * 100.0, MAX_CROSS_SLOPE * 100.0);
            let what = if self.cross_slope.is_nan() {
                "is not a number".to_string()
            } else {
                format!("{pct} % is outside ±{max} %")
            };
            return Some(format!(
                "cross slope {what} (a road's cross slope is 1.5–2 %, a superelevated \
                 curve's at most about 12 %)"
            ));
        }
        if let Some(c) = self.crown_x_m {
            if !c.is_finite() || c.abs() > MAX_CROWN_X_M {
                let (x, max) = basr_io::show_apart(c, MAX_CROWN_X_M);
                let what = if c.is_nan() {
                    "is not a number".to_string()
                } else {
                    format!("{x} m is not within ±{max} m of the lane centre")
                };
                return Some(format!("crown line x {what}"));
            }
        }
        let mut seen = std::collections::BTreeSet::new();
        for p in &self.planes {
            if p.stop == 0 || p.stop > stops {
                return Some(format!(
                    "a fitted plane names stop {}, but the job has {stops} stops",
                    p.stop
                ));
            }
            if !seen.insert(p.stop) {
                return Some(format!("stop {} has two fitted planes", p.stop));
            }
            let finite = [p.z_m, p.dz_dx, p.dz_dy].iter().all(|v| v.is_finite());
            if !finite
                || p.z_m.abs() > MAX_PLANE_OFFSET_M
                || p.dz_dx.hypot(p.dz_dy) > MAX_CROSS_SLOPE
            {
                return Some(format!(
                    "stop {}'s fitted plane (z {} m, slopes {} and {}) is not a road under \
                     the arm (within ±{MAX_PLANE_OFFSET_M} m of its base and sloped at most \
                     {} %)",
                    p.stop,
                    basr_io::show_num(p.z_m),
                    basr_io::show_num(p.dz_dx),
                    basr_io::show_num(p.dz_dy),
                    MAX_CROSS_SLOPE * 100.0
                ));
            }
        }
        None
    }
}

/// `v`, or 0 when it is rounding: a uniform slope is flat to the arm,
/// and its heights and rises come out of the differences as ±1e-17 m.
/// assumed: a nanometre (or 1e-9 m/m) is no surface any arm follows.
fn snap(v: f64) -> f64 {
    if v.abs() < 1e-9 {
        0.0
    } else {
        v
    }
}

/// Steepest surface basr plans on (m/m). source: AASHTO's Green Book caps
/// superelevation at 12 % (emax); cross slopes of tangent lanes are
/// 1.5–2 %. Beyond it the fan's lean against the road is no longer small.
pub const MAX_CROSS_SLOPE: f64 = 0.12;
/// A crown line further than this from the lane centre (m) is not under
/// any marking in it. assumed: two 3.66 m lanes each side.
pub const MAX_CROWN_X_M: f64 = 15.0;
/// A fitted plane more than this above or below the arm's base at its axis
/// (m) is not the road the truck stands on. assumed: a truck's bed and
/// suspension put the axis within a few centimetres of the surface; 0.3 m
/// is a curb's height.
pub const MAX_PLANE_OFFSET_M: f64 = 0.3;

#[cfg(test)]
mod tests {
    use super::*;

    fn station() -> Station {
        Station {
            x_m: 0.3,
            y_m: 4.6,
            heading_rad: -std::f64::consts::FRAC_PI_2 + 0.04,
        }
    }

    /// A road out of range is told with its number as a person writes it,
    /// not every digit of a huge one.
    #[test]
    fn a_road_out_of_range_is_told_shortly() {
        let steep = Road {
            cross_slope: 1e306,
            ..Road::default()
        };
        let p = steep.problem(0).unwrap();
        assert!(p.starts_with("cross slope 1e308 % is outside ±12 %"), "{p}");
        let crowned = Road {
            crown_x_m: Some(-1e300),
            ..Road::default()
        };
        let p = crowned.problem(0).unwrap();
        assert!(p.starts_with("crown line x -1e300 m is not within"), "{p}");
        // just past a limit, told apart from it; not a number, said so
        let just = Road {
            cross_slope: 0.120000001,
            crown_x_m: Some(MAX_CROWN_X_M + 1e-7),
            ..Road::default()
        };
        let p = just.problem(0).unwrap();
        assert!(
            p.starts_with("cross slope 12.0000001 % is outside ±12 %"),
            "{p}"
        );
        let p = Road {
            cross_slope: 0.0,
            ..just
        }
        .problem(0)
        .unwrap();
        assert!(
            p.starts_with("crown line x 15.0000001 m is not within ±15 m"),
            "{p}"
        );
        let p = Road {
            cross_slope: f64::NAN,
            ..Road::default()
        }
        .problem(0)
        .unwrap();
        assert!(p.starts_with("cross slope is not a number"), "{p}");
        let fitted = Road {
            planes: vec![StopPlane {
                stop: 1,
                z_m: 1e200,
                dz_dx: 0.5,
                dz_dy: 0.0,
            }],
            ..Road::default()
        };
        let p = fitted.problem(1).unwrap();
        assert!(p.contains("(z 1e200 m, slopes 0.5 and 0)"), "{p}");
        assert!(p.len() < 200, "{p}");
    }

    #[test]
    fn flat_is_the_default_and_not_written() {
        let r = Road::default();
        assert!(r.is_flat());
        assert_eq!(r.model_z([3.0, 1.0]), 0.0);
        let p = r.place(0, &station(), [1.0, 2.0], 0.3, 0.1, 0.05);
        assert_eq!((p.xy, p.base_z_m, p.tilt_rad), ([1.0, 2.0], 0.1, 0.05));
    }

    #[test]
    fn a_cross_slope_falls_to_the_right_and_a_crown_both_ways() {
        let r = Road {
            cross_slope: 0.02,
            ..Road::default()
        };
        assert!((r.model_z([1.0, 7.0]) + 0.02).abs() < 1e-15);
        let c = Road {
            cross_slope: 0.02,
            crown_x_m: Some(-1.83),
            ..Road::default()
        };
        assert_eq!(c.model_z([0.0, 0.0]), 0.0);
        // Both sides of the crown are below it.
        let top = c.model_z([-1.83, 0.0]);
        assert!(c.model_z([-2.83, 0.0]) < top && c.model_z([-0.83, 0.0]) < top);
        assert!((top - c.model_z([-2.83, 0.0]) - 0.02).abs() < 1e-12);
    }

    /// `relative` undoes `place`: the nozzle placed for a planned fan reads
    /// back as that fan, on slopes, across a crown and on a fitted plane.
    #[test]
    fn relative_inverts_place() {
        let roads = [
            Road {
                cross_slope: 0.02,
                ..Road::default()
            },
            Road {
                cross_slope: -0.04,
                crown_x_m: Some(0.5),
                ..Road::default()
            },
            Road {
                planes: vec![StopPlane {
                    stop: 1,
                    z_m: 0.012,
                    dz_dx: 0.015,
                    dz_dy: -0.01,
                }],
                ..Road::default()
            },
        ];
        let s = station();
        for r in &roads {
            for (tip, yaw, h, b) in [
                ([1.1, 1.0], 0.0, 0.12, 0.1),
                ([-0.4, 2.0], 1.2, 0.09, -0.2),
                ([0.2, 0.5], -2.5, 0.2, 0.0),
            ] {
                let on = r.place(0, &s, tip, yaw, h, b);
                let z_road = on.base_z_m + r.origin_z(&s);
                let back = r.relative(0, &s, on.xy, z_road, yaw, on.tilt_rad);
                let d = (back.xy[0] - tip[0]).hypot(back.xy[1] - tip[1]);
                // The slope is read at the nozzle, not the tip: second order.
                assert!(d < 1e-5, "{r:?} {tip:?}: foot {d} m off");
                assert!((back.height_m - h).abs() < 1e-5, "{r:?}: {}", back.height_m);
                assert!((back.tilt_rad - b).abs() < 1e-9);
            }
        }
    }

    /// On a plane falling 2 % along the fan, the nozzle leans down-slope
    /// by atan 0.02 and stands h / cos α over the surface under it; a
    /// uniform cross slope leans the truck with it and is flat to the arm.
    #[test]
    fn place_leans_with_the_surface() {
        let s = Station {
            x_m: 0.0,
            y_m: 5.0,
            heading_rad: -std::f64::consts::FRAC_PI_2,
        };
        let uniform = Road {
            cross_slope: 0.02,
            ..Road::default()
        };
        let on = uniform.place(0, &s, [1.0, 2.0], 0.0, 0.1, 0.0);
        assert!(on.tilt_rad.abs() < 1e-12 && (on.base_z_m - 0.1).abs() < 1e-12);
        // Base x is road −x at this heading: z = 0.02·x_B falls along road +x.
        let r = Road {
            planes: vec![StopPlane {
                stop: 1,
                z_m: 0.0,
                dz_dx: 0.02,
                dz_dy: 0.0,
            }],
            ..Road::default()
        };
        let on = r.place(0, &s, [1.0, 2.0], 0.0, 0.1, 0.0);
        let a = -(0.02f64).atan();
        assert!((on.tilt_rad - a).abs() < 1e-9, "{}", on.tilt_rad);
        let under = r.base_z(0, &s, on.xy);
        assert!((on.base_z_m - (under + 0.1 / a.cos())).abs() < 1e-12);
        // A crown between the axis and the point: the far side falls away.
        let crowned = Road {
            cross_slope: 0.02,
            crown_x_m: Some(0.5),
            ..Road::default()
        };
        // 1 m past the crown: 2 × 2 % under the plane the truck leans on.
        assert!((crowned.base_z(0, &s, [1.5, 2.0]) + 0.04).abs() < 1e-12);
        assert!(crowned.base_z(0, &s, [0.4, 2.0]).abs() < 1e-12);
    }

    #[test]
    fn problems_are_named() {
        let steep = Road {
            cross_slope: 0.2,
            ..Road::default()
        };
        assert!(steep.problem(1).unwrap().contains("cross slope 20 %"));
        let stray = Road {
            planes: vec![StopPlane {
                stop: 3,
                z_m: 0.0,
                dz_dx: 0.0,
                dz_dy: 0.0,
            }],
            ..Road::default()
        };
        assert!(stray.problem(2).unwrap().contains("stop 3"));
        assert!(stray.problem(3).is_none());
    }
}
