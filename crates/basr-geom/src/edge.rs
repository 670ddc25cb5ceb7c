//! An edge: a G0 chain of segments, measured and split by arc length.

use kurbo::{Affine, Point, Vec2};

use super::{integrate, Curve, GeomError, Segment, DEFAULT_ACCURACY, JOIN_TOLERANCE};

/// Parameters at increasing arc lengths `targets` along one segment, each
/// within `accuracy` of its target: safeguarded Newton steps on
/// s(t) = ∫|P'|, integrating only the short stretch from the previous
/// solution, so a run of targets costs little more than one arc length.
pub(crate) fn params_at_lengths(seg: &Segment, targets: &[f64], accuracy: f64) -> Vec<f64> {
    if let Segment::Line(_) = seg {
        return targets
            .iter()
            .map(|&s| seg.inv_arclen(s, accuracy))
            .collect();
    }
    let speed = |t: f64| seg.deriv(t).hypot();
    let tol = 0.1 * accuracy;
    let total = integrate(speed, 0.0, 1.0, tol);
    // (t, s(t)) of the last solution: integrals start from here.
    let (mut t0, mut s0) = (0.0, 0.0);
    let mut out = Vec::with_capacity(targets.len());
    for &target in targets {
        if target <= 0.0 {
            out.push(0.0);
            continue;
        }
        if target >= total {
            out.push(1.0);
            continue;
        }
        let (mut lo, mut hi) = (t0, 1.0);
        let mut t = (t0 + (target - s0) / speed(t0).max(1e-12)).clamp(lo, hi);
        let mut found = t;
        for _ in 0..60 {
            let s = if t >= t0 {
                s0 + integrate(speed, t0, t, tol)
            } else {
                s0 - integrate(speed, t, t0, tol)
            };
            let err = s - target;
            found = t;
            if err.abs() <= accuracy {
                break;
            }
            if err > 0.0 {
                hi = t;
            } else {
                lo = t;
            }
            let v = speed(t);
            let newton = t - err / v.max(1e-12);
            t = if v > 1e-12 && newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
        }
        // Move the integration anchor forward to the solution.
        s0 += integrate(speed, t0, found, tol);
        t0 = found;
        out.push(found);
    }
    out
}

/// A continuous chain of segments, each starting where the previous ends
/// (within [`JOIN_TOLERANCE`]). Lengths are measured once, at
/// [`DEFAULT_ACCURACY`].
#[derive(Debug, Clone, PartialEq)]
pub struct Edge {
    segments: Vec<Segment>,
    /// cum[i] = arc length from the edge's start to the start of segment i;
    /// one more entry than segments (the last is the total).
    cum: Vec<f64>,
}

impl Edge {
    /// Build an edge, checking that it is non-empty, finite, non-degenerate
    /// and continuous.
    pub fn new(segments: Vec<Segment>) -> Result<Edge, GeomError> {
        if segments.is_empty() {
            return Err(GeomError::Empty);
        }
        let mut cum = Vec::with_capacity(segments.len() + 1);
        cum.push(0.0);
        for (index, seg) in segments.iter().enumerate() {
            if !seg.is_finite() {
                return Err(GeomError::NotFinite { index });
            }
            if index > 0 {
                let prev_end = segments[index - 1].end();
                let start = seg.start();
                let gap = (start - prev_end).hypot();
                if gap > JOIN_TOLERANCE {
                    return Err(GeomError::Gap {
                        index,
                        prev_end,
                        start,
                        gap,
                    });
                }
            }
            let len = seg.arclen(DEFAULT_ACCURACY);
            if !len.is_finite() {
                return Err(GeomError::TooLong { index });
            }
            if len <= JOIN_TOLERANCE {
                return Err(GeomError::Degenerate { index });
            }
            cum.push(cum[index] + len);
        }
        Ok(Edge { segments, cum })
    }

