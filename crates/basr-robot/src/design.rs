//! Dimensional design of a telescopic arm for prescribed points (seed 002's
//! aim: "designing telescopic manipulators with prescribed workspace
//! points"), by Newton–Raphson on the workspace equations.
//!
//! Input: tip points in the base frame and a template arm (DH angles,
//! offsets, head, joints). Unknowns: the stroke range [d_min, d_max]. The
//! tip is painted at zero tilt and at either tilt limit, so each point
//! gives three wrist points H (002's reference point). Each H needs the
//! stroke whose torus (eq. 1) passes through it; moved by the margin along
//! the direction that stroke grows fastest, the farthest H must lie on the
//! d_max torus and the nearest on the d_min torus — the workspace's cover
//! surfaces (002 §3). Newton–Raphson solves those two eq. 1's for
//! (d_min, d_max) with a finite-difference Jacobian; the result is then
//! checked point by point with the arm's inverse kinematics, which also
//! holds the envelope (eq. 5) side and every joint limit.
//!
//! Refused (no arm of the kind reaches them): points that are not finite,
//! below the road, spread over more azimuth than the base window, or
//! needing a boom that extends more than [`MAX_EXTENSION_RATIO`] times its
//! retracted length or longer than [`MAX_BOOM_M`].

use serde::Serialize;

use super::envelope::real_roots;
use super::kind::{turns_within, ArmKind};
use super::telescopic::{spray_axis, Telescopic};
use super::NozzlePose;

/// assumed: a telescopic boom of at most four sections, each no longer than
/// the retracted boom, extends to at most 4× its retracted length.
pub const MAX_EXTENSION_RATIO: f64 = 4.0;
/// assumed: a boom longer than 12 m does not travel on a road truck.
pub const MAX_BOOM_M: f64 = 12.0;
/// Iteration cap and convergence threshold of the Newton–Raphson.
pub const MAX_ITERATIONS: usize = 50;
pub const TOLERANCE: f64 = 1e-12;

/// Why a design was refused.
#[derive(Debug, thiserror::Error)]
pub enum DesignError {
    #[error("{0}")]
    Points(String),
    #[error("no telescopic arm of this template reaches the points: {0}")]
    Unreachable(String),
    #[error("Newton–Raphson did not converge in {iterations} iterations (residual {residual:.3e}); {hint}")]
    NoConvergence {
        iterations: usize,
        residual: f64,
        hint: String,
    },
}

/// One Newton–Raphson iteration, for the convergence table.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Iteration {
    pub iteration: usize,
    pub d_min_m: f64,
    pub d_max_m: f64,
    /// max |F| (eq. 1 values divided by A², dimensionless).
    pub residual: f64,
    /// 1-norm condition number of the Jacobian, ‖J‖₁·‖J⁻¹‖₁.
    pub jacobian_condition: f64,
}

/// A design and how it was found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Design {
    #[serde(skip)]
    pub robot: Telescopic,
    pub iterations: Vec<Iteration>,
    pub margin_m: f64,
    /// Per point: the stroke it needs at zero tilt and its margin on the road.
    pub points: Vec<PointCheck>,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PointCheck {
    pub point_m: [f64; 3],
    pub stroke_m: f64,
    pub reach_margin_m: f64,
}

/// Parse a points file: `points_m = [[x, y, z], ...]` (SPEC §8).
pub fn parse_points(text: &str, origin: &str) -> Result<Vec<[f64; 3]>, DesignError> {
    #[derive(serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    struct File {
        points_m: Vec<Vec<f64>>,
    }
    let bad = |m: String| DesignError::Points(format!("{origin}: {m}"));
    let f: File = toml::from_str(text).map_err(|e| {
        bad(format!(
            "{}; a points file holds `points_m = [[x, y, z], ...]` in metres, base frame",
            basr_io::one_line(e.message())
        ))
    })?;
    if f.points_m.is_empty() || f.points_m.len() > 1000 {
        return Err(bad(format!(
            "points_m holds {} points; give 1 to 1000",
            f.points_m.len()
        )));
    }
    let mut out = Vec::new();
    for (i, p) in f.points_m.iter().enumerate() {
        match p.as_slice() {
            [x, y, z] if x.is_finite() && y.is_finite() && z.is_finite() => out.push([*x, *y, *z]),
            _ => {
                return Err(bad(format!(
                    "points_m[{i}] must be three finite numbers [x, y, z] (got {p:?})"
                )))
            }
        }
    }
    Ok(out)
}

