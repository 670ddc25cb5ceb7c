//! Regions → strokes. Each region is cut into bands (a run of rungs, each
//! joining a point on the left boundary to one on the right) by two
//! methods: boustrophedon cells swept along the region's long axis or
//! across it (`sweep`), and ring-following bands around a hole (`ring`).
//! A band is then made paintable: its ends are trimmed where it is
//! narrower than the fan can usefully paint, it is cut where the number of
//! passes its width needs changes, cut again where its rungs would lean
//! too far, and each piece is split into parallel strips at most one pass
//! wide. Pieces and strips share their cut rungs and edges, so the strokes
//! tile the band: no overlap, no gap. The method with the better predicted
//! film (then time) is kept per region and reported.

use super::passes::{band_region, paint, Painted, Passes};
pub use super::passes::{Band, Bands, Narrow, Steep};
use super::region::{signed_area, Region};
use super::{convex, lobes, ring, sweep, ShapeError};
use crate::font::Stroke;

/// Sweep directions closer than this (rad) are one. assumed: half a degree.
const SAME_ANGLE_RAD: f64 = 0.5 * std::f64::consts::PI / 180.0;
/// Films within this fraction of the area are equally good; time decides.
/// assumed: 1 % of the area.
const FILM_TIE: f64 = 0.01;

/// How a region was cut.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// Boustrophedon cells swept along this road angle (rad); with
    /// `cells_own_axes`, each cell is swept again along its own directions
    /// where that paints better.
    Sweep {
        angle_rad: f64,
        cells_own_axes: bool,
    },
    /// Bands following the ring around its hole; with `concentric`, pass
    /// pieces merged and split into concentric passes (`ring_passes`).
    Ring { concentric: bool },
    /// Convex pieces, each swept along its own long axis.
    Convex { pieces: usize },
    /// Lobes cut off between reflex corners and the core left, each swept
    /// along its own directions (`lobes`).
    Lobes { lobes: usize },
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        match self {
            Method::Sweep {
                angle_rad,
                cells_own_axes,
            } => write!(
                f,
                "boustrophedon cells swept at {:.1}°{}",
                angle_rad.to_degrees().rem_euclid(180.0),
                if *cells_own_axes {
                    ", each cell along its own axes"
                } else {
                    ""
                }
            ),
            Method::Ring { concentric: false } => write!(f, "ring-following bands"),
            Method::Ring { concentric: true } => {
                write!(f, "ring-following bands in concentric passes")
            }
            Method::Convex { pieces } => {
                write!(f, "{pieces} convex pieces, each swept along its long axis")
            }
            Method::Lobes { lobes } => {
                write!(
                    f,
                    "{lobes} lobes and the core, each swept along its own axes"
                )
            }
        }
    }
}

/// What one region's candidates predicted, and which was kept.
#[derive(Clone, Debug, PartialEq)]
pub struct Candidate {
    pub method: Method,
    pub strokes: usize,
    /// Predicted gun-on time plus the per-stroke overhead (s).
    pub time_s: f64,
    /// (Unpainted + oversprayed area) / region area.
    pub film_error: f64,
}

#[derive(Clone, Debug, PartialEq)]
pub struct RegionReport {
    pub area_m2: f64,
    pub chosen: Candidate,
    pub others: Vec<Candidate>,
}

/// The strokes (m, shape frame) and what was decided.
#[derive(Clone, Debug, PartialEq)]
pub struct Decomposition {
    pub strokes: Vec<Stroke>,
    pub regions: Vec<RegionReport>,
    pub narrow: Vec<Narrow>,
    /// Band ends left bare where they turn too steeply.
    pub steep: Vec<Steep>,
    pub area_m2: f64,
}

/// A whole decomposition's predicted figures: its regions' film errors
/// weighted by their areas, their times summed, its strokes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Prediction {
    pub film_error: f64,
    pub time_s: f64,
    pub strokes: usize,
}

/// Predictions closer than this in film error (fraction of the area) and
/// [`SAME_TIME_S`] in time, with as many strokes, are one decomposition
/// turned (a symmetric shape's sweeps at its symmetric angles). assumed: a
/// hundredth of a percent, far below any real difference of two cuts.
const SAME_FILM: f64 = 1e-4;
/// See [`SAME_FILM`]. assumed: 10 ms in minutes of painting.
const SAME_TIME_S: f64 = 0.01;

