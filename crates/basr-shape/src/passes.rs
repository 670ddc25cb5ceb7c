//! A band made paintable: its ends trimmed where it is narrower than the
//! fan can usefully paint, steep ends left bare, cut where the number of
//! passes its width needs changes and again where its rungs would lean too
//! far, and each piece split into parallel strips at most one pass wide
//! (`decompose` chooses the bands; this holds what is done to each). Pieces
//! and strips share their cut rungs and edges, so the strokes tile the
//! band: no overlap, no gap.

use kurbo::Point;

use super::region::{signed_area, Region};
use super::ShapeError;
use crate::font::Stroke;
use basr_geom::{Edge, Segment, JOIN_TOLERANCE};

/// Ends of a band narrower than this fraction of the narrowest fan band are
/// left unpainted; between it and the narrowest band the fan paints its
/// narrowest band, wider than the shape. assumed: half, which about
/// balances the area left bare against the area sprayed outside on a
/// straight-sided tip (both grow with the square of the cut width).
const CUT_FRACTION: f64 = 0.5;

/// Passes are planned this much narrower than the widest band the nozzle
/// height allows. assumed: 5 % keeps a pass inside the reach after the
/// tilt's height compensation.
const PASS_MARGIN: f64 = 0.95;

/// A piece is cut again where a rung would lean more than this from the
/// partner its arc-length position gives on the other edge (tan of the
/// angle). assumed: 30°; `plan::knots::pace` keeps the film on leaning
/// rungs, the cut keeps the fan's footprint close to square to the travel.
const MAX_LEAN: f64 = 0.577;

/// Time a stroke costs besides its painting (gun on and off, lead-in and
/// lead-out, the air move to the next). assumed: 2 s, about what today's
/// planner spends between the strokes of a letter.
const STROKE_OVERHEAD_S: f64 = 2.0;

/// Shortest piece a band is cut into (m). assumed: the nozzle needs about
/// this long to reach painting speed from rest (0.16 m/s at about 1 m/s²
/// takes 13 mm, but the tilt and base accelerate too); shorter pieces
/// paint heavy film at their ends.
const MIN_PIECE_M: f64 = 0.25;

/// Every stroke end paints heavy over about this length of its end rung
/// (the gun opens and closes while the nozzle and the fan's height and
/// tilt settle; the previews of the test shapes show 2–3 cm of heavy film
/// at ends). assumed: 3 cm; it makes the comparison prefer fewer and
/// narrower stroke ends (a tip ends on a point and costs nothing).
const END_HEAVY_M: f64 = 0.03;

/// A band end is left bare where its width changes faster than this per
/// metre of travel (and it is under one pass wide): the nozzle height
/// follows the width (001 eq. 2.5), and the previews of the heart's lobes
/// show film up to 4× where a dome's top is swept across (the vertical
/// joint's acceleration holds the nozzle back). assumed: 6 (the edges
/// leave the travel at 72°); the heart loses 0.8 % of its area to it, two
/// lens-shaped caps 4 cm deep that the job reports.
const MAX_WIDTH_RATE: f64 = 6.0;

/// A ring-following strip's edges may differ in length by this factor.
/// assumed: 1.5; the ring test shape's bands (radii 0.7 and 1.0, 1.43)
/// paint cv ≤ 0.04 at every height from 0.8 to 3 m with the tilt.
const MAX_EDGE_RATIO: f64 = 1.5;

/// Most concentric passes [`MAX_EDGE_RATIO`] asks for. assumed: 6, beyond
/// any test shape (the shield 1.2 m tall needs 3).
const MAX_RING_PASSES: usize = 6;

/// Strips with less area than this (m²) are float slivers. assumed: a
/// square millimetre.
const SLIVER_M2: f64 = 1e-6;

/// Rung spacing of the narrow-place analysis (m). assumed: 5 mm, a
/// quarter of the default rung spacing.
const REPORT_STEP_M: f64 = 0.005;

/// The fan's limits and rates the decomposition plans for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bands {
    /// Narrowest band: what the fan paints from the lowest nozzle height (m).
    pub min_width_m: f64,
    /// Widest band one pass paints, from the highest nozzle height (m).
    pub max_width_m: f64,
    /// Paint rate: speed × width (m²/s, SPEC §3).
    pub k_m2ps: f64,
    /// End-effector yaw rate limit (rad/s).
    pub yaw_rate_rad_s: f64,
}