/// Wrist points H (base frame) of one tip point: zero tilt and both tilt
/// limits, the fan along the arm (tilt leans the spray axis along it).
fn wrists(t: &Telescopic, p: [f64; 3]) -> Vec<[f64; 3]> {
    let yaw = p[1].atan2(p[0]);
    let l = t.arm.nozzle_m;
    let tl = &t.joints.tilt_rad;
    [0.0, tl.min, tl.max]
        .iter()
        .map(|&beta| {
            let s = spray_axis(yaw, beta);
            [p[0] - l * s[0], p[1] - l * s[1], p[2] - l * s[2]]
        })
        .collect()
}

/// (r, z) of H in 002's frame (z from the first frame's origin).
fn rz(t: &Telescopic, h: [f64; 3]) -> [f64; 2] {
    [h[0].hypot(h[1]), h[2] - t.arm.base_height_m]
}

/// A stroke the arm can use to put H at `h`, and the piece of d around it
/// where eq. 1 is monotone (so Newton there cannot slide to another root).
#[derive(Clone, Copy, Debug)]
struct Usable {
    h: [f64; 3],
    stroke: f64,
    piece: [f64; 2],
}

/// The root of eq. 1 at `h` (a torus through H) whose θ1 and θ2 have turns
/// inside the template's limits, nearest `near`: eq. 1 also holds for the
/// boom reaching over the base axis (θ1 + π), outside the base window.
fn usable_stroke(t: &Telescopic, h: [f64; 3], near: f64) -> Option<Usable> {
    let [r, z] = rz(t, h);
    let q = t.dh().quartic(r, z);
    let top = 2.0 * MAX_BOOM_M;
    let j = &t.joints;
    let stroke = real_roots(&q, 0.0, top)
        .into_iter()
        .filter(|&d| {
            t.arm_at_stroke(h, d).is_some_and(|[t1, t2, _]| {
                !turns_within(t1, &j.base_rot_rad.limit()).is_empty()
                    && !turns_within(t2, &j.boom_rad.limit()).is_empty()
            })
        })
        .min_by(|a, b| (a - near).abs().total_cmp(&(b - near).abs()))?;
    let dq = super::envelope::poly_derivative(&q);
    let crit = real_roots(&dq, 0.0, top);
    let lo = crit
        .iter()
        .copied()
        .filter(|&c| c < stroke)
        .fold(0.0, f64::max);
    let hi = crit
        .iter()
        .copied()
        .filter(|&c| c > stroke)
        .fold(top, f64::min);
    Some(Usable {
        h,
        stroke,
        piece: [lo, hi],
    })
}

/// H moved by `m` in its (r, z) half-plane along the direction its usable
/// stroke grows fastest (None where no stroke is usable nearby).
fn offset(t: &Telescopic, h: [f64; 3], near: f64, m: f64) -> Option<Usable> {
    let [r, z] = rz(t, h);
    let az = h[1].atan2(h[0]);
    let at = |r: f64, z: f64| [r * az.cos(), r * az.sin(), z + t.arm.base_height_m];
    let s = |r: f64, z: f64| usable_stroke(t, at(r, z), near).map(|u| u.stroke);
    let e = 1e-6;
    let g = [s(r + e, z)? - s(r - e, z)?, s(r, z + e)? - s(r, z - e)?];
    let n = g[0].hypot(g[1]);
    if !(n.is_finite() && n > 0.0) {
        return usable_stroke(t, h, near);
    }
    usable_stroke(t, at(r + m * g[0] / n, z + m * g[1] / n), near)
}
/// Solve J·x = b (Gaussian elimination, partial pivoting). Written here:
/// the system is 2×2; a linear-algebra crate would add more than it saves.
fn solve(mut j: Vec<Vec<f64>>, mut b: Vec<f64>) -> Option<Vec<f64>> {
    let n = b.len();
    for c in 0..n {
        let p = (c..n).max_by(|&x, &y| j[x][c].abs().total_cmp(&j[y][c].abs()))?;
        if j[p][c].abs() < 1e-300 {
            return None;
        }
        j.swap(c, p);
        b.swap(c, p);
        for r in c + 1..n {
            let f = j[r][c] / j[c][c];
            let pivot = j[c].clone();
            for (v, p) in j[r][c..].iter_mut().zip(&pivot[c..]) {
                *v -= f * p;
            }
            b[r] -= f * b[c];
        }
    }
    let mut x = vec![0.0; n];
    for r in (0..n).rev() {
        let s: f64 = (r + 1..n).map(|k| j[r][k] * x[k]).sum();
        x[r] = (b[r] - s) / j[r][r];
    }
    Some(x)
}

