//! Fitting a stop to where the truck really stopped (docs/site.md): points
//! of the marking whose road-frame place the job knows, measured by the
//! arm in its own base frame, give the stop's pose by least squares (two
//! or more points) and the road surface under it as a plane (three or
//! more).

use basr_job::{Station, StopPlane};

/// One measured reference point.
#[derive(Clone, Debug, PartialEq)]
pub struct Measured {
    /// The crew's name for it (the job sheet's), or `point N`.
    pub name: String,
    /// Where it is on the marking, road frame (m).
    pub road: [f64; 2],
    /// Where the arm measured it, base frame (m): x, y and the road
    /// surface's height z there.
    pub base: [f64; 3],
}

/// How well one point agrees with the fit.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Residual {
    pub name: String,
    /// Distance on the road between the point and where the fitted pose
    /// puts its measurement (m).
    pub xy_m: f64,
    /// Height of the measurement above the fitted plane (m; none without
    /// one).
    pub z_m: Option<f64>,
}

/// A stop's fitted pose and surface.
#[derive(Clone, Debug, PartialEq)]
pub struct Fitted {
    pub station: Station,
    /// The plane under the stop, from three or more points not on a line.
    pub plane: Option<StopPlane>,
    pub residuals: Vec<Residual>,
}

/// Why points do not fit.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum FitError {
    #[error(
        "{0} point(s) given: a stop's pose needs at least two measured points of its marking \
         (three or more also measure the road's surface)"
    )]
    TooFew(usize),
    #[error(
        "point {name:?} is {residual_mm:.1} mm from where the other points put it (tolerance \
         {tolerance_mm:.1} mm): check its chalk mark and its road_m on the job sheet, and \
         measure it again"
    )]
    Outlier {
        name: String,
        residual_mm: f64,
        tolerance_mm: f64,
    },
    #[error(
        "point {name:?}'s road height is {residual_mm:.1} mm off the road the other points \
         measure (tolerance {tolerance_mm:.1} mm): check that the tip touched the road there \
         (or its tip_gap_m) and measure it again"
    )]
    HeightOutlier {
        name: String,
        residual_mm: f64,
        tolerance_mm: f64,
    },
    #[error(
        "the road heights of points {names} do not lie on one road: one of them is up to \
         {residual_mm:.1} mm off the road the others measure (tolerance {tolerance_mm:.1} mm), \
         and the points cannot tell which; check that the tip touched the road at each (or \
         their tip_gap_m) and measure them again, or add a point away from the lines between \
         the others"
    )]
    Heights {
        names: String,
        residual_mm: f64,
        tolerance_mm: f64,
    },
    #[error(
        "points {a:?} and {b:?} are {road_m:.3} m apart on the marking but {base_m:.3} m apart \
         as measured ({diff_mm:.1} mm off, tolerance {tolerance_mm:.1} mm): one of them is \
         wrong; measure both again, or add a third point to tell which"
    )]
    Pair {
        a: String,
        b: String,
        road_m: f64,
        base_m: f64,
        diff_mm: f64,
        tolerance_mm: f64,
    },
    #[error(
        "points {a:?} and {b:?} are {dist_mm:.1} mm apart: too close to turn the stop by; \
         chalk points at least {min_m} m apart"
    )]
    TooClose {
        a: String,
        b: String,
        dist_mm: f64,
        min_m: f64,
    },
    #[error(
        "the measured road heights put the road {offset_mm:+.0} mm from the arm's base level at \
         its axis (at most ±{max_mm:.0} mm: the base frame's origin is on the road): check the \
         z of each point (base_m's third value, or tip_gap_m with encoders) and the arm's \
         vertical calibration"
    )]
    Offset { offset_mm: f64, max_mm: f64 },
    #[error(
        "the measured road heights make a plane sloped {slope_pct:.1} %: not a road (at most \
         {max_pct:.0} %); check the z of each point (base_m's third value: the road's height \
         under the tip, m)"
    )]
    Steep { slope_pct: f64, max_pct: f64 },
}

/// Points closer than this cannot fix the heading (m). assumed: a 2 mm
/// measurement over 0.5 m turns the stop by 0.23°, over the 0.1° the job
/// may be off; the job sheet lists points metres apart.
pub const MIN_SPAN_M: f64 = 0.5;

/// A fitted road more than this above or below the base's level at the
/// arm's axis (m) is a reading or calibration error: the base frame's
/// origin is on the road. assumed: a truck's load and tyres move its bed
/// by a few centimetres.
pub const MAX_AXIS_OFFSET_M: f64 = 0.05;