impl Bands {
    /// The bands `robot`'s nozzle paints: narrowest from the lowest tip
    /// height, widest from the highest (its paint law), at its fan joint's
    /// rate limit.
    pub fn of(robot: &basr_robot::AnyRobot) -> Bands {
        let law = basr_robot::paint_law::paint_law(robot);
        Bands {
            min_width_m: law.width_at_height(law.min_height_m),
            max_width_m: law.max_width_m(),
            k_m2ps: law.k_m2ps,
            yaw_rate_rad_s: robot.limits()[robot.fan_joint()].max_vel,
        }
    }
}

/// A run of rungs (left point, right point) in travel order (m).
#[derive(Clone, Debug, PartialEq)]
pub struct Band {
    pub rungs: Vec<(Point, Point)>,
}

impl Band {
    fn width(&self, i: usize) -> f64 {
        (self.rungs[i].1 - self.rungs[i].0).hypot()
    }
    /// Area between rungs i and i+1 (rungs of a band never cross).
    fn tile(&self, i: usize) -> f64 {
        let ((a, b), (c, d)) = (self.rungs[i], self.rungs[i + 1]);
        signed_area(&[a, b, d, c]).abs()
    }
}

/// A place narrower than the fan's narrowest band.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Narrow {
    /// Where it is narrowest (m, shape frame: lower-left corner at the origin).
    pub at: Point,
    /// Its narrowest width (m).
    pub width_m: f64,
    /// How much narrower than the fan's narrowest band (m).
    pub shortfall_m: f64,
    /// Length of the narrow stretch along the band (m).
    pub length_m: f64,
    /// Area left bare where it is narrower than the cut (m²).
    pub unpainted_m2: f64,
    /// Area the narrowest band sprays outside the shape (m²).
    pub overspray_m2: f64,
}

/// A band end left bare because its width changes faster than the nozzle
/// height follows (a dome's top swept across: the rungs shrink from a pass
/// to nothing within centimetres).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Steep {
    /// The middle of the rung where the band is cut (m, shape frame).
    pub at: Point,
    /// Width of that rung (m).
    pub width_m: f64,
    /// Depth of the bare end along the travel (m).
    pub length_m: f64,
    /// Its area (m²).
    pub unpainted_m2: f64,
}

/// What painting some bands takes.
#[derive(Default)]
pub(super) struct Painted {
    pub(super) strokes: Vec<Stroke>,
    pub(super) narrow: Vec<Narrow>,
    pub(super) steep: Vec<Steep>,
    pub(super) time_s: f64,
    /// Area painted wrong: left bare, sprayed outside, or in strips too
    /// short to reach painting speed (m²).
    pub(super) bad_m2: f64,
}

impl Painted {
    pub(super) fn append(&mut self, mut o: Painted) {
        self.strokes.append(&mut o.strokes);
        self.narrow.append(&mut o.narrow);
        self.steep.append(&mut o.steep);
        self.time_s += o.time_s;
        self.bad_m2 += o.bad_m2;
    }
}

/// A band's outline as a region (right edge forward, left edge back: counter-clockwise).
pub(super) fn band_region(b: &Band) -> Region {
    let mut outer: Vec<Point> = b.rungs.iter().map(|r| r.1).collect();
    outer.extend(b.rungs.iter().rev().map(|r| r.0));
    outer.dedup_by(|a, b| (*a - *b).hypot() < 2.0 * JOIN_TOLERANCE);
    Region {
        outer,
        holes: vec![],
    }
}

/// How a band's pass pieces are made beyond [`by_passes`].
#[derive(Clone, Copy, Default)]
pub(super) struct Passes {
    /// Short pieces joined to a neighbour ([`merge_short`]).
    pub(super) merge: bool,
    /// Curved pieces split into concentric passes ([`ring_passes`]).
    pub(super) concentric: bool,
}