/// ‖J‖₁·‖J⁻¹‖₁ (∞ when singular).
fn condition(j: &[Vec<f64>]) -> f64 {
    let n = j.len();
    let norm1 = |m: &[Vec<f64>]| {
        (0..n)
            .map(|c| (0..n).map(|r| m[r][c].abs()).sum::<f64>())
            .fold(0.0, f64::max)
    };
    let mut inv = vec![vec![0.0; n]; n];
    for c in 0..n {
        let mut e = vec![0.0; n];
        e[c] = 1.0;
        match solve(j.to_vec(), e) {
            Some(col) => (0..n).for_each(|r| inv[r][c] = col[r]),
            None => return f64::INFINITY,
        }
    }
    norm1(j) * norm1(&inv)
}

/// Design the stroke range of `template` so every point is reachable with
/// `margin_m` to spare.
pub fn design(
    template: &Telescopic,
    points: &[[f64; 3]],
    margin_m: f64,
) -> Result<Design, DesignError> {
    refuse_impossible(template, points)?;
    let (near, far) = extreme_wrists(template, points, margin_m)?;
    // F(x) for x = (d_min, d_max): eq. 1 at the margin-moved wrist points,
    // scaled by A² so the residual is dimensionless.
    let k = template.dh();
    let (near_rz, far_rz) = (rz(template, near.h), rz(template, far.h));
    let f = |x: &[f64]| -> Vec<f64> {
        let g = |p: [f64; 2], d: f64| k.torus(p[0], p[1], d) / k.coefficients(d).a.powi(2);
        vec![g(near_rz, x[0]), g(far_rz, x[1])]
    };
    let pieces = [near.piece, far.piece];
    // Start from the template's strokes, inside the monotone pieces.
    let inside = |v: f64, [lo, hi]: [f64; 2]| v.clamp(lo + 0.05 * (hi - lo), hi - 0.05 * (hi - lo));
    let mut x = vec![
        inside(template.joints.stroke_m.min, pieces[0]),
        inside(template.joints.stroke_m.max, pieces[1]),
    ];
    let mut table = Vec::new();
    for it in 0..=MAX_ITERATIONS {
        let fx = f(&x);
        let res = fx.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let h = 1e-7;
        let jac: Vec<Vec<f64>> = (0..2)
            .map(|r| {
                (0..2)
                    .map(|c| {
                        let (mut xp, mut xm) = (x.clone(), x.clone());
                        xp[c] += h;
                        xm[c] -= h;
                        (f(&xp)[r] - f(&xm)[r]) / (2.0 * h)
                    })
                    .collect()
            })
            .collect();
        table.push(Iteration {
            iteration: it,
            d_min_m: x[0],
            d_max_m: x[1],
            residual: res,
            jacobian_condition: condition(&jac),
        });
        if res < TOLERANCE {
            return finish(template, points, margin_m, x, table);
        }
        let Some(step) = solve(jac, fx.iter().map(|v| -v).collect()) else {
            break;
        };
        // Damped, and kept inside each unknown's monotone piece (a step
        // that leaves it goes halfway to the piece's end instead).
        let mut t = 1.0;
        let mut next = x.clone();
        for _ in 0..30 {
            next = (0..2)
                .map(|i| {
                    let v = x[i] + t * step[i];
                    let [lo, hi] = pieces[i];
                    if v <= lo {
                        0.5 * (x[i] + lo)
                    } else if v >= hi {
                        0.5 * (x[i] + hi)
                    } else {
                        v
                    }
                })
                .collect();
            let r = f(&next).iter().fold(0.0f64, |a, v| a.max(v.abs()));
            if r < res {
                break;
            }
            t *= 0.5;
        }
        x = next;
    }
    let residual = table.last().map_or(f64::NAN, |i| i.residual);
    Err(DesignError::NoConvergence {
        iterations: table.len(),
        residual,
        hint: "the Jacobian is singular or the points need strokes the torus family cannot give; \
               move the points or widen the template"
            .into(),
    })
}

