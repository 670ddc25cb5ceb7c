//! S and B of the embedded font coincide with the curves that 001 appendix A's
//! C code defines (control points, arcs and straight runs, placed by the
//! code's flags). The reference curves are rebuilt here from the appendix's
//! formulas, independently of `basr::geom`.

use basr::font::Font;
use basr::geom::Curve;

type P = (f64, f64);

/// Appendix A's cardinal spline polynomial, term by term as in the C code.
fn card(p: [f64; 4], a: f64, t: f64) -> f64 {
    ((-a * t * t * t) + (2.0 * a * t * t) + (-a * t)) * p[0]
        + (((2.0 - a) * t * t * t) + ((a - 3.0) * t * t) + 1.0) * p[1]
        + (((a - 2.0) * t * t * t) + ((3.0 - 2.0 * a) * t * t) + (a * t)) * p[2]
        + ((a * t * t * t) + (-a * t * t)) * p[3]
}

fn spline(px: [f64; 4], py: [f64; 4], t0: f64, t1: f64, map: impl Fn(P) -> P) -> Vec<P> {
    (0..=2000)
        .map(|i| {
            let t = t0 + (t1 - t0) * i as f64 / 2000.0;
            map((card(px, 1.0, t), card(py, 1.0, t)))
        })
        .collect()
}

fn line(a: P, b: P) -> Vec<P> {
    (0..=400)
        .map(|i| {
            let u = i as f64 / 400.0;
            (a.0 + u * (b.0 - a.0), a.1 + u * (b.1 - a.1))
        })
        .collect()
}

fn curve(f: impl Fn(f64) -> P) -> Vec<P> {
    (0..=2000).map(|i| f(i as f64 / 2000.0)).collect()
}

/// Distance from p to a polyline.
fn dist(p: P, poly: &[P]) -> f64 {
    poly.windows(2)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            let (dx, dy) = (b.0 - a.0, b.1 - a.1);
            let len2 = dx * dx + dy * dy;
            let u = if len2 > 0.0 {
                (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            ((a.0 + u * dx - p.0).powi(2) + (a.1 + u * dy - p.1).powi(2)).sqrt()
        })
        .fold(f64::INFINITY, f64::min)
}

/// Both ways: every reference point lies on some font edge, and every font
/// edge point lies on some reference curve.
fn assert_coincide(ch: char, reference: &[Vec<P>]) {
    let font = Font::embedded();
    let glyph = font.glyph(ch).expect("glyph present");
    let edges: Vec<Vec<P>> = glyph
        .strokes
        .iter()
        .flat_map(|s| [&s.left, &s.right])
        .flat_map(|e| e.segments().iter())
        .map(|seg| {
            // Per segment, so the joins between segments are polyline vertices.
            (0..=2000)
                .map(|i| seg.eval(i as f64 / 2000.0))
                .map(|p| (p.x, p.y))
                .collect()
        })
        .collect();
    let tol = 1e-5;
    for (k, r) in reference.iter().enumerate() {
        for &p in r.iter().step_by(37) {
            let d = edges
                .iter()
                .map(|e| dist(p, e))
                .fold(f64::INFINITY, f64::min);
            assert!(
                d < tol,
                "{ch}: reference curve {k} point {p:?} is {d:e} off the font"
            );
        }
    }
    for (k, e) in edges.iter().enumerate() {
        for &p in e.iter().step_by(41) {
            let d = reference
                .iter()
                .map(|r| dist(p, r))
                .fold(f64::INFINITY, f64::min);
            assert!(
                d < tol,
                "{ch}: font edge {k} point {p:?} is {d:e} off appendix A"
            );
        }
    }
}