/// Three points span a plane only if their triangle is at least this
/// tall (m) over its longest side. assumed: 2 mm of height error over
/// 0.3 m tilts the plane by under 1 %.
pub const MIN_PLANE_WIDTH_M: f64 = 0.3;

/// The rigid motion road = R(φ)·base + t that best maps the measurements
/// onto the marking (least squares: the 2-D Kabsch solution), as a
/// station: the axis at t, heading φ + π/2.
fn pose_of(points: &[&Measured]) -> Station {
    let n = points.len() as f64;
    let mean = |f: &dyn Fn(&Measured) -> [f64; 2]| {
        let s = points.iter().fold([0.0, 0.0], |a, p| {
            let v = f(p);
            [a[0] + v[0], a[1] + v[1]]
        });
        [s[0] / n, s[1] / n]
    };
    let cb = mean(&|p| [p.base[0], p.base[1]]);
    let cr = mean(&|p| p.road);
    let (mut dot, mut cross) = (0.0, 0.0);
    for p in points {
        let b = [p.base[0] - cb[0], p.base[1] - cb[1]];
        let r = [p.road[0] - cr[0], p.road[1] - cr[1]];
        dot += b[0] * r[0] + b[1] * r[1];
        cross += b[0] * r[1] - b[1] * r[0];
    }
    let phi = cross.atan2(dot);
    let (s, c) = phi.sin_cos();
    Station {
        x_m: cr[0] - (c * cb[0] - s * cb[1]),
        y_m: cr[1] - (s * cb[0] + c * cb[1]),
        heading_rad: basr_robot::kinematics::wrap_pi(phi + std::f64::consts::FRAC_PI_2),
    }
}

/// Road distance between a point and its measurement mapped by `st`.
fn miss(st: &Station, p: &Measured) -> f64 {
    let r = st.base_to_road([p.base[0], p.base[1]]);
    (r[0] - p.road[0]).hypot(r[1] - p.road[1])
}

/// The least-squares plane z = c0 + cx·x + cy·y through the measured
/// heights, if the points span one.
fn plane_of(stop: usize, points: &[&Measured]) -> Option<StopPlane> {
    if points.len() < 3 || !spans_plane(points) {
        return None;
    }
    // Normal equations about the centroid (well conditioned).
    let n = points.len() as f64;
    let cx = points.iter().map(|p| p.base[0]).sum::<f64>() / n;
    let cy = points.iter().map(|p| p.base[1]).sum::<f64>() / n;
    let cz = points.iter().map(|p| p.base[2]).sum::<f64>() / n;
    let (mut sxx, mut sxy, mut syy, mut sxz, mut syz) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for p in points {
        let (x, y, z) = (p.base[0] - cx, p.base[1] - cy, p.base[2] - cz);
        sxx += x * x;
        sxy += x * y;
        syy += y * y;
        sxz += x * z;
        syz += y * z;
    }
    let det = sxx * syy - sxy * sxy;
    let dz_dx = (sxz * syy - syz * sxy) / det;
    let dz_dy = (syz * sxx - sxz * sxy) / det;
    Some(StopPlane {
        stop,
        z_m: cz - dz_dx * cx - dz_dy * cy,
        dz_dx,
        dz_dy,
    })
}

/// Whether some three of the points make a triangle at least
/// [`MIN_PLANE_WIDTH_M`] tall over its longest side.
fn spans_plane(points: &[&Measured]) -> bool {
    let xy = |p: &Measured| [p.base[0], p.base[1]];
    let n = points.len();
    for i in 0..n {
        for j in i + 1..n {
            for k in j + 1..n {
                let (a, b, c) = (xy(points[i]), xy(points[j]), xy(points[k]));
                let area2 = ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])).abs();
                let longest = [(a, b), (b, c), (c, a)]
                    .iter()
                    .map(|(p, q)| (p[0] - q[0]).hypot(p[1] - q[1]))
                    .fold(0.0, f64::max);
                if longest > 0.0 && area2 / longest >= MIN_PLANE_WIDTH_M {
                    return true;
                }
            }
        }
    }
    false
}