/// Refusals that hold for every arm built on the template.
fn refuse_impossible(t: &Telescopic, points: &[[f64; 3]]) -> Result<(), DesignError> {
    for (i, p) in points.iter().enumerate() {
        if p[2] < 0.0 {
            return Err(DesignError::Unreachable(format!(
                "points_m[{i}] is {:.3} m below the road; the nozzle paints from above it (z ≥ 0)",
                -p[2]
            )));
        }
    }
    // The base window bounds the azimuths any arm of the template reaches.
    let mut az: Vec<f64> = points.iter().map(|p| p[1].atan2(p[0])).collect();
    az.sort_by(f64::total_cmp);
    let gaps = az.windows(2).map(|w| w[1] - w[0]).chain(std::iter::once(
        az[0] + std::f64::consts::TAU - az[az.len() - 1],
    ));
    let spread = std::f64::consts::TAU - gaps.fold(0.0, f64::max);
    let w = &t.joints.base_rot_rad;
    if spread > w.max - w.min {
        return Err(DesignError::Unreachable(format!(
            "the points spread over {:.1}° of azimuth round the base axis; the base turns {:.1}° \
             (joints.base_rot_rad of the template)",
            spread.to_degrees(),
            (w.max - w.min).to_degrees()
        )));
    }
    Ok(())
}

/// The nearest and farthest wrist points, moved by the margin.
fn extreme_wrists(
    t: &Telescopic,
    points: &[[f64; 3]],
    margin: f64,
) -> Result<(Usable, Usable), DesignError> {
    let mid = 0.5 * (t.joints.stroke_m.min + t.joints.stroke_m.max);
    let mut near: Option<Usable> = None;
    let mut far: Option<Usable> = None;
    for (i, p) in points.iter().enumerate() {
        for h in wrists(t, *p) {
            let (Some(lo), Some(hi)) = (offset(t, h, mid, -margin), offset(t, h, mid, margin))
            else {
                return Err(DesignError::Unreachable(format!(
                    "points_m[{i}]: no stroke up to {} m puts the wrist there with the base and boom \
                     joints in their ranges",
                    2.0 * MAX_BOOM_M
                )));
            };
            if near.is_none_or(|n| lo.stroke < n.stroke) {
                near = Some(lo);
            }
            if far.is_none_or(|f| hi.stroke > f.stroke) {
                far = Some(hi);
            }
        }
    }
    let (Some(n), Some(f)) = (near, far) else {
        return Err(DesignError::Points("no points".into()));
    };
    let (ns, fs) = (n.stroke, f.stroke);
    if fs > MAX_BOOM_M {
        return Err(DesignError::Unreachable(format!(
            "the farthest point needs a {fs:.2} m boom; a road truck carries at most {MAX_BOOM_M} m (assumed)"
        )));
    }
    if ns <= 0.0 || fs / ns > MAX_EXTENSION_RATIO {
        return Err(DesignError::Unreachable(format!(
            "the points need strokes from {ns:.2} m to {fs:.2} m, {:.1}× the shortest; a telescopic boom \
             extends to at most {MAX_EXTENSION_RATIO}× its retracted length (assumed, four sections)",
            fs / ns
        )));
    }
    Ok((n, f))
}