impl Prediction {
    /// Equally good films by the predictor: within the same [`FILM_TIE`]
    /// step, as [`candidates`] ranks them.
    pub fn film_tied(&self, o: &Prediction) -> bool {
        (self.film_error / FILM_TIE).floor() == (o.film_error / FILM_TIE).floor()
    }

    /// The same decomposition by every predicted figure (a copy turned by
    /// the shape's symmetry).
    pub fn same(&self, o: &Prediction) -> bool {
        self.strokes == o.strokes
            && (self.film_error - o.film_error).abs() < SAME_FILM
            && (self.time_s - o.time_s).abs() < SAME_TIME_S
    }
}

impl Decomposition {
    /// What the predictor says of the whole decomposition.
    pub fn prediction(&self) -> Prediction {
        let bad: f64 = self
            .regions
            .iter()
            .map(|r| r.chosen.film_error * r.area_m2)
            .sum();
        Prediction {
            film_error: if self.area_m2 > 0.0 {
                bad / self.area_m2
            } else {
                0.0
            },
            time_s: self.regions.iter().map(|r| r.chosen.time_s).sum(),
            strokes: self.strokes.len(),
        }
    }
}

#[derive(Clone)]
struct Plan {
    candidate: Candidate,
    strokes: Vec<Stroke>,
    narrow: Vec<Narrow>,
    steep: Vec<Steep>,
}

/// Share of a region's area by which its strokes plus what they report
/// left bare may differ from it. assumed: 1 %. Measured on the test shapes
/// (tests/data/shapes, 2 m): every plan within 0.01 % but the ring's
/// sweeps, 0.7 % short (their cells' chords along the round hole); an 8's
/// counters painted over were 21 %.
const TILE_TOLERANCE: f64 = 0.01;

/// Samples per stroke edge for [`tiles`]' areas. assumed: as the tests'.
const TILE_SAMPLES: usize = 400;

/// The plan's strokes, with the area its tips and steep ends report left
/// bare, add up to the region's `area` (m²) within [`TILE_TOLERANCE`].
fn tiles(p: &Plan, area: f64) -> bool {
    let strokes: f64 = p
        .strokes
        .iter()
        .map(|s| signed_area(&s.outline(TILE_SAMPLES)))
        .sum();
    let bare: f64 = p.narrow.iter().map(|n| n.unpainted_m2).sum::<f64>()
        + p.steep.iter().map(|s| s.unpainted_m2).sum::<f64>();
    ((strokes + bare) - area).abs() <= TILE_TOLERANCE * area
}

/// The most candidate decompositions [`candidates`] returns. assumed: 8
/// keeps `plan::shapes` measuring them under ten seconds for the test
/// shapes while holding every method the predictor ranks close.
pub const MAX_CANDIDATES: usize = 8;

/// Decompose every region, each by the plan with the best predicted film
/// (then time); see the module docs.
pub fn decompose(
    regions: &[Region],
    lim: &Bands,
    origin: &str,
) -> Result<Decomposition, ShapeError> {
    let mut all = candidates(regions, lim, origin)?;
    Ok(all.swap_remove(0))
}