/// Paint the bands: tips trimmed, steep ends cut, pass pieces made by
/// `rule`, each split into strips.
pub(super) fn paint(
    bands: &[Band],
    lim: &Bands,
    origin: &str,
    rule: Passes,
) -> Result<Painted, ShapeError> {
    let mut out = Painted::default();
    let pass = lim.max_width_m * PASS_MARGIN;
    for band in bands {
        let (kept, mut nar) = trim(band, lim);
        let mut pieces = vec![];
        for b in &kept {
            let (piece, mut steep) = steep_ends(b, lim.max_width_m);
            out.bad_m2 += steep.iter().map(|s| s.unpainted_m2).sum::<f64>();
            out.steep.append(&mut steep);
            pieces.extend(piece);
        }
        let kept = pieces;
        out.bad_m2 += nar
            .iter()
            .map(|n| n.unpainted_m2 + n.overspray_m2)
            .sum::<f64>();
        out.narrow.append(&mut nar);
        for piece in kept {
            for (p, n) in by_passes(&piece, pass, rule.merge.then_some(lim.min_width_m)) {
                for q in by_lean(&p) {
                    let mut k = passes_for(&q, n, lim);
                    if rule.concentric {
                        k = k.max(ring_passes(&q, lim));
                    }
                    for s in strips(&q, k) {
                        // A sliver between two outline vertices a float's
                        // width apart has no length to paint.
                        let side = |f: fn(&(Point, Point)) -> Point| {
                            polyline_len(&s.rungs.iter().map(f).collect::<Vec<_>>())
                        };
                        let area: f64 = (0..s.rungs.len() - 1).map(|i| s.tile(i)).sum();
                        if side(|r| r.0).min(side(|r| r.1)) <= 4.0 * JOIN_TOLERANCE
                            || area <= SLIVER_M2
                        {
                            continue;
                        }
                        if mid_len(&s) < MIN_PIECE_M {
                            out.bad_m2 += area;
                        }
                        out.bad_m2 += END_HEAVY_M * (s.width(0) + s.width(s.rungs.len() - 1));
                        out.time_s += predicted_time(&s, lim) + STROKE_OVERHEAD_S;
                        out.strokes.push(stroke(&s, origin)?);
                    }
                }
            }
        }
    }
    Ok(out)
}

fn lerp_rung(a: (Point, Point), b: (Point, Point), t: f64) -> (Point, Point) {
    (a.0.lerp(b.0, t), a.1.lerp(b.1, t))
}

/// Where between rungs i and i+1 the width crosses `w` (linear in width).
fn cross_at(band: &Band, i: usize, w: f64) -> (Point, Point) {
    let (w0, w1) = (band.width(i), band.width(i + 1));
    let t = if (w1 - w0).abs() < 1e-15 {
        0.5
    } else {
        ((w - w0) / (w1 - w0)).clamp(0.0, 1.0)
    };
    lerp_rung(band.rungs[i], band.rungs[i + 1], t)
}

/// Cut the band where it is narrower than the cut width, and list every
/// stretch narrower than the fan's narrowest band.
fn trim(band: &Band, lim: &Bands) -> (Vec<Band>, Vec<Narrow>) {
    let cut = lim.min_width_m * CUT_FRACTION;
    let n = band.rungs.len();
    let mut kept = vec![];
    let mut cur: Vec<(Point, Point)> = vec![];
    for i in 0..n {
        let w = band.width(i);
        if w >= cut {
            if cur.is_empty() && i > 0 {
                cur.push(cross_at(band, i - 1, cut));
            }
            cur.push(band.rungs[i]);
        } else if !cur.is_empty() {
            cur.push(cross_at(band, i - 1, cut));
            kept.push(Band {
                rungs: std::mem::take(&mut cur),
            });
        }
    }
    if cur.len() >= 2 {
        kept.push(Band { rungs: cur });
    }
    kept.retain(|b| b.rungs.len() >= 2);
    // Narrow stretches, tile by tile on a finer copy (a sweep cell's rungs
    // are only at the outline's vertices; its width is linear between them).
    let band = &refined(band, REPORT_STEP_M);
    let n = band.rungs.len();
    let mut narrow: Vec<Narrow> = vec![];
    let mut open: Option<Narrow> = None;
    for i in 0..n.saturating_sub(1) {
        let (w0, w1) = (band.width(i), band.width(i + 1));
        let wm = 0.5 * (w0 + w1);
        if wm < lim.min_width_m {
            let tile = band.tile(i);
            let len = (lerp_mid(band.rungs[i + 1]) - lerp_mid(band.rungs[i])).hypot();
            let nr = open.get_or_insert(Narrow {
                at: lerp_mid(band.rungs[i]),
                width_m: f64::INFINITY,
                shortfall_m: 0.0,
                length_m: 0.0,
                unpainted_m2: 0.0,
                overspray_m2: 0.0,
            });
            let wmin = w0.min(w1);
            if wmin < nr.width_m {
                nr.width_m = wmin;
                nr.at = if w0 < w1 {
                    lerp_mid(band.rungs[i])
                } else {
                    lerp_mid(band.rungs[i + 1])
                };
            }
            nr.length_m += len;
            if wm < cut {
                nr.unpainted_m2 += tile;
            } else if wm > 0.0 {
                nr.overspray_m2 += tile * (lim.min_width_m / wm - 1.0);
            }
        } else if let Some(nr) = open.take() {
            narrow.push(nr);
        }
    }
    narrow.extend(open);
    for nr in &mut narrow {
        nr.shortfall_m = lim.min_width_m - nr.width_m;
    }
    (kept, narrow)
}

