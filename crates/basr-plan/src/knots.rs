//! Rungs to knots: fan direction, width, nozzle height and painting speed per rung (001 eq. 2.4–2.6), and splitting wide strokes into passes.
//!
//! A rung joins opposing points of a stroke's two edges (001 fig. 2.8). Its
//! `left` end is the point on the stroke's left edge as the font gives it;
//! nothing here assumes which way the nozzle travels. The fan axis ψ points
//! from `left` to `right` (eq. 2.4 with point 1 = left), and β > 0 leans the
//! fan towards +ψ (SPEC §2); see `tilt` for the geometry.

use kurbo::{Point, Vec2};

pub use super::rungs::Rung;
use super::tilt;
pub use super::tilt::TiltMethod;

/// Rungs narrower than this (m) have no direction of their own: they take
/// the fan direction of the nearest proper rung (e.g. a pointed stroke end).
const DEGENERATE_WIDTH_M: f64 = 1e-9;

pub use basr_robot::paint_law::{HeightLaw, PaintLaw};

/// One knot: where the nozzle is and how it is oriented and moving at one rung.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Knot {
    /// Rung midpoint (road frame).
    pub mid: Point,
    /// Nozzle tip's xy after the tilt correction (001 eq. 2.21–2.23); `mid` when β = 0.
    pub tip: Point,
    /// Nozzle tip height above the road (eq. 2.5 or the calibrated law, lowered by tilt per eq. 2.24, then clamped to the reach).
    pub z_m: f64,
    /// Fan direction ψ (road frame, eq. 2.4), from the rung's left to its right end.
    pub yaw_rad: f64,
    /// Tilt β within ±max tilt; β > 0 leans the fan towards +ψ.
    pub tilt_rad: f64,
    /// Rung length (the stroke width being painted).
    pub width_m: f64,
    /// Length of the fan's footprint on the road: `width_m`, or more where
    /// the height was clamped up to the minimum.
    pub fan_width_m: f64,
    /// The fan turned this far off the rung's direction ψ (rad; `yaw_rad`
    /// includes it): a footprint longer than the rung, turned, covers the
    /// rung's width across the stroke (`narrow::turn_narrow`). Zero unless
    /// the height was clamped.
    pub turn_rad: f64,
    /// Stroke width painted across the direction of travel (m): the stroke
    /// area the rung sweeps per metre of nozzle (tip) travel, over the tiles
    /// on either side, so that speed × swept width = k wherever the fan spans
    /// the rung. It equals `width_m` where rungs stand square to a straight
    /// path and the tip follows the midpoint, and is less where rungs lean
    /// (the outer edge of a curve is longer than the inner one, so opposing
    /// points drift apart).
    pub swept_width_m: f64,
    /// Nozzle speed along the tip path that lays the target film: each tile
    /// between two rungs is crossed in (area the fan sweeps over it) / k
    /// (eq. 2.6 made physical, see [`pace`]).
    pub speed_mps: f64,
}

impl Knot {
    /// Width of road across the stroke the fan covers: its footprint's
    /// length, foreshortened by its turn off the rung.
    pub fn covered_width_m(&self) -> f64 {
        self.fan_width_m * self.turn_rad.cos()
    }

    /// A test's knot at road (x, y): fan along +x, untilted, 0.2 m up,
    /// a 0.1 m stroke painted at 0.2 m/s.
    #[cfg(test)]
    pub(crate) fn at(x: f64, y: f64) -> Knot {
        Knot {
            mid: Point::new(x, y),
            tip: Point::new(x, y),
            z_m: 0.2,
            yaw_rad: 0.0,
            tilt_rad: 0.0,
            width_m: 0.1,
            fan_width_m: 0.1,
            turn_rad: 0.0,
            swept_width_m: 0.1,
            speed_mps: 0.2,
        }
    }
}

/// A knot whose nozzle height was raised to the vertical joint's minimum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeightClamp {
    /// Rung index in the input.
    pub rung: usize,
    /// Height the rung needed (m).
    pub wanted_m: f64,
    /// Height used (m): the minimum.
    pub used_m: f64,
}

/// Knots of one stroke (or one pass) and what the tilt did to the paint balance.
#[derive(Clone, Debug, PartialEq)]
pub struct KnotPlan {
    pub knots: Vec<Knot>,
    /// Range (min, max) of the area ratios U in percent over all cells without tilt (001 eq. 2.7–2.8).
    pub u_before: (f64, f64),
    /// The same with the chosen tilts.
    pub u_after: (f64, f64),
    /// Knots whose nozzle height was clamped up to the minimum (the fan paints wider than the rung there).
    pub clamped: Vec<HeightClamp>,
}

