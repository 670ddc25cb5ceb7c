//! Lobes of a region: the convex parts its outline bulges into between two
//! reflex corners (a star's arms, a cross's bars), cut off along the chord
//! between those corners, and the core left when they are gone (a star's
//! pentagon). Each piece is then swept along its own directions, so a
//! star's arm is painted from its base to its tip in one stroke where one
//! sweep for the whole region (or the triangulation's convex pieces, which
//! merge an arm with half the centre) cuts it across.

use kurbo::Point;

use super::region::{signed_area, Region};

/// A turn this small (|cross| / (|a|·|b|), the sine of the turn) is
/// straight, neither convex nor reflex. assumed: 0.01 (about half a
/// degree), above the chord noise of a flattened curve's 1 mm tolerance on
/// the segments a lobe's corners are made of.
const STRAIGHT_SIN: f64 = 0.01;
/// A lobe smaller than this fraction of its region is not worth its own
/// stroke. assumed: 2 %; a five-pointed star's arm is about 12 %.
const MIN_LOBE_FRACTION: f64 = 0.02;

/// The lobes and the core of `r` (lobes first, core last; all without
/// holes but the core, counter-clockwise; a run around a hole is not a
/// lobe, so every hole stays in the core) and each lobe's direction from
/// its chord to its tip (rad, square to the chord), or `None` when fewer than two
/// lobes are cut off (the region is then better cut by the other methods).
/// A lobe is the outline's run from one reflex corner to the next with
/// only convex or straight corners between them, closed by the chord
/// between the two reflex corners; it is cut off only when it is convex,
/// at least `min_chord` across (the fan's narrowest band: a narrower neck
/// is a tip, not an arm) and [`MIN_LOBE_FRACTION`] of the region, and
/// its chord runs inside the region.
pub fn pieces(r: &Region, min_chord: f64) -> Option<(Vec<Region>, Vec<f64>)> {
    let p = &r.outer;
    let n = p.len();
    if n < 5 {
        return None;
    }
    let turn = |i: usize| {
        let (a, b, c) = (p[(i + n - 1) % n], p[i], p[(i + 1) % n]);
        let (u, v) = (b - a, c - b);
        u.cross(v) / (u.hypot() * v.hypot()).max(1e-30)
    };
    let reflex: Vec<usize> = (0..n).filter(|&i| turn(i) < -STRAIGHT_SIN).collect();
    if reflex.len() < 2 {
        return None;
    }
    let area = r.area();
    let mut lobes: Vec<(usize, usize)> = vec![];
    for k in 0..reflex.len() {
        let (a, b) = (reflex[k], reflex[(k + 1) % reflex.len()]);
        let len = (b + n - a) % n;
        if len < 2 {
            continue;
        }
        let lobe: Vec<Point> = (0..=len).map(|j| p[(a + j) % n]).collect();
        let chord = (p[a], p[b]);
        if (chord.1 - chord.0).hypot() < min_chord
            || signed_area(&lobe) < MIN_LOBE_FRACTION * area
            || !convex(&lobe)
            || !inside(r, chord, (a, b))
            || holds_a_hole(r, &lobe)
        {
            continue;
        }
        lobes.push((a, b));
    }
    if lobes.len() < 2 {
        return None;
    }
    // The core: the outline with each lobe's run replaced by its chord.
    let mut core: Vec<Point> = vec![];
    let mut i = lobes[0].1;
    let start = i;
    loop {
        core.push(p[i]);
        i = match lobes.iter().find(|l| l.0 == i) {
            Some(l) => l.1,
            None => (i + 1) % n,
        };
        if i == start {
            break;
        }
    }
    let mut out: Vec<Region> = lobes
        .iter()
        .map(|&(a, b)| Region {
            outer: (0..=(b + n - a) % n).map(|j| p[(a + j) % n]).collect(),
            holes: vec![],
        })
        .collect();
    if signed_area(&core) > MIN_LOBE_FRACTION * area {
        out.push(Region {
            outer: core,
            holes: r.holes.clone(),
        });
    }
    let axes = lobes
        .iter()
        .map(|&(a, b)| (p[b] - p[a]).atan2() + std::f64::consts::FRAC_PI_2)
        .collect();
    Some((out, axes))
}

/// Every corner of the counter-clockwise polygon turns left or goes straight.
fn convex(p: &[Point]) -> bool {
    let n = p.len();
    (0..n).all(|i| {
        let (a, b, c) = (p[(i + n - 1) % n], p[i], p[(i + 1) % n]);
        let (u, v) = (b - a, c - b);
        u.cross(v) >= -STRAIGHT_SIN * u.hypot() * v.hypot()
    })
}

/// The chord between outline vertices `ends` runs inside the region: it
/// crosses no contour edge (but the ones at its ends) and its midpoint is
/// filled.
fn inside(r: &Region, chord: (Point, Point), ends: (usize, usize)) -> bool {
    let (c0, c1) = chord;
    let crosses = |a: Point, b: Point| {
        let d = c1 - c0;
        let e = b - a;
        let den = d.cross(e);
        if den.abs() < 1e-15 {
            return false;
        }
        let t = (a - c0).cross(e) / den;
        let u = (a - c0).cross(d) / den;
        (1e-9..1.0 - 1e-9).contains(&t) && (1e-9..1.0 - 1e-9).contains(&u)
    };
    let n = r.outer.len();
    for (ci, c) in r.contours().enumerate() {
        let m = c.len();
        for i in 0..m {
            let j = (i + 1) % m;
            let touches = ci == 0 && [i, j].iter().any(|v| *v == ends.0 || *v == ends.1);
            if !touches && crosses(c[i], c[j]) {
                return false;
            }
        }
        debug_assert!(ci > 0 || m == n);
    }
    let mid = c0.midpoint(c1);
    r.contours().map(|c| winding(c, mid)).sum::<i32>() != 0
}