/// The band without the ends where its width changes faster than
/// [`MAX_WIDTH_RATE`] per metre of travel while under `below` (one pass)
/// wide, and those ends.
fn steep_ends(b: &Band, below: f64) -> (Option<Band>, Vec<Steep>) {
    let fine = refined(b, REPORT_STEP_M);
    let n = fine.rungs.len();
    let fast = |i: usize| {
        let ds = (lerp_mid(fine.rungs[i + 1]) - lerp_mid(fine.rungs[i])).hypot();
        let (w0, w1) = (fine.width(i), fine.width(i + 1));
        (w1 - w0).abs() > MAX_WIDTH_RATE * ds && w0.min(w1) < below
    };
    let (Some(first), Some(last)) = (
        (0..n - 1).find(|&i| !fast(i)),
        (0..n - 1).rfind(|&i| !fast(i)),
    ) else {
        return (None, vec![]);
    };
    let last = last + 1;
    let end = |range: std::ops::Range<usize>, cut: usize| {
        let area: f64 = range.clone().map(|i| fine.tile(i)).sum();
        let ends = [range.start, range.end];
        let length = (lerp_mid(fine.rungs[ends[1]]) - lerp_mid(fine.rungs[ends[0]])).hypot();
        (area > SLIVER_M2).then(|| Steep {
            at: lerp_mid(fine.rungs[cut]),
            width_m: fine.width(cut),
            length_m: length,
            unpainted_m2: area,
        })
    };
    let mut steep: Vec<Steep> = vec![];
    steep.extend(end(0..first, first));
    steep.extend(end(last..n - 1, last));
    if steep.is_empty() {
        return (Some(b.clone()), steep);
    }
    let kept = (last > first).then(|| Band {
        rungs: fine.rungs[first..=last].to_vec(),
    });
    (kept, steep)
}

/// Rungs at most `step` apart (midpoint travel), by linear interpolation.
fn refined(band: &Band, step: f64) -> Band {
    let mut rungs = vec![band.rungs[0]];
    for w in band.rungs.windows(2) {
        let d = (lerp_mid(w[1]) - lerp_mid(w[0])).hypot();
        let k = ((d / step).ceil() as usize).clamp(1, 10_000);
        for j in 1..=k {
            rungs.push(lerp_rung(w[0], w[1], j as f64 / k as f64));
        }
    }
    Band { rungs }
}

fn lerp_mid(r: (Point, Point)) -> Point {
    r.0.midpoint(r.1)
}