/// Errors of the rung → knot stage.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PlanError {
    #[error(transparent)]
    BadLaw(#[from] basr_robot::paint_law::BadLaw),
    #[error("a stroke with no rungs cannot be painted")]
    NoRungs,
    #[error("rung {rung} has a coordinate that is not a finite number")]
    NotFinite { rung: usize },
    #[error("all {count} rungs of the stroke have zero width, so the fan has no direction")]
    Degenerate { count: usize },
    #[error(
        "rung {rung} is {width_m:.3} m wide and needs the nozzle {height_m:.3} m above the road, above the vertical joint's reach of {max_height_m:.3} m: split the stroke into passes no wider than {max_width_m:.3} m (split_passes)"
    )]
    TooWide {
        rung: usize,
        width_m: f64,
        height_m: f64,
        max_height_m: f64,
        max_width_m: f64,
    },
    #[error("passes: max width {max_width_m} m must be positive and larger than the overlap {overlap_m} m (≥ 0)")]
    BadPassSplit { max_width_m: f64, overlap_m: f64 },
}

/// Rungs → knots: per rung ψ (eq. 2.4), width, height (eq. 2.5 or the
/// calibrated law), tilt β by `method` within ±`max_tilt_rad` (001 §2.5),
/// the corrected nozzle position (eq. 2.21–2.24) and the painting speed
/// v = k / w (eq. 2.6).
///
/// Heights below the vertical joint's minimum are clamped and listed; the
/// fan then covers more than the rung and the speed is set by the width it
/// covers, so the film stays the target. A rung needing more than the
/// maximum height is an error: split the stroke with `passes::split_passes` first.
/// Zero-width rungs (a pointed stroke end) take the fan direction of the
/// nearest rung with width.
pub fn knots(
    rungs: &[Rung],
    law: &PaintLaw,
    method: TiltMethod,
    max_tilt_rad: f64,
) -> Result<KnotPlan, PlanError> {
    // the tilt's rate is not limited, so nothing is smoothed
    knots_within(rungs, law, method, max_tilt_rad, f64::INFINITY, 0)
}