/// A hole of `r` lies inside `lobe`. The chord crosses no hole's edge
/// (`inside`), so a hole is wholly in the lobe or wholly out of it: one
/// vertex tells. Cutting such a lobe off as a solid piece would paint its
/// hole over (an 8's two loops are two lobes with a counter each).
fn holds_a_hole(r: &Region, lobe: &[Point]) -> bool {
    r.holes
        .iter()
        .any(|h| h.first().is_some_and(|&q| winding(lobe, q) != 0))
}

/// Winding number of the closed polygon `c` about `q`.
fn winding(c: &[Point], q: Point) -> i32 {
    let m = c.len();
    let mut w = 0;
    for i in 0..m {
        let (a, b) = (c[i], c[(i + 1) % m]);
        let side = (b - a).cross(q - a);
        if a.y <= q.y && b.y > q.y && side > 0.0 {
            w += 1;
        } else if a.y > q.y && b.y <= q.y && side < 0.0 {
            w -= 1;
        }
    }
    w
}

#[cfg(test)]
mod tests {
    use super::super::region::from_radii;
    use super::*;

    fn star(inner: f64) -> Region {
        let radii: Vec<f64> = (0..10)
            .map(|i| if i % 2 == 0 { 1.0 } else { inner })
            .collect();
        from_radii(&radii, std::f64::consts::FRAC_PI_2)
    }

    #[test]
    fn a_star_is_five_arms_and_a_pentagon() {
        let r = star(0.4);
        let (pieces, axes) = pieces(&r, 0.1).expect("lobes");
        assert_eq!((pieces.len(), axes.len()), (6, 5));
        assert!(pieces[..5].iter().all(|p| p.outer.len() == 3));
        assert_eq!(pieces[5].outer.len(), 5);
        let sum: f64 = pieces.iter().map(Region::area).sum();
        assert!((sum - r.area()).abs() < 1e-9 * r.area());
    }

    /// An 8: two rings joined at a waist. The outline's two reflex corners
    /// bound two convex runs (the loops), but each holds a counter, so
    /// neither is a lobe, and no counter is painted over.
    #[test]
    fn loops_around_holes_are_not_lobes() {
        let square = |x0: f64, y0: f64, s: f64| {
            vec![
                Point::new(x0, y0),
                Point::new(x0 + s, y0),
                Point::new(x0 + s, y0 + s),
                Point::new(x0, y0 + s),
            ]
        };
        let hole = |x0: f64, y0: f64, s: f64| {
            let mut h = square(x0, y0, s);
            h.reverse();
            h
        };
        // Octagon-ish loops: a lower loop 0..2 and an upper 0..2 above it,
        // pinched to 1.6 wide at the waist y = 2.
        let outer = vec![
            Point::new(0.5, 0.0),
            Point::new(1.5, 0.0),
            Point::new(2.0, 0.5),
            Point::new(2.0, 1.5),
            Point::new(1.8, 2.0),
            Point::new(2.0, 2.5),
            Point::new(2.0, 3.5),
            Point::new(1.5, 4.0),
            Point::new(0.5, 4.0),
            Point::new(0.0, 3.5),
            Point::new(0.0, 2.5),
            Point::new(0.2, 2.0),
            Point::new(0.0, 1.5),
            Point::new(0.0, 0.5),
        ];
        let solid = Region {
            outer: outer.clone(),
            holes: vec![],
        };
        // Without counters the loops are lobes (the test means something).
        assert!(pieces(&solid, 0.1).is_some());
        let eight = Region {
            outer,
            holes: vec![hole(0.6, 0.6, 0.8), hole(0.6, 2.6, 0.8)],
        };
        assert!(pieces(&eight, 0.1).is_none());
        // One counter: the loop that holds it is not cut off, so with a
        // single lobe left none are.
        let six = Region {
            outer: eight.outer.clone(),
            holes: vec![hole(0.6, 0.6, 0.8)],
        };
        assert!(pieces(&six, 0.1).is_none());
    }

    #[test]
    fn a_convex_region_has_no_lobes() {
        let sq = Region {
            outer: vec![
                Point::new(0.0, 0.0),
                Point::new(1.0, 0.0),
                Point::new(1.0, 1.0),
                Point::new(0.0, 1.0),
                Point::new(-0.5, 0.5),
            ],
            holes: vec![],
        };
        assert!(pieces(&sq, 0.1).is_none());
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]
        /// Random star-shaped polygons: the lobes and the core are convex
        /// but the core, and they add up to the region.
        #[test]
        fn lobes_and_core_tile_the_region(
            radii in proptest::collection::vec(0.3f64..1.2, 6..16)
        ) {
            let r = from_radii(&radii, 0.0);
            if let Some((pieces, axes)) = pieces(&r, 0.05) {
                let sum: f64 = pieces.iter().map(Region::area).sum();
                // A core under 2 % of the region is dropped with its area.
                let core_dropped = pieces.len() == axes.len();
                proptest::prop_assert!(
                    core_dropped || (sum - r.area()).abs() < 1e-9 * r.area(),
                    "pieces {} vs region {}", sum, r.area()
                );
                for p in &pieces[..axes.len()] {
                    proptest::prop_assert!(convex(&p.outer));
                    proptest::prop_assert!(p.area() > 0.0);
                }
            }
        }
    }

    #[test]
    fn arms_with_necks_narrower_than_the_fan_stay_on() {
        assert!(pieces(&star(0.4), 1.0).is_none());
    }
}