/// Every region's plans ranked by predicted film (within [`FILM_TIE`] of
/// the region's area, then time), as at most [`MAX_CANDIDATES`] whole
/// decompositions: candidate j takes each region's j-th plan (its last
/// when it has fewer). The first is [`decompose`]'s.
pub fn candidates(
    regions: &[Region],
    lim: &Bands,
    origin: &str,
) -> Result<Vec<Decomposition>, ShapeError> {
    let mut ranked: Vec<(f64, Vec<Plan>, Vec<Candidate>)> = vec![];
    for r in regions {
        let area = r.area();
        let mut plans = region_plans(r, area, lim, origin)?;
        // A plan whose strokes do not tile the region paints a hole over or
        // leaves a piece bare unreported; the preview, judging the film
        // against the strokes, could not tell. Such a plan is a bug here,
        // never a choice.
        plans.retain(|p| tiles(p, area));
        if plans.is_empty() {
            return Err(ShapeError::invalid(
                origin,
                format!(
                    "no decomposition of the {area:.3} m² region tiles it (an internal error: please report it with the file)"
                ),
            ));
        }
        let key = |p: &Plan| {
            (
                (p.candidate.film_error / FILM_TIE).floor(),
                p.candidate.time_s,
            )
        };
        plans.sort_by(|a, b| {
            let (ka, kb) = (key(a), key(b));
            ka.0.total_cmp(&kb.0).then(ka.1.total_cmp(&kb.1))
        });
        let every: Vec<Candidate> = plans.iter().map(|p| p.candidate.clone()).collect();
        ranked.push((area, shortlist(plans), every));
    }
    let n = ranked
        .iter()
        .map(|(_, p, _)| p.len())
        .max()
        .unwrap_or(1)
        .clamp(1, MAX_CANDIDATES);
    let mut out = vec![];
    for j in 0..n {
        let mut d = Decomposition {
            strokes: vec![],
            regions: vec![],
            narrow: vec![],
            steep: vec![],
            area_m2: 0.0,
        };
        for (area, plans, every) in &ranked {
            let k = j.min(plans.len().saturating_sub(1));
            let Some(chosen) = plans.get(k) else {
                continue;
            };
            d.strokes.extend(chosen.strokes.iter().cloned());
            d.narrow.extend(chosen.narrow.iter().copied());
            d.steep.extend(chosen.steep.iter().copied());
            d.regions.push(RegionReport {
                area_m2: *area,
                chosen: chosen.candidate.clone(),
                others: every
                    .iter()
                    .filter(|c| **c != chosen.candidate)
                    .cloned()
                    .collect(),
            });
            d.area_m2 += area;
        }
        out.push(d);
    }
    Ok(out)
}

/// A plan's family: the predictor ranks them on film it cannot fully see
/// (the planner slows where cells are short or the fan turns fast), so
/// each family's best is measured before the list ends.
fn family(m: &Method) -> u8 {
    match m {
        Method::Sweep {
            cells_own_axes: false,
            ..
        } => 0,
        Method::Sweep { .. } => 1,
        Method::Ring { concentric: false } => 2,
        Method::Ring { concentric: true } => 5,
        Method::Convex { .. } => 3,
        Method::Lobes { .. } => 4,
    }
}

/// The ranked plans of one region cut to [`MAX_CANDIDATES`]: a plan the
/// predictor cannot tell from an earlier one (the same strokes, film and
/// time: a symmetric shape's sweep turned to a symmetric angle) is dropped,
/// so the list holds distinct decompositions; the best plan of every
/// [`family`] that would fall off the end takes the last places, in rank
/// order. At some sizes the predictor's favourites all paint badly (a star
/// 2 m tall: its sweeps leave cells too short for the run-up) while the
/// convex pieces it ranks tenth paint evenly.
fn shortlist(plans: Vec<Plan>) -> Vec<Plan> {
    let pred = |p: &Plan| Prediction {
        film_error: p.candidate.film_error,
        time_s: p.candidate.time_s,
        strokes: p.candidate.strokes,
    };
    let mut distinct: Vec<Plan> = vec![];
    for p in plans {
        if !distinct.iter().any(|q| pred(q).same(&pred(&p))) {
            distinct.push(p);
        }
    }
    if distinct.len() <= MAX_CANDIDATES {
        return distinct;
    }
    let mut missing: Vec<usize> = vec![];
    for (i, p) in distinct.iter().enumerate().skip(MAX_CANDIDATES) {
        let f = family(&p.candidate.method);
        let seen = |j: &usize| family(&distinct[*j].candidate.method) == f;
        if !distinct[..MAX_CANDIDATES]
            .iter()
            .any(|q| family(&q.candidate.method) == f)
            && !missing.iter().any(seen)
        {
            missing.push(i);
        }
    }
    let head = MAX_CANDIDATES - missing.len();
    let tail: Vec<Plan> = missing.iter().map(|&i| distinct[i].clone()).collect();
    distinct.truncate(head);
    distinct.extend(tail);
    distinct
}