#[test]
fn s_matches_appendix_a() {
    // primitive3.ff: TSspline px = (0, 2, 4, 2), py = (6, −0.2, 6, 8), a = 1,
    // mirrored y → 25 − y; `arcs`: ellipse rx = 1, ry = 2 moved to (2, 18)
    // above a straight run x = 3 (y 18..19). Flags: 1 as is, 2 x → 4 − x,
    // 3 y → 25 − y, 4 both.
    let flags: [fn(P) -> P; 4] = [
        |p| p,
        |p| (4.0 - p.0, p.1),
        |p| (p.0, 25.0 - p.1),
        |p| (4.0 - p.0, 25.0 - p.1),
    ];
    let mut reference = vec![];
    for flag in flags {
        reference.push(spline(
            [0.0, 2.0, 4.0, 2.0],
            [6.0, -0.2, 6.0, 8.0],
            0.0,
            1.0,
            |(x, y)| flag((x, 25.0 - y)),
        ));
        // x = rx·sqrt(1 − y²/ry²) as in the code, sampled by angle so the
        // steep end near y = ry is resolved: (cos φ, 2 sin φ).
        reference.push(curve(|u| {
            let phi = std::f64::consts::FRAC_PI_2 * u;
            let y = 2.0 * phi.sin();
            flag((2.0 + (1.0 - y * y / 4.0).max(0.0).sqrt(), 19.0 + y))
        }));
        reference.push(line(flag((3.0, 18.0)), flag((3.0, 19.0))));
    }
    // primitiveS.ff: midSspline (2, 4, 1, 3) / (3, 10, 18, 25) with the
    // straight run x = 1, y 18..22, moved by (−1, −3); midSspline2 turns it 180°.
    let spine = |rot: bool| {
        move |(x, y): P| {
            let q = (x - 1.0, y - 3.0);
            if rot {
                (4.0 - q.0, 25.0 - q.1)
            } else {
                q
            }
        }
    };
    for rot in [false, true] {
        reference.push(spline(
            [2.0, 4.0, 1.0, 3.0],
            [3.0, 10.0, 18.0, 25.0],
            0.0,
            1.0,
            spine(rot),
        ));
        reference.push(line(spine(rot)((1.0, 18.0)), spine(rot)((1.0, 22.0))));
    }
    assert_coincide('S', &reference);
}

#[test]
fn b_matches_appendix_a() {
    // interpolate3.c `spline`: px = (3, 1, 4, 2), py = (5, 0, 5, 15.2), a = 1,
    // then x = 4 from y = 5 to 7, all mirrored about y = 12.5; arc.ff: r = 2
    // about (1, 19) from 90° to 0°, then x = 3 from y = 19 to 18.
    // primitive1 flags: 2 mirrors about y = 18, 3 moves down 10, 4 mirrors
    // about 18 and moves down 11.
    let flags: [fn(P) -> P; 4] = [
        |p| p,
        |p| (p.0, 36.0 - p.1),
        |p| (p.0, p.1 - 10.0),
        |p| (p.0, 25.0 - p.1),
    ];
    // Flags 2 and 3 overlap on the middle bar; the font cuts both along
    // y = 13, where the outer spline (unmirrored) reaches y = 2.
    let mut lo: f64 = 0.0;
    let mut hi: f64 = 1.0;
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if card([5.0, 0.0, 5.0, 15.2], 1.0, mid) < 2.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let t_cut = 0.5 * (lo + hi);
    let x_cut = card([3.0, 1.0, 4.0, 2.0], 1.0, t_cut);
    let mut reference = vec![];
    for (k, flag) in flags.into_iter().enumerate() {
        let t0 = if k == 1 || k == 2 { t_cut } else { 0.0 };
        reference.push(spline(
            [3.0, 1.0, 4.0, 2.0],
            [5.0, 0.0, 5.0, 15.2],
            t0,
            1.0,
            |(x, y)| flag((x, 25.0 - y)),
        ));
        reference.push(line(flag((4.0, 20.0)), flag((4.0, 18.0))));
        reference.push(curve(|u| {
            let th = std::f64::consts::FRAC_PI_2 * (1.0 - u);
            flag((1.0 + 2.0 * th.cos(), 19.0 + 2.0 * th.sin()))
        }));
        reference.push(line(flag((3.0, 19.0)), flag((3.0, 18.0))));
    }
    // pathB.c primitive2: the stem, x = 0.5 ± 0.5 from y = 0 to 25. The
    // font paints the bars through it (docs/font.md "B's bars through the
    // stem"), so its sides are edges only between the bars, y = 4..11 and
    // 15..21; beside the bars x = 0 is the bars' caps (rungs, not edges:
    // `font::tests::b_through_its_stem_keeps_the_seed_outline` checks the
    // outline's area) and x = 1 lies inside them.
    for (y0, y1) in [(4.0, 11.0), (15.0, 21.0)] {
        reference.push(line((0.0, y0), (0.0, y1)));
        reference.push(line((1.0, y0), (1.0, y1)));
    }
    // The font's own additions: the cut, the piece joining flags 3 and 4,
    // and the bars' edges carried on over the stem's width.
    reference.push(line((0.0, 13.0), (x_cut, 13.0)));
    reference.push(line((3.0, 7.0), (3.0, 8.0)));
    reference.push(line((4.0, 7.0), (4.0, 8.0)));
    for y in [0.0, 4.0, 11.0, 15.0, 21.0, 25.0] {
        reference.push(line((0.0, y), (1.0, y)));
    }
    assert_coincide('B', &reference);
}