    /// The segments, in order.
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }

    /// Total arc length.
    pub fn length(&self) -> f64 {
        self.cum[self.segments.len()]
    }

    /// First point.
    pub fn start(&self) -> Point {
        self.segments[0].start()
    }

    /// Last point.
    pub fn end(&self) -> Point {
        self.segments[self.segments.len() - 1].end()
    }

    /// Segment index and its parameter at arc length `s` from the start
    /// (clamped to the edge).
    fn locate(&self, s: f64, accuracy: f64) -> (usize, f64) {
        let s = s.clamp(0.0, self.length());
        // Last segment whose start is at or before s.
        let i = match self.cum[1..].iter().position(|&c| s <= c) {
            Some(i) => i,
            None => self.segments.len() - 1,
        };
        let seg = &self.segments[i];
        let local = s - self.cum[i];
        let seg_len = self.cum[i + 1] - self.cum[i];
        let t = if local <= 0.0 {
            0.0
        } else if local >= seg_len {
            1.0
        } else {
            seg.inv_arclen(local, accuracy)
        };
        (i, t)
    }

    /// The point at arc length `s` from the start.
    pub fn point_at_length(&self, s: f64) -> Point {
        let (i, t) = self.locate(s, DEFAULT_ACCURACY);
        self.segments[i].eval(t)
    }

    /// The unit tangent (direction of travel) at arc length `s`.
    pub fn tangent_at_length(&self, s: f64) -> Vec2 {
        let (i, t) = self.locate(s, DEFAULT_ACCURACY);
        let d = self.segments[i].deriv(t);
        if d.hypot() > 1e-12 {
            return d.normalize();
        }
        // A cusp of the parametrisation: use a short chord instead.
        let h = 1e-6 * self.length();
        let chord = self.point_at_length(s + h) - self.point_at_length(s - h);
        if chord.hypot() > 0.0 {
            chord.normalize()
        } else {
            Vec2::ZERO
        }
    }

    /// n + 1 points splitting the edge into n pieces of equal arc length
    /// (001 §2.4, fig. 2.7), exact to [`DEFAULT_ACCURACY`] rather than the
    /// seed's chord interpolation. The first and last points are the edge's
    /// ends. `n = 0` is treated as 1.
    pub fn subdivide(&self, n: usize) -> Vec<Point> {
        let n = n.max(1);
        let total = self.length();
        let mut out = Vec::with_capacity(n + 1);
        out.push(self.start());
        // Targets are increasing: hand each segment the ones that fall in it
        // and let it walk forward (much cheaper than n independent searches).
        let mut k = 1;
        for (i, seg) in self.segments.iter().enumerate() {
            let mut local = Vec::new();
            while k < n {
                let s = total * k as f64 / n as f64;
                if s > self.cum[i + 1] && i + 1 < self.segments.len() {
                    break;
                }
                local.push(s - self.cum[i]);
                k += 1;
            }
            if local.is_empty() {
                continue;
            }
            let ts = params_at_lengths(seg, &local, DEFAULT_ACCURACY);
            out.extend(ts.into_iter().map(|t| seg.eval(t)));
        }
        out.push(self.end());
        out
    }

    /// k points at equal arc length along the edge, both ends included
    /// (k ≥ 2), for drawing and export.
    pub fn sample(&self, k: usize) -> Vec<Point> {
        self.subdivide(k.max(2) - 1)
    }

    /// The edge mapped by an affine transform.
    pub fn transformed(&self, m: &Affine) -> Edge {
        let segments: Vec<Segment> = self.segments.iter().map(|s| s.transformed(m)).collect();
        Edge::from_trusted(segments)
    }

    /// The edge run from its end to its start.
    pub fn reversed(&self) -> Edge {
        let segments: Vec<Segment> = self.segments.iter().rev().map(|s| s.reversed()).collect();
        Edge::from_trusted(segments)
    }

    /// The edge followed by `other` (which must start where this one ends).
    pub fn joined(&self, other: &Edge) -> Result<Edge, GeomError> {
        let mut segments = self.segments.clone();
        segments.extend(other.segments.iter().cloned());
        Edge::new(segments)
    }

    /// Rebuild the cumulative lengths of segments already known to chain.
    fn from_trusted(segments: Vec<Segment>) -> Edge {
        let mut cum = Vec::with_capacity(segments.len() + 1);
        cum.push(0.0);
        for (i, seg) in segments.iter().enumerate() {
            cum.push(cum[i] + seg.arclen(DEFAULT_ACCURACY));
        }
        Edge { segments, cum }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Cardinal, Conic};
    use proptest::prelude::*;

    fn s_outer() -> Edge {
        let c = Cardinal::new(
            [
                (0.0, 6.0).into(),
                (2.0, -0.2).into(),
                (4.0, 6.0).into(),
                (2.0, 8.0).into(),
            ],
            1.0,
        );
        Edge::new(vec![
            Segment::Cardinal(c),
            Segment::line((4.0, 6.0), (4.0, 9.0)),
        ])
        .unwrap()
    }

    #[test]
    fn refuses_gaps_and_degenerate_segments() {
        let e = Edge::new(vec![
            Segment::line((0.0, 0.0), (1.0, 0.0)),
            Segment::line((1.1, 0.0), (2.0, 0.0)),
        ]);
        assert!(matches!(e, Err(GeomError::Gap { index: 1, .. })));
        let e = Edge::new(vec![Segment::line((0.0, 0.0), (0.0, 0.0))]);
        assert!(matches!(e, Err(GeomError::Degenerate { index: 0 })));
        assert!(matches!(Edge::new(vec![]), Err(GeomError::Empty)));
        let e = Edge::new(vec![Segment::line((f64::NAN, 0.0), (1.0, 0.0))]);
        assert!(matches!(e, Err(GeomError::NotFinite { index: 0 })));
        // Finite ends whose distance overflows: not "zero length".
        let e = Edge::new(vec![Segment::line((1.0, 0.0), (1.0, 1e300))]);
        assert!(matches!(e, Err(GeomError::TooLong { index: 0 })));
    }

    #[test]
    fn subdivision_ends_and_spacing() {
        let e = s_outer();
        let pts = e.subdivide(60);
        assert_eq!(pts.len(), 61);
        assert_eq!(pts[0], e.start());
        assert_eq!(pts[60], e.end());
        // The last 3 units are straight: points there lie on x = 4.
        let step = e.length() / 60.0;
        let straight = (3.0 / step).floor() as usize;
        for p in &pts[60 - straight..] {
            assert!((p.x - 4.0).abs() < 1e-9);
        }
    }

    #[test]
    fn transform_and_reverse() {
        let e = s_outer();
        let m = Affine::new([1.0, 0.0, 0.0, -1.0, 0.0, 25.0]); // y → 25 − y
        let f = e.transformed(&m);
        assert!((f.length() - e.length()).abs() < 1e-9);
        assert!((f.start() - Point::new(2.0, 25.2)).hypot() < 1e-12);
        let r = e.reversed();
        assert!((r.length() - e.length()).abs() < 1e-9);
        let a = e.point_at_length(2.5);
        let b = r.point_at_length(r.length() - 2.5);
        assert!((a - b).hypot() < 1e-8);
        let t = e.tangent_at_length(0.0);
        assert!((t - Vec2::new(1.0, 0.0)).hypot() < 1e-12);
    }

    /// Composite Simpson rule with `n` (even) intervals: an arc-length
    /// reference that shares no code with `quad.rs` or kurbo.
    fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
        let h = (b - a) / n as f64;
        let inner: f64 = (1..n)
            .map(|i| f(a + h * i as f64) * if i % 2 == 1 { 4.0 } else { 2.0 })
            .sum();
        (f(a) + inner + f(b)) * h / 3.0
    }

    /// Appendix A's cardinal polynomial (a = 1) and its derivative in t,
    /// written out independently of `Cardinal`.
    fn appendix_cardinal(p: [f64; 4], t: f64) -> (f64, f64) {
        let v = (-t * t * t + 2.0 * t * t - t) * p[0]
            + (t * t * t - 2.0 * t * t + 1.0) * p[1]
            + (-t * t * t + t * t + t) * p[2]
            + (t * t * t - t * t) * p[3];
        let d = (-3.0 * t * t + 4.0 * t - 1.0) * p[0]
            + (3.0 * t * t - 4.0 * t) * p[1]
            + (-3.0 * t * t + 2.0 * t + 1.0) * p[2]
            + (3.0 * t * t - 2.0 * t) * p[3];
        (v, d)
    }

    /// One piece of a reference edge, described by its own formula.
    enum RefPiece {
        Line(Point, Point),
        /// Centre, radii, from and to angle (radians, from < to).
        Ellipse(Point, Vec2, f64, f64),
        /// Appendix A's spline (a = 1), control x and control y.
        Cardinal([f64; 4], [f64; 4]),
    }

    impl RefPiece {
        /// Length from the piece's start to the point of it nearest `p`,
        /// and how far `p` is from that point.
        fn length_to(&self, p: Point) -> (f64, f64) {
            match self {
                RefPiece::Line(a, b) => {
                    let ab = *b - *a;
                    let u = ((p - *a).dot(ab) / ab.hypot2()).clamp(0.0, 1.0);
                    (u * ab.hypot(), (*a + ab * u - p).hypot())
                }
                RefPiece::Ellipse(c, r, from, to) => {
                    let phi = ((p.y - c.y) / r.y)
                        .atan2((p.x - c.x) / r.x)
                        .clamp(*from, *to);
                    let speed = |f: f64| (r.x * f.sin()).hypot(r.y * f.cos());
                    let on = Point::new(c.x + r.x * phi.cos(), c.y + r.y * phi.sin());
                    (simpson(speed, *from, phi, 20_000), (on - p).hypot())
                }
                RefPiece::Cardinal(px, py) => {
                    let at = |t: f64| {
                        let (x, dx) = appendix_cardinal(*px, t);
                        let (y, dy) = appendix_cardinal(*py, t);
                        (Point::new(x, y), Vec2::new(dx, dy))
                    };
                    // Nearest parameter: a scan, then Newton on (P − p)·P'.
                    let dist = |t: f64| (at(t).0 - p).hypot();
                    let mut t = (0..=1000)
                        .map(|i| i as f64 / 1000.0)
                        .min_by(|a, b| dist(*a).total_cmp(&dist(*b)))
                        .unwrap_or(0.0);
                    let g = |t: f64| (at(t).0 - p).dot(at(t).1);
                    for _ in 0..50 {
                        let h = 1e-7;
                        let slope = (g(t + h) - g(t - h)) / (2.0 * h);
                        if slope.abs() > 0.0 {
                            t = (t - g(t) / slope).clamp(0.0, 1.0);
                        }
                    }
                    (simpson(|u| at(u).1.hypot(), 0.0, t, 20_000), dist(t))
                }
            }
        }

        fn length(&self) -> f64 {
            match self {
                RefPiece::Line(a, b) => (*b - *a).hypot(),
                RefPiece::Ellipse(c, r, _, to) => {
                    let end = Point::new(c.x + r.x * to.cos(), c.y + r.y * to.sin());
                    self.length_to(end).0
                }
                RefPiece::Cardinal(px, py) => {
                    let end =
                        Point::new(appendix_cardinal(*px, 1.0).0, appendix_cardinal(*py, 1.0).0);
                    self.length_to(end).0
                }
            }
        }
    }

    /// The arc-length coordinate of `p` along the reference pieces (that of
    /// the piece `p` lies on).
    fn reference_coordinate(pieces: &[RefPiece], p: Point) -> f64 {
        let mut before = 0.0;
        let mut best = (f64::INFINITY, 0.0);
        for piece in pieces {
            let (s, off) = piece.length_to(p);
            if off < best.0 - 1e-12 {
                best = (off, before + s);
            }
            before += piece.length();
        }
        assert!(best.0 < 1e-9, "{p:?} is {:e} off the edge", best.0);
        best.1
    }

    /// 001 §2.4: the two opposing edges of a stroke are split into n pieces
    /// of equal arc length, accurate to 1e-6 of the edge length. Both edges
    /// of primitive 2's shape (a straight run and an ellipse against appendix
    /// A's spline and a straight run), measured by a reference that shares
    /// no code with the subdivision: Simpson's rule on each curve's own
    /// formula, and each point's place found by projecting it onto it.
    #[test]
    fn subdivision_is_accurate_to_1e6_of_the_edge_length() {
        use std::f64::consts::FRAC_PI_2;
        let (px, py) = ([0.0, 2.0, 4.0, 2.0], [6.0, -0.2, 6.0, 8.0]);
        let (centre, radii) = (Point::new(2.0, 6.0), Vec2::new(1.0, 2.0));
        let mut segs = vec![Segment::line((3.0, 0.0), (3.0, 6.0))];
        segs.extend(
            Conic::elliptical_arc(centre, radii, 0.0, FRAC_PI_2)
                .into_iter()
                .map(Segment::Conic),
        );
        let inner = Edge::new(segs).unwrap();
        let inner_ref = [
            RefPiece::Line(Point::new(3.0, 0.0), Point::new(3.0, 6.0)),
            RefPiece::Ellipse(centre, radii, 0.0, FRAC_PI_2),
        ];
        let outer = s_outer();
        let outer_ref = [
            RefPiece::Cardinal(px, py),
            RefPiece::Line(Point::new(4.0, 6.0), Point::new(4.0, 9.0)),
        ];
        for (edge, pieces) in [(&inner, &inner_ref[..]), (&outer, &outer_ref[..])] {
            let total: f64 = pieces.iter().map(RefPiece::length).sum();
            assert!(
                (edge.length() - total).abs() <= 1e-9 * total,
                "length {} vs reference {total}",
                edge.length()
            );
            for n in [1, 7, 60, 100, 240] {
                for (k, p) in edge.subdivide(n).into_iter().enumerate() {
                    let s = reference_coordinate(pieces, p);
                    let want = total * k as f64 / n as f64;
                    assert!(
                        (s - want).abs() <= 1e-6 * total,
                        "n = {n}, point {k}: at {s}, want {want} (error {:e} of the length)",
                        (s - want).abs() / total
                    );
                }
            }
        }
    }

    /// A dense polyline by uniform *parameter* steps (independent of the
    /// arc-length code under test), with cumulative chord lengths.
    fn reference_polyline(e: &Edge) -> (Vec<Point>, Vec<f64>) {
        let mut pts = vec![e.start()];
        for seg in e.segments() {
            for i in 1..=4000 {
                pts.push(seg.eval(i as f64 / 4000.0));
            }
        }
        let mut cum = vec![0.0];
        for w in pts.windows(2) {
            let last = cum[cum.len() - 1];
            cum.push(last + (w[1] - w[0]).hypot());
        }
        (pts, cum)
    }

    /// Arc-length coordinate of `p` on the reference polyline, searching only
    /// near `expect` (random splines may loop close to themselves).
    fn coordinate(poly: &(Vec<Point>, Vec<f64>), p: Point, expect: f64, window: f64) -> f64 {
        let (pts, cum) = poly;
        let mut best = (f64::INFINITY, 0.0);
        for i in 0..pts.len() - 1 {
            if (cum[i] - expect).abs() > window {
                continue;
            }
            let (a, b) = (pts[i], pts[i + 1]);
            let ab = b - a;
            let len2 = ab.hypot2();
            let u = if len2 > 0.0 {
                ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let d = (a + ab * u - p).hypot();
            if d < best.0 {
                best = (d, cum[i] + u * len2.sqrt());
            }
        }
        best.1
    }

    fn arb_edge() -> impl Strategy<Value = Edge> {
        let pt = || (-5.0f64..5.0, -5.0f64..5.0);
        (
            prop::array::uniform4(pt()),
            0.3f64..1.5,
            (0.2f64..3.0, 0.2f64..3.0),
            0.2f64..2.8,
            (-3.0f64..3.0, -3.0f64..3.0),
        )
            .prop_filter_map("degenerate", |(cp, a, radii, sweep, tail)| {
                let pts = cp.map(|(x, y)| Point::new(x, y));
                let c = Cardinal::new(pts, a);
                let arc_start = c.end();
                // An elliptical arc starting where the spline ends.
                let centre = arc_start - Vec2::new(radii.0, 0.0);
                let arcs = Conic::elliptical_arc(centre, Vec2::new(radii.0, radii.1), 0.0, sweep);
                let mut segs = vec![Segment::Cardinal(c)];
                segs.extend(arcs.into_iter().map(Segment::Conic));
                let last = segs.last()?.end();
                segs.push(Segment::line(last, last + Vec2::new(tail.0, tail.1)));
                Edge::new(segs).ok()
            })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        #[test]
        fn equal_arc_length_pieces(e in arb_edge()) {
            let n = 60;
            let pts = e.subdivide(n);
            prop_assert_eq!(pts.len(), n + 1);
            let poly = reference_polyline(&e);
            let total = poly.1[poly.1.len() - 1];
            prop_assert!(((total - e.length()) / total).abs() < 1e-5);
            let s: Vec<f64> = pts
                .iter()
                .enumerate()
                .map(|(k, p)| coordinate(&poly, *p, total * k as f64 / n as f64, 0.05 * total))
                .collect();
            let mean = total / n as f64;
            for k in 0..n {
                let piece = s[k + 1] - s[k];
                prop_assert!(((piece - mean) / mean).abs() < 1e-3, "piece {}: {} vs {}", k, piece, mean);
            }
        }
    }
}