/// Every plan of one region: sweeps along each of its directions (with
/// and without each cell tried along its own axes), ring-following bands
/// around a single hole, and convex pieces.
fn region_plans(r: &Region, area: f64, lim: &Bands, origin: &str) -> Result<Vec<Plan>, ShapeError> {
    let axis = sweep::principal_angle(r);
    let mut plans: Vec<Plan> = vec![];
    for angle in sweep_angles(r, lim.max_width_m) {
        let bands = sweep::bands(r, angle);
        for cells in [false, true] {
            let method = Method::Sweep {
                angle_rad: angle,
                cells_own_axes: cells,
            };
            plans.push(plan(method, &bands, area, lim, origin)?);
        }
    }
    if let Some(bands) = ring::bands(r, axis) {
        for concentric in [false, true] {
            let method = Method::Ring { concentric };
            plans.push(plan(method, &bands, area, lim, origin)?);
        }
    }
    let pieces = convex::pieces(r);
    if pieces.len() > 1 {
        let method = Method::Convex {
            pieces: pieces.len(),
        };
        let free: Vec<Piece> = pieces.iter().map(|p| (p, None, false)).collect();
        plans.push(pieces_plan(method, &free, area, lim, origin)?);
    }
    if let Some((pieces, axes)) = lobes::pieces(r, lim.min_width_m) {
        // Each lobe from its base to its tip (one stroke where it is one
        // pass wide); the core along a lobe's axis, so its strokes start
        // squarely on the chords, with short pass pieces merged (a star's
        // pentagon: two passes end to end, not five short bits).
        let all: Vec<Piece> = pieces
            .iter()
            .enumerate()
            .map(|(i, p)| match axes.get(i) {
                Some(a) => (p, Some(vec![*a]), false),
                None => (p, Some(axes.clone()), true),
            })
            .collect();
        let method = Method::Lobes { lobes: axes.len() };
        plans.push(pieces_plan(method, &all, area, lim, origin)?);
    }
    Ok(plans)
}

/// A piece of a region, the directions it may be swept along (`None`: its
/// own, [`sweep_angles`]; the best predicted is kept) and whether its short
/// pass pieces are merged ([`merge_short`]).
type Piece<'a> = (&'a Region, Option<Vec<f64>>, bool);

/// Pieces of a region, each swept along its direction.
fn pieces_plan(
    method: Method,
    pieces: &[Piece],
    area: f64,
    lim: &Bands,
    origin: &str,
) -> Result<Plan, ShapeError> {
    let mut all = Painted::default();
    for (p, fixed, merge) in pieces {
        let mut best: Option<Painted> = None;
        let angles = fixed
            .clone()
            .unwrap_or_else(|| sweep_angles(p, lim.min_width_m));
        for angle in angles {
            let rule = Passes {
                merge: *merge,
                concentric: false,
            };
            let alt = paint(&sweep::bands(p, angle), lim, origin, rule)?;
            if best.as_ref().is_none_or(|b| alt.better_than(b, p.area())) {
                best = Some(alt);
            }
        }
        all.append(best.unwrap_or_default());
    }
    Ok(all.into_plan(method, area))
}

impl Painted {
    fn into_plan(self, method: Method, area: f64) -> Plan {
        Plan {
            candidate: Candidate {
                method,
                strokes: self.strokes.len(),
                time_s: self.time_s,
                film_error: if area > 0.0 { self.bad_m2 / area } else { 0.0 },
            },
            strokes: self.strokes,
            narrow: self.narrow,
            steep: self.steep,
        }
    }
    /// Lower is better: the film first (within [`FILM_TIE`] of `area`), then time.
    fn better_than(&self, o: &Painted, area: f64) -> bool {
        if (self.bad_m2 - o.bad_m2).abs() > FILM_TIE * area {
            self.bad_m2 < o.bad_m2
        } else {
            self.time_s < o.time_s
        }
    }
}

fn plan(
    method: Method,
    bands: &[Band],
    area: f64,
    lim: &Bands,
    origin: &str,
) -> Result<Plan, ShapeError> {
    let mut all = Painted::default();
    let concentric = matches!(method, Method::Ring { concentric: true });
    let rule = Passes {
        merge: concentric,
        concentric,
    };
    for band in bands {
        let mut best = paint(std::slice::from_ref(band), lim, origin, rule)?;
        if let Method::Sweep {
            cells_own_axes: true,
            ..
        } = method
        {
            // A sweep cell may point elsewhere than the region (a star's
            // arm): try it swept along its own axis and across it.
            let cell = band_region(band);
            let cell_area = cell.area();
            for angle in sweep_angles(&cell, lim.max_width_m) {
                let alt = paint(&sweep::bands(&cell, angle), lim, origin, Passes::default())?;
                if alt.better_than(&best, cell_area) {
                    best = alt;
                }
            }
        }
        all.append(best);
    }
    Ok(all.into_plan(method, area))
}