/// Fit stop `stop` (counted from 1) to `points`; a point further than
/// `tolerance_m` from where the others put it is refused by name.
pub fn fit(stop: usize, points: &[Measured], tolerance_m: f64) -> Result<Fitted, FitError> {
    if points.len() < 2 {
        return Err(FitError::TooFew(points.len()));
    }
    let all: Vec<&Measured> = points.iter().collect();
    let span = widest_pair(&all);
    if span.2 < MIN_SPAN_M {
        return Err(FitError::TooClose {
            a: all[span.0].name.clone(),
            b: all[span.1].name.clone(),
            dist_mm: span.2 * 1e3,
            min_m: MIN_SPAN_M,
        });
    }
    let st = pose_of(&all);
    // Each point against where the others put it (with three or more; two
    // can only be checked against each other): a point that pulls the fit
    // its way hides half its miss in the fit with it.
    let worst = if all.len() >= 3 {
        (0..all.len())
            .map(|k| {
                let rest = others(&all, k);
                miss(&pose_of(&rest), all[k])
            })
            .fold(0.0, f64::max)
    } else {
        all.iter().map(|p| miss(&st, p)).fold(0.0, f64::max)
    };
    if worst > tolerance_m {
        return Err(culprit(&all, tolerance_m));
    }
    // Each height against the plane the others measure, where the others
    // measure one (four points or more): one height misread by 35 mm
    // tilted the fitted road to 5 % where it was 2 % and the job said
    // READY (the issue-29 audit).
    if let Some(e) = height_outlier(&all, tolerance_m) {
        return Err(e);
    }
    let plane = plane_of(stop, &all);
    if let Some(p) = &plane {
        if p.z_m.abs() > MAX_AXIS_OFFSET_M {
            return Err(FitError::Offset {
                offset_mm: p.z_m * 1e3,
                max_mm: MAX_AXIS_OFFSET_M * 1e3,
            });
        }
        let slope = p.dz_dx.hypot(p.dz_dy);
        if slope > basr_job::road::MAX_CROSS_SLOPE {
            return Err(FitError::Steep {
                slope_pct: slope * 100.0,
                max_pct: basr_job::road::MAX_CROSS_SLOPE * 100.0,
            });
        }
    }
    let residuals = all
        .iter()
        .map(|p| Residual {
            name: p.name.clone(),
            xy_m: miss(&st, p),
            z_m: plane
                .as_ref()
                .map(|pl| p.base[2] - pl.z_at([p.base[0], p.base[1]])),
        })
        .collect();
    Ok(Fitted {
        station: st,
        plane,
        residuals,
    })
}

/// A height more than `tolerance_m` off the plane the other points
/// measure, when some is: the point without which the others agree best
/// (as [`culprit`] names a point off on the road), when they agree within
/// the tolerance and less than half as well without any other point; else
/// the set (four points cannot tell: any three lie on their plane). None
/// with fewer than four points, or where the others span no plane.
fn height_outlier(all: &[&Measured], tolerance_m: f64) -> Option<FitError> {
    if all.len() < 4 {
        return None;
    }
    // per point: how well the others agree with their plane, and its
    // height off that plane
    let off: Vec<(usize, f64, f64)> = (0..all.len())
        .filter_map(|k| {
            let rest = others(all, k);
            let pl = plane_of(0, &rest)?;
            let dz = |p: &Measured| (p.base[2] - pl.z_at([p.base[0], p.base[1]])).abs();
            let agree = rest.iter().map(|p| dz(p)).fold(0.0, f64::max);
            Some((k, agree, dz(all[k])))
        })
        .collect();
    let worst = off.iter().map(|o| o.2).fold(0.0, f64::max);
    if worst <= tolerance_m {
        return None;
    }
    // The one without which the others agree best, when they agree within
    // the tolerance and clearly better than without any other point.
    let mut by_agree = off.clone();
    by_agree.sort_by(|a, b| a.1.total_cmp(&b.1));
    if let [(k, best, dz), (_, next, _), ..] = by_agree[..] {
        if best <= tolerance_m && 2.0 * best < next {
            return Some(FitError::HeightOutlier {
                name: all[k].name.clone(),
                residual_mm: dz * 1e3,
                tolerance_mm: tolerance_m * 1e3,
            });
        }
    }
    let named: Vec<String> = all.iter().map(|p| format!("{:?}", p.name)).collect();
    Some(FitError::Heights {
        names: named.join(", "),
        residual_mm: worst * 1e3,
        tolerance_mm: tolerance_m * 1e3,
    })
}

