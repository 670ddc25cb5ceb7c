//! Ring-following bands of a region with one hole: rungs run radially from
//! the hole to the outer boundary, so a ring is painted as a few curved
//! bands around it instead of the many cells a sweep cuts it into. Applies
//! where every ray from the hole's centroid meets the hole once and then
//! the outer boundary once (both boundaries star-shaped about it), which
//! holds for rings, frames and washers.

use std::f64::consts::TAU;

use kurbo::{Point, Vec2};

use super::decompose::Band;
use super::region::Region;

/// Largest angle one band sweeps around the centre. assumed: a quarter
/// turn keeps each band's fan rotation at 90°, well inside the end
/// effector's yaw range, with four joins per ring.
const MAX_SECTOR_RAD: f64 = std::f64::consts::FRAC_PI_2;
/// Uniform ray spacing, besides a ray through every vertex. assumed: 1°
/// puts a rung every 17 mm on a 1 m radius, under the 20 mm rung spacing.
const RAY_STEP_RAD: f64 = TAU / 360.0;

/// The ring's bands (counter-clockwise travel, left edge on the hole), or
/// `None` when the region is not ring-like.
pub fn bands(r: &Region, start_angle: f64) -> Option<Vec<Band>> {
    if r.holes.len() != 1 {
        return None;
    }
    let hole = &r.holes[0];
    let c = centroid(hole);
    let mut angles: Vec<f64> = (0..360).map(|i| i as f64 * RAY_STEP_RAD).collect();
    for p in hole.iter().chain(r.outer.iter()) {
        angles.push((*p - c).atan2().rem_euclid(TAU));
    }
    let sectors = (TAU / MAX_SECTOR_RAD).ceil() as usize;
    let cuts: Vec<f64> = (0..sectors)
        .map(|i| (start_angle + i as f64 * TAU / sectors as f64).rem_euclid(TAU))
        .collect();
    angles.extend(&cuts);
    angles.sort_by(f64::total_cmp);
    angles.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    // Rungs at each angle, inner end (left of counter-clockwise travel) first.
    let mut rungs: Vec<(f64, Point, Point)> = Vec::with_capacity(angles.len());
    for &a in &angles {
        let d = Vec2::from_angle(a);
        let inner = single_hit(hole, c, d)?;
        let outer = single_hit(&r.outer, c, d)?;
        if outer <= inner {
            return None;
        }
        rungs.push((a, c + d * inner, c + d * outer));
    }
    // Cut the circle of rungs into sectors starting at the first cut.
    let first = rungs
        .iter()
        .position(|(a, _, _)| (*a - cuts[0]).abs() < 1e-9)?;
    rungs.rotate_left(first);
    let start = rungs[0];
    rungs.push(start);
    let mut out = vec![];
    let mut cur: Vec<(Point, Point)> = vec![];
    for (i, (a, p, q)) in rungs.iter().enumerate() {
        cur.push((*p, *q));
        let at_cut = i > 0 && cuts.iter().any(|k| (a - k).abs() < 1e-9);
        if at_cut && cur.len() > 1 {
            out.push(Band {
                rungs: std::mem::take(&mut cur),
            });
            cur.push((*p, *q));
        }
    }
    Some(out)
}

/// Distance along the ray c + t·d to the contour, if it crosses exactly once.
fn single_hit(poly: &[Point], c: Point, d: Vec2) -> Option<f64> {
    let n = poly.len();
    let mut hits: Vec<f64> = vec![];
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        let e = b - a;
        let den = d.cross(e);
        if den.abs() < 1e-15 {
            continue;
        }
        let w = a - c;
        let t = w.cross(e) / den;
        let u = w.cross(d) / den;
        // Half-open in u so a ray through a vertex counts once.
        if t > 0.0 && (-1e-12..=1.0 + 1e-12).contains(&u) {
            hits.push(t);
        }
    }
    // A ray through a vertex meets both edges there: one crossing.
    hits.sort_by(f64::total_cmp);
    hits.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    (hits.len() == 1).then(|| hits[0])
}

/// Area centroid of a simple polygon (either orientation).
fn centroid(p: &[Point]) -> Point {
    let n = p.len();
    let (mut a, mut x, mut y) = (0.0, 0.0, 0.0);
    for i in 0..n {
        let (s, t) = (p[i], p[(i + 1) % n]);
        let w = s.x * t.y - t.x * s.y;
        a += w;
        x += (s.x + t.x) * w;
        y += (s.y + t.y) * w;
    }
    if a.abs() < 1e-15 {
        return p.first().copied().unwrap_or(Point::ORIGIN);
    }
    Point::new(x / (3.0 * a), y / (3.0 * a))
}