/// [`knots`] with the tilt's change along the pass kept within
/// `max_tilt_rate_rps` at eq. 2.6's painting speed: where the rungs ask
/// the tilt to change faster (a bowl's curve running into a straight run,
/// where the quadrilateral balance falls from its limit to zero within a
/// few rungs), the change is spread evenly to both sides (`turn::spread_steps`),
/// so the time law need not slow the nozzle for the tilt joint, its
/// corners rounded by `tilt_smoothing` rounds (`tuning::Rates`).
pub fn knots_within(
    rungs: &[Rung],
    law: &PaintLaw,
    method: TiltMethod,
    max_tilt_rad: f64,
    max_tilt_rate_rps: f64,
    tilt_smoothing: usize,
) -> Result<KnotPlan, PlanError> {
    law.validate()?;
    if !(max_tilt_rad.is_finite() && max_tilt_rad >= 0.0) {
        return Err(PlanError::BadLaw(basr_robot::paint_law::BadLaw {
            field: "max_tilt_rad",
            value: max_tilt_rad,
            why: "must be a finite angle ≥ 0",
        }));
    }
    if rungs.is_empty() {
        return Err(PlanError::NoRungs);
    }
    for (k, r) in rungs.iter().enumerate() {
        if !(r.left.is_finite() && r.right.is_finite()) {
            return Err(PlanError::NotFinite { rung: k });
        }
    }
    let yaws = yaws(rungs)?;
    let fan = law.fan_angle_rad;
    let max_width = law.max_width_m();
    for (k, r) in rungs.iter().enumerate() {
        let h = law.height_for_width(r.width());
        // Tiny tolerance so a rung exactly at the reach (e.g. from split_passes) passes.
        if h > law.max_height_m * (1.0 + 1e-9) {
            return Err(PlanError::TooWide {
                rung: k,
                width_m: r.width(),
                height_m: h,
                max_height_m: law.max_height_m,
                max_width_m: max_width,
            });
        }
    }

    let mut betas = tilt::tilts(rungs, method, fan, max_tilt_rad);
    if max_tilt_rate_rps.is_finite() && max_tilt_rate_rps > 0.0 && rungs.len() > 2 {
        let min_width = law.width_at_height(law.min_height_m);
        let step: Vec<f64> = rungs
            .windows(2)
            .map(|r| {
                let ds = (r[1].mid() - r[0].mid()).hypot().max(MIN_TIP_STEP_M);
                let w = 0.5 * (r[0].width() + r[1].width());
                max_tilt_rate_rps * ds * w.max(min_width) / law.k_m2ps
            })
            .collect();
        super::turn::spread_smooth_steps(&mut betas, &step, tilt_smoothing);
    }
    let u_before = tilt::u_range(&tilt::u_ratios(rungs, &[], fan));
    let u_after = tilt::u_range(&tilt::u_ratios(rungs, &betas, fan));

    let mut clamped = Vec::new();
    let mut out = Vec::with_capacity(rungs.len());
    for (k, (r, (&yaw, &beta))) in rungs.iter().zip(yaws.iter().zip(betas.iter())).enumerate() {
        let w = r.width();
        let mid = r.mid();
        let dir = Vec2::from_angle(yaw);
        // Eq. 2.21–2.23: the foot moves against the lean so the fan still spans the rung.
        let tip = mid - tilt::foot_offset(w, beta, fan) * dir;
        // Eq. 2.24 relative to eq. 2.5; applied to the calibrated law too
        // (assumed: a real fan's footprint scales with height as the ideal one).
        let factor = tilt::height_factor(beta, fan);
        let wanted = law.height_for_width(w) * factor;
        let (z, fan_width) = if wanted < law.min_height_m {
            clamped.push(HeightClamp {
                rung: k,
                wanted_m: wanted,
                used_m: law.min_height_m,
            });
            (
                law.min_height_m,
                law.width_at_height(law.min_height_m / factor).max(w),
            )
        } else {
            (wanted, w)
        };
        out.push(Knot {
            mid,
            tip,
            z_m: z,
            yaw_rad: yaw,
            tilt_rad: beta,
            width_m: w,
            fan_width_m: fan_width,
            turn_rad: 0.0,
            swept_width_m: w,
            speed_mps: law.k_m2ps / fan_width, // 001 eq. 2.6
        });
    }
    pace(rungs, &mut out, law.k_m2ps);
    Ok(KnotPlan {
        knots: out,
        u_before,
        u_after,
        clamped,
    })
}

/// Smallest tip step (m) the time law parameterises by; `plan::compile`
/// floors each step of the arc length the same way, so a rung turning in
/// place still takes its time.
pub const MIN_TIP_STEP_M: f64 = 1e-4;

/// Set each knot's painting speed so that every tile between two rungs gets
/// the target film, and its swept width.
///
/// Eq. 2.6 (v = k / w) assumes the rung stands square to the path. On a
/// curve the opposing edge points drift apart: the rung leans, the road it
/// sweeps per metre of travel is less than its length, and v = k / w lays up
/// to twice the film (the seed's tile areas, fig. 2.11, show the same
/// thing). Here the fan's footprint (`fan_width_m` long, centred on the
/// rung's midpoint, along ψ) is swept from knot to knot; tile j is crossed
/// in Δt_j = A_fan,j / k, so the paint volume flow × efficiency × Δt_j
/// covers the swept area at the target film. The speed at a knot is the tip
/// travel over the time of its two tiles. Where a tile sweeps nothing (two
/// coincident rungs), eq. 2.6 stands.
pub fn pace(rungs: &[Rung], ks: &mut [Knot], k_m2ps: f64) {
    let n = ks.len().min(rungs.len());
    if n < 2 || k_m2ps.is_nan() || k_m2ps <= 0.0 {
        return;
    }
    let footprint = |k: &Knot| {
        let half = 0.5 * k.fan_width_m * Vec2::from_angle(k.yaw_rad);
        (k.mid - half, k.mid + half)
    };
    // Per tile: fan-swept area, stroke-swept area, midpoint and tip travel.
    let tiles: Vec<(f64, f64, f64, f64)> = (0..n - 1)
        .map(|j| {
            let (a0, b0) = footprint(&ks[j]);
            let (a1, b1) = footprint(&ks[j + 1]);
            let fan = swept_area(a0, b0, a1, b1);
            let (r0, r1) = (&rungs[j], &rungs[j + 1]);
            let stroke = swept_area(r0.left, r0.right, r1.left, r1.right);
            let mid = (ks[j + 1].mid - ks[j].mid).hypot();
            let tip = (ks[j + 1].tip - ks[j].tip).hypot().max(MIN_TIP_STEP_M);
            (fan, stroke, mid, tip)
        })
        .collect();
    for (i, knot) in ks.iter_mut().enumerate().take(n) {
        let around = &tiles[i.saturating_sub(1)..i.min(n - 2) + 1];
        let (fan, stroke, mid, tip) = around.iter().fold((0.0, 0.0, 0.0, 0.0), |acc, t| {
            (acc.0 + t.0, acc.1 + t.1, acc.2 + t.2, acc.3 + t.3)
        });
        // Below a square micrometre nothing is swept: keep eq. 2.6.
        if fan > 1e-12 && fan.is_finite() {
            knot.speed_mps = tip * k_m2ps / fan;
        }
        if mid > 1e-9 && stroke.is_finite() {
            knot.swept_width_m = stroke / tip;
        }
    }
}