/// Cut where the number of passes the width needs changes; each piece with
/// its pass count (the most any of its rungs needs); with `merge` (the
/// fan's narrowest band) short pieces are joined to a neighbour ([`merge_short`]).
fn by_passes(band: &Band, pass: f64, merge: Option<f64>) -> Vec<(Band, usize)> {
    // A cut rung is exactly `k · pass` wide: round-off must not count it as k + 1.
    let count = |w: f64| ((w / pass - 1e-9).ceil() as usize).max(1);
    let n = band.rungs.len();
    let mut out = vec![];
    let mut cur = vec![band.rungs[0]];
    let mut k = count(band.width(0));
    for i in 1..n {
        let ki = count(band.width(i));
        if ki != k {
            let edge = k.min(ki) as f64 * pass;
            let r = cross_at(band, i - 1, edge);
            cur.push(r);
            out.push((
                Band {
                    rungs: std::mem::take(&mut cur),
                },
                k,
            ));
            cur.push(r);
            k = ki;
        }
        cur.push(band.rungs[i]);
    }
    out.push((Band { rungs: cur }, k));
    let out: Vec<(Band, usize)> = out
        .into_iter()
        .map(|(mut b, k)| {
            b.rungs
                .dedup_by(|a, b| (a.0 - b.0).hypot() < 1e-9 && (a.1 - b.1).hypot() < 1e-9);
            let k = (0..b.rungs.len())
                .map(|i| count(b.width(i)))
                .max()
                .unwrap_or(k);
            (b, k)
        })
        .filter(|(b, _)| b.rungs.len() >= 2)
        .collect();
    match merge {
        Some(min_width) => merge_short(out, min_width),
        None => out,
    }
}

/// Pieces shorter than [`MIN_PIECE_M`] joined to a neighbour (the one
/// needing more passes), painted with the larger count: a short piece
/// between two pass-count changes (a pentagon swept from an edge: one pass
/// where it starts, two in its middle) would start from rest and end before
/// the nozzle reaches painting speed, painting heavy film; its strips in
/// the merged piece are narrower than a pass but as long as the
/// neighbour's. A piece whose strips would then be narrower than the fan's
/// narrowest band `min_width` stays (a tip split in two paints the narrow
/// band twice over its middle).
pub(super) fn merge_short(mut pieces: Vec<(Band, usize)>, min_width: f64) -> Vec<(Band, usize)> {
    let narrowest = |b: &Band| {
        (0..b.rungs.len())
            .map(|i| b.width(i))
            .fold(f64::INFINITY, f64::min)
    };
    let mut i = 0;
    while i < pieces.len() && pieces.len() > 1 {
        let j = match (i.checked_sub(1), (i + 1 < pieces.len()).then_some(i + 1)) {
            (Some(a), Some(b)) if pieces[b].1 > pieces[a].1 => b,
            (Some(a), _) => a,
            (None, Some(b)) => b,
            (None, None) => break,
        };
        let k = pieces[i].1.max(pieces[j].1);
        if mid_len(&pieces[i].0) >= MIN_PIECE_M || narrowest(&pieces[i].0) / (k as f64) < min_width
        {
            i += 1;
            continue;
        }
        let (lo, hi) = (i.min(j), i.max(j));
        let (b, _) = pieces.remove(hi);
        let a = &mut pieces[lo];
        a.0.rungs.extend(b.rungs.into_iter().skip(1));
        a.1 = k;
        i = 0;
    }
    pieces
}

/// Cumulative arc-length fractions of one side's points.
fn fractions(pts: &[Point]) -> Vec<f64> {
    let mut s = vec![0.0];
    for w in pts.windows(2) {
        s.push(s[s.len() - 1] + (w[1] - w[0]).hypot());
    }
    let total = s[s.len() - 1].max(1e-15);
    s.iter().map(|v| v / total).collect()
}

/// Cut the band where equal-arc-length rungs would lean too far.
fn by_lean(band: &Band) -> Vec<Band> {
    let n = band.rungs.len();
    if n < 3 {
        return vec![band.clone()];
    }
    let l: Vec<Point> = band.rungs.iter().map(|r| r.0).collect();
    let r: Vec<Point> = band.rungs.iter().map(|r| r.1).collect();
    let (fl, fr) = (fractions(&l), fractions(&r));
    let len_r = polyline_len(&r);
    let len_l = polyline_len(&l);
    let mut worst = (0.0, 0usize);
    for i in 1..n - 1 {
        let shift = (fl[i] - fr[i]).abs() * 0.5 * (len_l + len_r);
        let lean = shift / band.width(i).max(1e-9);
        if lean > worst.0 {
            worst = (lean, i);
        }
    }
    let i = worst.1;
    let short = |r: &[(Point, Point)]| mid_len(&Band { rungs: r.to_vec() }) < MIN_PIECE_M;
    if worst.0 <= MAX_LEAN || short(&band.rungs[..=i]) || short(&band.rungs[i..]) {
        return vec![band.clone()];
    }
    let mut out = by_lean(&Band {
        rungs: band.rungs[..=i].to_vec(),
    });
    out.extend(by_lean(&Band {
        rungs: band.rungs[i..].to_vec(),
    }));
    out
}