/// The designed robot, checked point by point with inverse kinematics.
fn finish(
    template: &Telescopic,
    points: &[[f64; 3]],
    margin_m: f64,
    x: Vec<f64>,
    iterations: Vec<Iteration>,
) -> Result<Design, DesignError> {
    let mut robot = template.clone();
    robot.joints.stroke_m.min = x[0];
    robot.joints.stroke_m.max = x[1];
    if let Some((field, why)) = robot.problems().into_iter().next() {
        return Err(DesignError::Unreachable(format!(
            "the solved arm is not valid: {field}: {why}"
        )));
    }
    let mut checks = Vec::new();
    for (i, p) in points.iter().enumerate() {
        let pose = NozzlePose {
            x_m: p[0],
            y_m: p[1],
            z_m: p[2],
            yaw_rad: 0.0,
            tilt_rad: 0.0,
        };
        let all = robot.ik(&pose).map_err(|e| {
            DesignError::Unreachable(format!(
                "points_m[{i}] is still out of reach with the solved strokes ({e}); the template's other joints bind"
            ))
        })?;
        let q = robot.nearest(&all, &robot.rest()).unwrap_or(all[0]);
        checks.push(PointCheck {
            point_m: *p,
            stroke_m: q[2],
            reach_margin_m: super::section::reach_margin(&robot, p[0], p[1], p[2]),
        });
    }
    Ok(Design {
        robot,
        iterations,
        margin_m,
        points: checks,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kind::TELESCOPIC_TOML;
    use crate::AnyRobot;

    fn template() -> Telescopic {
        match AnyRobot::from_toml_str(TELESCOPIC_TOML, "shipped").unwrap() {
            AnyRobot::Telescopic(t) => t,
            _ => unreachable!(),
        }
    }

    /// Four points across a 12 ft lane, 3 m behind the base.
    fn lane() -> Vec<[f64; 3]> {
        [-1.83, -0.61, 0.61, 1.83]
            .iter()
            .map(|&x| [x, 3.0, 0.15])
            .collect()
    }

    #[test]
    fn lane_points_converge_and_are_reachable() {
        let d = design(&template(), &lane(), 0.1).unwrap();
        let last = d.iterations.last().unwrap();
        assert!(last.residual < TOLERANCE);
        assert!(d.iterations.len() < 20, "{:?}", d.iterations);
        for c in &d.points {
            assert!(c.stroke_m >= d.robot.joints.stroke_m.min);
            assert!(c.stroke_m <= d.robot.joints.stroke_m.max);
        }
        // The designed strokes are tight: each is on a margin-moved point.
        assert!(d.robot.joints.stroke_m.max < template().joints.stroke_m.max);
    }

    #[test]
    fn impossible_sets_are_refused_with_why() {
        let t = template();
        let below = design(&t, &[[0.0, 3.0, -0.1]], 0.1)
            .unwrap_err()
            .to_string();
        assert!(below.contains("below the road"), "{below}");
        let around = design(
            &t,
            &[[0.0, 3.0, 0.1], [0.0, -3.0, 0.1], [3.0, 0.0, 0.1]],
            0.1,
        )
        .unwrap_err()
        .to_string();
        assert!(around.contains("azimuth"), "{around}");
        let spread = design(&t, &[[0.0, 1.0, 0.1], [0.0, 11.0, 0.1]], 0.1)
            .unwrap_err()
            .to_string();
        assert!(spread.contains("retracted length"), "{spread}");
        let far = design(&t, &[[0.0, 30.0, 0.1]], 0.1)
            .unwrap_err()
            .to_string();
        assert!(far.contains("boom"), "{far}");
    }

    #[test]
    fn points_file_errors_name_the_point() {
        assert_eq!(
            parse_points("points_m = [[1, 2, 3.5]]", "p").unwrap(),
            [[1.0, 2.0, 3.5]]
        );
        let e = parse_points("points_m = [[1, 2]]", "p.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("points_m[0]"), "{e}");
        let e = parse_points("points = []", "p.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("points_m"), "{e}");
    }
}