/// Every point of `all` but the `k`th.
fn others<'a>(all: &[&'a Measured], k: usize) -> Vec<&'a Measured> {
    (0..all.len()).filter(|&i| i != k).map(|i| all[i]).collect()
}

/// The two points furthest apart (indices) and their base-frame distance.
fn widest_pair(points: &[&Measured]) -> (usize, usize, f64) {
    let mut best = (0, 1, 0.0);
    for i in 0..points.len() {
        for j in i + 1..points.len() {
            let (a, b) = (&points[i].base, &points[j].base);
            let d = (a[0] - b[0]).hypot(a[1] - b[1]);
            if d > best.2 {
                best = (i, j, d);
            }
        }
    }
    best
}

/// The point to blame when the fit misses by more than the tolerance: the
/// one without which the others agree best, with its distance from where
/// they put it. Two points cannot say which is wrong: their distances
/// disagree.
fn culprit(all: &[&Measured], tolerance_m: f64) -> FitError {
    if all.len() == 2 {
        let (a, b) = (all[0], all[1]);
        let road_m = (a.road[0] - b.road[0]).hypot(a.road[1] - b.road[1]);
        let base_m = (a.base[0] - b.base[0]).hypot(a.base[1] - b.base[1]);
        return FitError::Pair {
            a: a.name.clone(),
            b: b.name.clone(),
            road_m,
            base_m,
            diff_mm: (road_m - base_m).abs() * 1e3,
            tolerance_mm: tolerance_m * 1e3,
        };
    }
    let mut best: Option<(f64, usize, f64)> = None;
    for k in 0..all.len() {
        let rest = others(all, k);
        let st = pose_of(&rest);
        let agree = rest.iter().map(|p| miss(&st, p)).fold(0.0, f64::max);
        if best.is_none_or(|(a, _, _)| agree < a) {
            best = Some((agree, k, miss(&st, all[k])));
        }
    }
    let (_, k, off) = best.unwrap_or((0.0, 0, 0.0));
    FitError::Outlier {
        name: all[k].name.clone(),
        residual_mm: off * 1e3,
        tolerance_mm: tolerance_m * 1e3,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn truth() -> Station {
        Station {
            x_m: 0.25,
            y_m: 4.27,
            heading_rad: -std::f64::consts::FRAC_PI_2 + 2.5f64.to_radians(),
        }
    }

    /// Points of the marking measured from `st` on a plane.
    fn measured(st: &Station, plane: &StopPlane, road: &[[f64; 2]]) -> Vec<Measured> {
        road.iter()
            .enumerate()
            .map(|(i, r)| {
                let b = st.road_to_base(*r);
                Measured {
                    name: format!("p{}", i + 1),
                    road: *r,
                    base: [b[0], b[1], plane.z_at(b)],
                }
            })
            .collect()
    }

    fn tilted() -> StopPlane {
        StopPlane {
            stop: 1,
            z_m: 0.004,
            dz_dx: 0.02,
            dz_dy: -0.005,
        }
    }

    const ROAD: [[f64; 2]; 3] = [[-1.0, 0.0], [1.0, 0.0], [0.0, 2.4]];

    #[test]
    fn exact_points_give_the_pose_and_the_plane() {
        let f = fit(1, &measured(&truth(), &tilted(), &ROAD), 0.01).unwrap();
        let t = truth();
        assert!((f.station.x_m - t.x_m).abs() < 1e-12);
        assert!((f.station.y_m - t.y_m).abs() < 1e-12);
        assert!((f.station.heading_rad - t.heading_rad).abs() < 1e-12);
        let p = f.plane.unwrap();
        assert!((p.dz_dx - 0.02).abs() < 1e-12 && (p.dz_dy + 0.005).abs() < 1e-12);
        assert!(f.residuals.iter().all(|r| r.xy_m < 1e-12));
    }

    #[test]
    fn two_points_give_the_pose_without_a_plane() {
        let f = fit(1, &measured(&truth(), &tilted(), &ROAD[..2]), 0.01).unwrap();
        assert!(f.plane.is_none());
        assert!((f.station.heading_rad - truth().heading_rad).abs() < 1e-12);
    }

    /// The reference points' usual spread: a word's four corners, and a
    /// fifth off the lines between them.
    const CORNERS: [[f64; 2]; 5] = [[-1.5, 0.0], [1.5, 0.0], [1.5, 2.4], [-1.5, 2.4], [0.4, 0.8]];

    /// One road height misread by 35 mm: four points refuse the set (any
    /// three lie on their plane, so they cannot tell which), five name it;
    /// five whose fifth lies on a line between two others cannot tell
    /// either.
    #[test]
    fn a_misread_height_is_refused() {
        let mut four = measured(&truth(), &tilted(), &CORNERS[..4]);
        four[2].base[2] += 0.035;
        assert!(
            matches!(fit(1, &four, 0.01), Err(FitError::Heights { .. })),
            "{:?}",
            fit(1, &four, 0.01)
        );
        let mut five = measured(&truth(), &tilted(), &CORNERS);
        five[2].base[2] += 0.035;
        match fit(1, &five, 0.01) {
            Err(FitError::HeightOutlier {
                name, residual_mm, ..
            }) => {
                assert_eq!(name, "p3");
                assert!((residual_mm - 35.0).abs() < 0.5, "{residual_mm}");
            }
            other => panic!("{other:?}"),
        }
        let mut centred = measured(
            &truth(),
            &tilted(),
            &[[-1.5, 0.0], [1.5, 0.0], [1.5, 2.4], [-1.5, 2.4], [0.0, 1.2]],
        );
        centred[2].base[2] += 0.035;
        match fit(1, &centred, 0.01) {
            Err(FitError::Heights { names, .. }) => {
                assert!(names.contains("p3") && names.contains("p1"), "{names}")
            }
            other => panic!("{other:?}"),
        }
        // Three points always lie on their plane: nothing to check (the
        // plane they give may still be refused, as too far off the axis).
        let mut three = measured(&truth(), &tilted(), &CORNERS[..3]);
        three[2].base[2] += 0.035;
        assert!(!matches!(
            fit(1, &three, 0.01),
            Err(FitError::Heights { .. } | FitError::HeightOutlier { .. })
        ));
    }

    /// Heights read within ±2 mm (the noise) pass the check at the
    /// 10 mm tolerance, every time, on four and five points.
    #[test]
    fn heights_within_two_millimetres_pass() {
        let mut seed = 12345u64;
        let mut noise = move || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0) * 0.002
        };
        for n in [4, 5] {
            for _ in 0..500 {
                let mut pts = measured(&truth(), &tilted(), &CORNERS[..n]);
                for p in &mut pts {
                    p.base[2] += noise();
                }
                assert!(fit(1, &pts, 0.01).is_ok(), "{:?}", fit(1, &pts, 0.01));
            }
        }
    }

    #[test]
    fn an_outlier_is_named_with_its_distance() {
        let mut pts = measured(
            &truth(),
            &tilted(),
            &[[-1.0, 0.0], [1.0, 0.0], [0.0, 2.4], [0.5, 1.2]],
        );
        pts[2].base[0] += 0.15;
        match fit(1, &pts, 0.01) {
            Err(FitError::Outlier {
                name, residual_mm, ..
            }) => {
                assert_eq!(name, "p3");
                assert!((residual_mm - 150.0).abs() < 1.0, "{residual_mm}");
            }
            other => panic!("{other:?}"),
        }
        // Three points: still the moved one.
        let mut three = measured(&truth(), &tilted(), &ROAD);
        three[0].base[1] += 0.15;
        assert!(
            matches!(fit(1, &three, 0.01), Err(FitError::Outlier { name, .. }) if name == "p1")
        );
    }

    #[test]
    fn bad_sets_are_refused() {
        let pts = measured(&truth(), &tilted(), &ROAD);
        assert_eq!(fit(1, &pts[..1], 0.01), Err(FitError::TooFew(1)));
        let close = measured(&truth(), &tilted(), &[[0.0, 0.0], [0.1, 0.0]]);
        assert!(matches!(
            fit(1, &close, 0.01),
            Err(FitError::TooClose { .. })
        ));
        let mut two = measured(&truth(), &tilted(), &ROAD[..2]);
        two[1].base[0] += 0.05;
        assert!(matches!(fit(1, &two, 0.01), Err(FitError::Pair { .. })));
        let steep = StopPlane {
            dz_dx: 0.3,
            ..tilted()
        };
        assert!(matches!(
            fit(1, &measured(&truth(), &steep, &ROAD), 0.01),
            Err(FitError::Steep { .. })
        ));
        // Three points on a line measure no plane.
        let line = measured(&truth(), &tilted(), &[[-1.0, 0.0], [0.0, 0.0], [1.0, 0.0]]);
        assert!(fit(1, &line, 0.01).unwrap().plane.is_none());
    }
}