/// Length of a band's midline (m).
pub(super) fn mid_len(b: &Band) -> f64 {
    polyline_len(&b.rungs.iter().map(|r| lerp_mid(*r)).collect::<Vec<_>>())
}

pub(super) fn polyline_len(p: &[Point]) -> f64 {
    p.windows(2).map(|w| (w[1] - w[0]).hypot()).sum()
}

/// The pass count, from `n` up, at which every rung the planner will cut
/// (equal arc length on each edge, which may lean) is at most one pass
/// wide; never so many that a strip is narrower than the fan's narrowest
/// band where the piece is wide enough for `n` (a tip split in two would
/// paint each half with the full narrow band, twice over the middle).
fn passes_for(q: &Band, n: usize, lim: &Bands) -> usize {
    let max_width_m = lim.max_width_m;
    let narrowest = (0..q.rungs.len())
        .map(|i| q.width(i))
        .fold(f64::INFINITY, f64::min);
    let fits = |k: usize| {
        strips(q, k).iter().all(|s| {
            let l: Vec<Point> = s.rungs.iter().map(|r| r.0).collect();
            let r: Vec<Point> = s.rungs.iter().map(|r| r.1).collect();
            let (fl, fr) = (fractions(&l), fractions(&r));
            // Between two fractions where either side has a vertex both
            // points move linearly, so the rung's length is convex there and
            // greatest at an end: checking every vertex fraction of both
            // sides finds the widest rung exactly. 129 equal fractions missed
            // one 0.16 % wider than a pass between them (issue 31, P1: a
            // star whose strip's 50 equal-arc-length rungs held one).
            fl.iter().chain(&fr).all(|&t| {
                (at_fraction(&r, &fr, t) - at_fraction(&l, &fl, t)).hypot() <= max_width_m
            })
        })
    };
    let wide_enough = |k: usize| k == n || narrowest / k as f64 >= lim.min_width_m;
    // Fitting one pass comes first: a rung wider than the fan's widest band
    // leaves its ends thin.
    (n..n + 4)
        .take_while(|&k| wide_enough(k))
        .find(|&k| fits(k))
        .or_else(|| (n..n + 4).find(|&k| fits(k)))
        .unwrap_or(n + 4)
}

/// Concentric passes for a band curving around a hole: the fewest strips
/// whose edges differ in length by at most [`MAX_EDGE_RATIO`] (the film
/// across a strip goes as the inverse of its edges' travel: a wide band
/// around a small hole paints its inner side heavy), but none narrower
/// than the fan's narrowest band.
pub(super) fn ring_passes(q: &Band, lim: &Bands) -> usize {
    let narrowest = (0..q.rungs.len())
        .map(|i| q.width(i))
        .fold(f64::INFINITY, f64::min);
    let even = |k: usize| {
        strips(q, k).iter().all(|s| {
            let l = polyline_len(&s.rungs.iter().map(|r| r.0).collect::<Vec<_>>());
            let r = polyline_len(&s.rungs.iter().map(|r| r.1).collect::<Vec<_>>());
            l.max(r) <= MAX_EDGE_RATIO * l.min(r)
        })
    };
    let mut k = 1;
    while !even(k) && narrowest / (k + 1) as f64 >= lim.min_width_m && k < MAX_RING_PASSES {
        k += 1;
    }
    k
}

/// The point at arc-length fraction `t` of a polyline with fractions `f`.
fn at_fraction(p: &[Point], f: &[f64], t: f64) -> Point {
    let i = f.partition_point(|&v| v < t).clamp(1, f.len() - 1);
    let u = ((t - f[i - 1]) / (f[i] - f[i - 1]).max(1e-15)).clamp(0.0, 1.0);
    p[i - 1].lerp(p[i], u)
}