/// Sweep directions worth trying for `r`: square to each outline edge at
/// least `min_len` long (so that edge is one rung and a band starts or
/// ends on it squarely, not on a sliver), then along and across the long
/// axis; one of each pair closer than [`SAME_ANGLE_RAD`].
fn sweep_angles(r: &Region, min_len: f64) -> Vec<f64> {
    use std::f64::consts::{FRAC_PI_2, PI};
    let axis = sweep::principal_angle(r);
    let mut out: Vec<f64> = vec![];
    let mut edges: Vec<(f64, f64)> = r
        .contours()
        .flat_map(|c| {
            (0..c.len()).map(move |i| {
                let d = c[(i + 1) % c.len()] - c[i];
                (d.hypot(), d.atan2() + FRAC_PI_2)
            })
        })
        .filter(|(len, _)| *len >= min_len)
        .collect();
    edges.sort_by(|a, b| b.0.total_cmp(&a.0));
    for a in edges
        .into_iter()
        .map(|e| e.1)
        .chain([axis, axis + FRAC_PI_2])
    {
        let a = a.rem_euclid(PI);
        let near = |b: &f64| {
            let d = (a - b).rem_euclid(PI);
            d.min(PI - d) < SAME_ANGLE_RAD
        };
        if !out.iter().any(near) {
            out.push(a);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::font::{overlap_area, DEFAULT_LIMITS};
    use crate::region::signed_area;
    use kurbo::Point;
    use proptest::prelude::*;

    fn bands() -> Bands {
        Bands::of(&basr_robot::AnyRobot::load_or_default(None).expect("embedded robot"))
    }

    /// Strokes tile the region: their areas plus what the tips leave bare
    /// add up to the region, no rung is wider than a pass, none overlap.
    fn assert_tiles(regions: &[Region]) {
        let d = decompose(regions, &bands(), "test").expect("decomposes");
        assert_decomposition_tiles(regions, &d);
    }

    fn assert_decomposition_tiles(regions: &[Region], d: &Decomposition) {
        let lim = bands();
        let area: f64 = regions.iter().map(Region::area).sum();
        let strokes: f64 = d.strokes.iter().map(|s| signed_area(&s.outline(400))).sum();
        let bare: f64 = d.narrow.iter().map(|n| n.unpainted_m2).sum::<f64>()
            + d.steep.iter().map(|s| s.unpainted_m2).sum::<f64>();
        assert!(
            ((strokes + bare) - area).abs() < 0.005 * area,
            "strokes {strokes} + bare {bare} vs region {area}"
        );
        for (k, s) in d.strokes.iter().enumerate() {
            for (i, (a, b)) in s.rungs(50).into_iter().enumerate() {
                let w = (b - a).hypot();
                assert!(
                    w <= lim.max_width_m + 1e-9,
                    "stroke {k} of {} ({:?}), rung {i} of 50: {w} m, wider than the widest \
                     band {} m",
                    d.strokes.len(),
                    d.regions
                        .iter()
                        .map(|r| r.chosen.method)
                        .collect::<Vec<_>>(),
                    lim.max_width_m
                );
            }
        }
        let fine = crate::font::Limits {
            scan_step: 0.002,
            overlap_area: 1e-5,
            ..DEFAULT_LIMITS
        };
        for i in 0..d.strokes.len() {
            for j in i + 1..d.strokes.len() {
                let o = overlap_area(&d.strokes[i], &d.strokes[j], &fine);
                assert!(o < 2e-4, "strokes {i} and {j} overlap by {o} m²");
            }
        }
    }

    fn square_ring(outer: f64, inner: f64) -> Region {
        let sq = |h: f64| {
            vec![
                Point::new(-h, -h),
                Point::new(h, -h),
                Point::new(h, h),
                Point::new(-h, h),
            ]
        };
        let mut hole = sq(inner);
        hole.reverse();
        Region {
            outer: sq(outer),
            holes: vec![hole],
        }
    }

    /// The guard `candidates` applies: every plan of a square frame tiles
    /// it, and the same plan without one of its strokes does not.
    #[test]
    fn a_plan_missing_a_stroke_does_not_tile() {
        let r = square_ring(1.0, 0.75);
        let area = r.area();
        let plans = region_plans(&r, area, &bands(), "test").expect("plans");
        assert!(!plans.is_empty());
        for p in &plans {
            assert!(tiles(p, area), "{:?}", p.candidate.method);
            let mut short = Plan {
                candidate: p.candidate.clone(),
                strokes: p.strokes.clone(),
                narrow: p.narrow.clone(),
                steep: p.steep.clone(),
            };
            short.strokes.pop();
            assert!(!tiles(&short, area), "{:?}", p.candidate.method);
        }
    }

    #[test]
    fn a_square_frame_tiles() {
        assert_tiles(&[square_ring(1.0, 0.75)]);
    }

    #[test]
    fn a_wide_rectangle_is_split_into_passes() {
        let r = Region {
            outer: vec![
                Point::new(0.0, 0.0),
                Point::new(1.0, 0.0),
                Point::new(1.0, 3.0),
                Point::new(0.0, 3.0),
            ],
            holes: vec![],
        };
        let d = decompose(std::slice::from_ref(&r), &bands(), "test").expect("decomposes");
        // 1 m across, passes of at most 0.95 × 0.41 m: three strips along its length.
        assert_eq!(d.strokes.len(), 3);
        assert!(d.narrow.is_empty());
        assert_tiles(&[r]);
    }

    #[test]
    fn a_round_ring_is_painted_as_ring_following_bands() {
        let circle = |r: f64| -> Vec<Point> {
            (0..128)
                .map(|i| {
                    let a = std::f64::consts::TAU * i as f64 / 128.0;
                    Point::new(r * a.cos(), r * a.sin())
                })
                .collect()
        };
        let mut hole = circle(0.7);
        hole.reverse();
        let r = Region {
            outer: circle(1.0),
            holes: vec![hole],
        };
        assert_tiles(std::slice::from_ref(&r));
        let d = decompose(&[r], &bands(), "test").expect("decomposes");
        assert!(matches!(d.regions[0].chosen.method, Method::Ring { .. }));
        assert_eq!(d.strokes.len(), 4);
    }

    /// A figure eight: two loops pinched at a waist, a counter in each.
    /// The outline's two reflex corners bound the loops, which once made
    /// them "lobes" cut off without their counters: that candidate painted
    /// both counters over (and the preview, measuring against the strokes,
    /// called it even). Every candidate must keep them.
    #[test]
    fn every_candidate_of_a_figure_eight_keeps_its_counters() {
        let p = |x: f64, y: f64| Point::new(0.25 * x, 0.25 * y);
        let outer: Vec<Point> = [
            (0.5, 0.0),
            (1.5, 0.0),
            (2.0, 0.5),
            (2.0, 1.5),
            (1.8, 2.0),
            (2.0, 2.5),
            (2.0, 3.5),
            (1.5, 4.0),
            (0.5, 4.0),
            (0.0, 3.5),
            (0.0, 2.5),
            (0.2, 2.0),
            (0.0, 1.5),
            (0.0, 0.5),
        ]
        .iter()
        .map(|&(x, y)| p(x, y))
        .collect();
        // Clockwise counters 0.2 m square, 0.15 m of band around them.
        let counter = |y0: f64| vec![p(0.6, y0), p(0.6, y0 + 0.8), p(1.4, y0 + 0.8), p(1.4, y0)];
        let r = Region {
            outer,
            holes: vec![counter(0.6), counter(2.6)],
        };
        let all = candidates(std::slice::from_ref(&r), &bands(), "test").expect("decomposes");
        assert!(all.len() > 1);
        for d in &all {
            assert_decomposition_tiles(std::slice::from_ref(&r), d);
        }
    }

    /// The star `random_star_polygons_tile` found on a clean clone (issue
    /// 31, P1): a strip of its decomposition was wider than the widest
    /// band one pass paints. Kept as a plain test as well as in
    /// proptest-regressions/shape/decompose.txt so it runs whatever seed
    /// the property test draws.
    #[test]
    fn the_star_that_held_a_band_wider_than_a_pass_tiles() {
        let radii = [
            0.9570366644665043,
            0.6681598566749936,
            0.4781911179228048,
            1.1143794053900888,
            0.8790835737214171,
        ];
        assert_tiles(&[super::super::region::from_radii(&radii, 0.0)]);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(12))]
        /// Random star-shaped polygons (a radius per vertex) always tile.
        #[test]
        fn random_star_polygons_tile(radii in proptest::collection::vec(0.4f64..1.2, 5..14)) {
            assert_tiles(&[super::super::region::from_radii(&radii, 0.0)]);
        }
    }
}