/// Area (m²) swept by a segment whose ends move in straight lines from
/// (`p0`, `q0`) to (`p1`, `q1`), each point of the segment keeping its
/// fraction along it. The map (u, t) ↦ lerp(lerp(p0, q0, u), lerp(p1, q1, u), t)
/// has a Jacobian bilinear in u and t; where it keeps one sign the area is
/// the mean of its four corner values (exact), else it is integrated on a
/// 16 × 16 midpoint grid (a rung turning about a point inside itself).
pub fn swept_area(p0: Point, q0: Point, p1: Point, q1: Point) -> f64 {
    let (a, b) = (q0 - p0, (q1 - p1) - (q0 - p0));
    let (c, d) = (p1 - p0, (q1 - q0) - (p1 - p0));
    // J(u, t) = cross(a + t b, c + u d)
    let jac = |u: f64, t: f64| (a + t * b).cross(c + u * d);
    let corners = [jac(0.0, 0.0), jac(1.0, 0.0), jac(0.0, 1.0), jac(1.0, 1.0)];
    if corners.iter().all(|&j| j >= 0.0) || corners.iter().all(|&j| j <= 0.0) {
        return (corners.iter().sum::<f64>() / 4.0).abs();
    }
    const N: usize = 16;
    let h = 1.0 / N as f64;
    let mut sum = 0.0;
    for iu in 0..N {
        for it in 0..N {
            sum += jac((iu as f64 + 0.5) * h, (it as f64 + 0.5) * h).abs();
        }
    }
    sum * h * h
}