/// The band as `n` parallel strips, left to right.
fn strips(band: &Band, n: usize) -> Vec<Band> {
    (0..n)
        .map(|j| {
            let (t0, t1) = (j as f64 / n as f64, (j + 1) as f64 / n as f64);
            Band {
                rungs: band
                    .rungs
                    .iter()
                    .map(|(a, b)| (a.lerp(*b, t0), a.lerp(*b, t1)))
                    .collect(),
            }
        })
        .collect()
}

/// Gun-on time of one strip: each tile at the film's rate over the width the
/// fan covers (never less than its narrowest band), or the yaw joint's time
/// to turn the fan, whichever is longer.
fn predicted_time(s: &Band, lim: &Bands) -> f64 {
    let mut paint = 0.0;
    let mut yaw = 0.0;
    for i in 0..s.rungs.len() - 1 {
        let w = 0.5 * (s.width(i) + s.width(i + 1));
        let cover = if w > 0.0 {
            lim.min_width_m.max(w) / w
        } else {
            1.0
        };
        paint += s.tile(i) * cover / lim.k_m2ps;
        let d0 = s.rungs[i].1 - s.rungs[i].0;
        let d1 = s.rungs[i + 1].1 - s.rungs[i + 1].0;
        yaw += d0.cross(d1).atan2(d0.dot(d1)).abs();
    }
    paint.max(yaw / lim.yaw_rate_rad_s)
}

fn edge(pts: impl Iterator<Item = Point>, origin: &str) -> Result<Edge, ShapeError> {
    let mut v: Vec<Point> = vec![];
    for p in pts {
        if v.last()
            .is_none_or(|q| (*q - p).hypot() > 2.0 * JOIN_TOLERANCE)
        {
            v.push(p);
        }
    }
    let segs = v.windows(2).map(|w| Segment::line(w[0], w[1])).collect();
    Edge::new(segs).map_err(|e| {
        ShapeError::invalid(
            origin,
            format!("a band edge could not be built ({e}); the outline is degenerate there"),
        )
    })
}

fn stroke(s: &Band, origin: &str) -> Result<Stroke, ShapeError> {
    Ok(Stroke {
        left: edge(s.rungs.iter().map(|r| r.0), origin)?,
        right: edge(s.rungs.iter().map(|r| r.1), origin)?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bands() -> Bands {
        Bands::of(&basr_robot::AnyRobot::load_or_default(None).expect("embedded robot"))
    }

    #[test]
    fn a_pointed_tip_is_trimmed_and_reported_with_its_shortfall() {
        // A band 0.3 m wide narrowing to a point over 2 m.
        let band = Band {
            rungs: vec![
                (Point::new(0.0, 0.0), Point::new(0.3, 0.0)),
                (Point::new(0.15, 2.0), Point::new(0.15, 2.0)),
            ],
        };
        let lim = bands();
        let (kept, narrow) = trim(&band, &lim);
        assert_eq!(kept.len(), 1);
        let end = kept[0].rungs.last().copied().expect("rungs");
        let cut = (end.1 - end.0).hypot();
        assert!(
            (cut - CUT_FRACTION * lim.min_width_m).abs() < 1e-9,
            "cut at {cut}"
        );
        assert_eq!(narrow.len(), 1);
        let tip = narrow[0];
        assert!(tip.at.y > 1.99 && tip.width_m < 1e-9);
        assert!((tip.shortfall_m - lim.min_width_m).abs() < 1e-9);
        // Narrower than the fan's narrowest band over 2 m × 0.097 / 0.3.
        let long = 2.0 * lim.min_width_m / 0.3;
        assert!(
            (tip.length_m - long).abs() < 0.01,
            "{} vs {long}",
            tip.length_m
        );
        // Bare: the last half of that length, a triangle.
        let bare = 0.5 * (0.5 * long) * (0.5 * lim.min_width_m);
        assert!(
            (tip.unpainted_m2 - bare).abs() < 0.05 * bare,
            "{} vs {bare}",
            tip.unpainted_m2
        );
        assert!(tip.overspray_m2 > 0.0);
    }
}