/// ψ per rung; degenerate rungs borrow the nearest proper rung's direction.
fn yaws(rungs: &[Rung]) -> Result<Vec<f64>, PlanError> {
    let proper: Vec<usize> = (0..rungs.len())
        .filter(|&k| rungs[k].width() > DEGENERATE_WIDTH_M)
        .collect();
    if proper.is_empty() {
        return Err(PlanError::Degenerate { count: rungs.len() });
    }
    Ok((0..rungs.len())
        .map(|k| {
            let nearest = match proper.binary_search(&k) {
                Ok(i) => proper[i],
                Err(0) => proper[0],
                Err(i) if i == proper.len() => proper[i - 1],
                // Ties go to the earlier rung (deterministic).
                Err(i) => {
                    if k - proper[i - 1] <= proper[i] - k {
                        proper[i - 1]
                    } else {
                        proper[i]
                    }
                }
            };
            rungs[nearest].yaw()
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    const FAN: f64 = 63.5 * PI / 180.0; // 001 App. A

    fn law() -> PaintLaw {
        PaintLaw {
            fan_angle_rad: FAN,
            k_m2ps: 0.4e-3 / 60.0 * 0.9 / 0.38e-3, // SPEC §4 assumed: 0.4 L/min, 0.9, 0.38 mm
            height: HeightLaw::Geometric,
            min_height_m: 0.05,
            max_height_m: 0.33,
        }
    }

    fn straight(width: f64, n: usize) -> Vec<Rung> {
        (0..n)
            .map(|k| {
                let y = 0.02 * k as f64;
                Rung {
                    left: Point::new(0.0, y),
                    right: Point::new(width, y),
                }
            })
            .collect()
    }

    #[test]
    fn swept_area_of_simple_motions() {
        let p = Point::new;
        // A 1 m segment moved 0.5 m square to itself sweeps 0.5 m².
        let a = swept_area(p(0.0, 0.0), p(1.0, 0.0), p(0.0, 0.5), p(1.0, 0.5));
        assert!((a - 0.5).abs() < 1e-12, "{a}");
        // Slid along itself it sweeps nothing new.
        let a = swept_area(p(0.0, 0.0), p(1.0, 0.0), p(0.3, 0.0), p(1.3, 0.0));
        assert!(a.abs() < 1e-12, "{a}");
        // Turned by θ about its midpoint (ends on straight chords): two
        // triangles of legs ½ and chord ½·2 sin(θ/2), i.e. ¼ sin θ in all.
        let th: f64 = 0.2;
        let (c, s) = (0.5 * th.cos(), 0.5 * th.sin());
        let a = swept_area(p(-0.5, 0.0), p(0.5, 0.0), p(-c, -s), p(c, s));
        assert!((a - 0.25 * th.sin()).abs() < 2e-3 * a, "{a}");
    }

    #[test]
    fn leaning_rungs_are_paced_by_the_road_they_sweep() {
        // A straight band 0.1 m wide whose rungs lean: each right point sits
        // 0.1 m further along than its left point. Rungs are 0.141 m long but
        // sweep only 0.1 m of road per metre; eq. 2.6 with the rung length
        // would lay 1.41× the film. Untilted, so tip = mid.
        let l = law();
        let rungs: Vec<Rung> = (0..40)
            .map(|k| {
                let x = 0.02 * k as f64;
                Rung {
                    left: Point::new(x, 0.0),
                    right: Point::new(x + 0.1, 0.1),
                }
            })
            .collect();
        let plan = knots(&rungs, &l, TiltMethod::None, 0.0).unwrap();
        for k in &plan.knots {
            assert!((k.width_m - 0.1 * 2f64.sqrt()).abs() < 1e-12);
            assert!((k.swept_width_m - 0.1).abs() < 1e-9, "{}", k.swept_width_m);
            assert!((k.speed_mps * 0.1 / l.k_m2ps - 1.0).abs() < 1e-9);
        }
        // Square rungs on a straight band keep eq. 2.6 exactly.
        let plan = knots(&straight(0.2, 5), &l, TiltMethod::None, 0.0).unwrap();
        for k in &plan.knots {
            assert!((k.speed_mps * 0.2 / l.k_m2ps - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn radial_rungs_on_an_annulus_keep_eq_2_6() {
        // Rungs from r = 1.0 to 1.2 m every 1°: the swept tile is an annulus
        // sector whose area is the rung length × the midpoint's arc.
        let l = law();
        let rungs: Vec<Rung> = (0..30)
            .map(|k| {
                let d = Vec2::from_angle((k as f64).to_radians());
                Rung {
                    left: Point::ORIGIN + d,
                    right: Point::ORIGIN + 1.2 * d,
                }
            })
            .collect();
        let plan = knots(&rungs, &l, TiltMethod::None, 0.0).unwrap();
        for k in &plan.knots {
            // Chords instead of arcs: the midpoint path is a polygon.
            assert!(
                (k.speed_mps * 0.2 / l.k_m2ps - 1.0).abs() < 1e-4,
                "{}",
                k.speed_mps
            );
            assert!((k.swept_width_m / 0.2 - 1.0).abs() < 1e-4);
        }
    }

    #[test]
    fn straight_stroke_knots_follow_eq_2_4_to_2_6() {
        let l = law();
        let plan = knots(
            &straight(0.2, 5),
            &l,
            TiltMethod::Quadrilateral,
            tilt::DEFAULT_MAX_TILT_RAD,
        )
        .unwrap();
        for k in &plan.knots {
            assert!((k.mid.x - 0.1).abs() < 1e-12);
            assert_eq!(k.tip, k.mid);
            assert!(k.yaw_rad.abs() < 1e-12);
            assert!(k.tilt_rad.abs() < 1e-12);
            assert!((k.z_m - 0.1 / (FAN / 2.0).tan()).abs() < 1e-12);
            assert!((k.speed_mps * k.width_m - l.k_m2ps).abs() < 1e-15);
        }
        assert!((plan.u_before.0 - 50.0).abs() < 1e-9 && (plan.u_before.1 - 50.0).abs() < 1e-9);
        assert!(plan.clamped.is_empty());
    }

    #[test]
    fn narrow_rungs_are_clamped_and_slowed_for_the_wider_fan() {
        let l = law();
        let plan = knots(&straight(0.02, 3), &l, TiltMethod::None, 0.0).unwrap();
        assert_eq!(plan.clamped.len(), 3);
        for k in &plan.knots {
            assert_eq!(k.z_m, l.min_height_m);
            assert!((k.fan_width_m - l.width_at_height(l.min_height_m)).abs() < 1e-12);
            assert!((k.speed_mps * k.fan_width_m - l.k_m2ps).abs() < 1e-15);
        }
    }

    #[test]
    fn too_wide_names_the_rung_and_the_fix() {
        let err = knots(&straight(0.6, 3), &law(), TiltMethod::None, 0.0).unwrap_err();
        assert!(matches!(err, PlanError::TooWide { rung: 0, .. }));
        assert!(err.to_string().contains("split"), "{err}");
    }

    #[test]
    fn bad_law_names_the_field() {
        let mut l = law();
        l.k_m2ps = -1.0;
        let err = knots(&straight(0.2, 2), &l, TiltMethod::None, 0.0).unwrap_err();
        assert!(err.to_string().contains("k_m2ps"), "{err}");
        l = law();
        l.height = HeightLaw::Linear { c0: 0.0, c1: 0.0 };
        assert!(knots(&straight(0.2, 2), &l, TiltMethod::None, 0.0).is_err());
        assert_eq!(
            knots(&[], &law(), TiltMethod::None, 0.0),
            Err(PlanError::NoRungs)
        );
        let nan = [Rung {
            left: Point::new(f64::NAN, 0.0),
            right: Point::ZERO,
        }];
        assert_eq!(
            knots(&nan, &law(), TiltMethod::None, 0.0),
            Err(PlanError::NotFinite { rung: 0 })
        );
    }

    #[test]
    fn pointed_end_borrows_the_neighbours_direction() {
        let mut rungs = straight(0.2, 4);
        rungs[0] = Rung {
            left: Point::new(0.1, 0.0),
            right: Point::new(0.1, 0.0),
        };
        let plan = knots(&rungs, &law(), TiltMethod::None, 0.0).unwrap();
        assert!(plan.knots[0].yaw_rad.abs() < 1e-12);
        assert!(plan.knots[0].speed_mps.is_finite());
        assert_eq!(plan.clamped.len(), 1);
        let all_zero = [rungs[0]; 2];
        assert_eq!(
            knots(&all_zero, &law(), TiltMethod::None, 0.0),
            Err(PlanError::Degenerate { count: 2 })
        );
    }

    #[test]
    fn linear_law_matches_the_calibration() {
        let mut l = law();
        // 001 App. A (pathS.c): z = 509.3 mm + 0.878715·w incl. the gun mount; here without the mount.
        l.height = HeightLaw::Linear {
            c0: 0.01,
            c1: 0.878715,
        };
        let plan = knots(&straight(0.3, 2), &l, TiltMethod::None, 0.0).unwrap();
        assert!((plan.knots[0].z_m - (0.01 + 0.878715 * 0.3)).abs() < 1e-12);
        assert!((l.width_at_height(l.height_for_width(0.3)) - 0.3).abs() < 1e-12);
    }

    fn arc_rungs(r_in: f64, r_out: f64, n: usize) -> Vec<Rung> {
        (0..n)
            .map(|k| {
                let a = 0.02 * k as f64;
                let d = Vec2::from_angle(a);
                Rung {
                    left: Point::ZERO + r_in * d,
                    right: Point::ZERO + r_out * d,
                }
            })
            .collect()
    }

    #[test]
    fn tilt_lowers_the_nozzle_and_moves_its_foot_towards_the_lean() {
        let plan = knots(
            &arc_rungs(0.3, 0.6, 10),
            &law(),
            TiltMethod::Quadrilateral,
            tilt::DEFAULT_MAX_TILT_RAD,
        )
        .unwrap();
        assert!(plan.u_before.0 < 45.0);
        assert!(plan.u_after.0 > plan.u_before.0);
        for k in &plan.knots {
            assert!(k.tilt_rad < 0.0 && k.tilt_rad >= -tilt::DEFAULT_MAX_TILT_RAD);
            assert!(k.z_m < law().height_for_width(k.width_m));
            // β < 0 leans towards −ψ (inwards); the foot moves outwards (+ψ) to keep the fan on the rung.
            let along = (k.tip - k.mid).dot(Vec2::from_angle(k.yaw_rad));
            assert!(along > 0.0);
        }
    }
}
