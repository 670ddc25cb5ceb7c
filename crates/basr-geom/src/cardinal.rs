//! Cardinal spline segment of 001 eq. 2.1–2.3 (tension `a`, four control points).

use kurbo::{Affine, CubicBez, ParamCurve, ParamCurveArclen, ParamCurveDeriv, Point, Vec2};

use super::Curve;

/// A cardinal spline through four control points q = (P1, P2, P3, P4) with
/// tension `a`: V(t) = [t³ t² t 1] · M_cs · q (001 eq. 2.1–2.3), which runs
/// from P2 (t = 0) to P3 (t = 1) with end tangents a(P3 − P1) and a(P4 − P2).
///
/// The third row of M_cs is (−a, 0, a, 0) as in appendix A's code; the
/// printed eq. 2.3 drops the `a` (a transcription slip: without it the rows
/// would not sum to zero and the curve would move when its points move
/// together).
///
/// `range` keeps only the part t ∈ [t0, t1] of the spline, reparametrised to
/// [0, 1]; the curve is the same cubic either way. Evaluation goes through the
/// equivalent cubic Bézier (a cubic Hermite segment), so kurbo does the
/// numerics.
#[derive(Debug, Clone, PartialEq)]
pub struct Cardinal {
    points: [Point; 4],
    tension: f64,
    range: (f64, f64),
    bez: CubicBez,
}

impl Cardinal {
    /// The whole spline between P2 and P3.
    pub fn new(points: [Point; 4], tension: f64) -> Cardinal {
        Cardinal::with_range(points, tension, (0.0, 1.0))
    }

    /// The part t ∈ [range.0, range.1] of the spline.
    pub fn with_range(points: [Point; 4], tension: f64, range: (f64, f64)) -> Cardinal {
        let [p1, p2, p3, p4] = points;
        let a = tension;
        // Hermite → Bézier: inner control points one third along the tangents.
        let full = CubicBez::new(
            p2,
            p2 + (p3 - p1) * (a / 3.0),
            p3 - (p4 - p2) * (a / 3.0),
            p3,
        );
        let bez = if range == (0.0, 1.0) {
            full
        } else {
            full.subsegment(range.0..range.1)
        };
        Cardinal {
            points,
            tension,
            range,
            bez,
        }
    }

    /// The four control points P1..P4.
    pub fn points(&self) -> [Point; 4] {
        self.points
    }

    /// The tension `a` (0.5 is Catmull–Rom; appendix A uses 1).
    pub fn tension(&self) -> f64 {
        self.tension
    }

    /// The kept parameter range of the full spline.
    pub fn range(&self) -> (f64, f64) {
        self.range
    }

    /// The equivalent cubic Bézier.
    pub fn to_cubic(&self) -> CubicBez {
        self.bez
    }

    /// Eq. 2.1 evaluated literally on the full spline's parameter t ∈ [0, 1]
    /// (reference form; [`Curve::eval`] uses the Bézier form).
    pub fn eval_matrix(&self, t: f64) -> Point {
        let a = self.tension;
        // Rows of M_cs (001 eq. 2.3, third row as in appendix A).
        let m = [
            [-a, 2.0 - a, -2.0 + a, a],
            [2.0 * a, -3.0 + a, 3.0 - 2.0 * a, -a],
            [-a, 0.0, a, 0.0],
            [0.0, 1.0, 0.0, 0.0],
        ];
        let f = [t * t * t, t * t, t, 1.0]; // eq. 2.2
        let mut out = Vec2::ZERO;
        for (fi, row) in f.iter().zip(m.iter()) {
            for (mij, p) in row.iter().zip(self.points.iter()) {
                out += p.to_vec2() * (fi * mij);
            }
        }
        out.to_point()
    }

    /// The same curve with its direction reversed.
    pub fn reversed(&self) -> Cardinal {
        let [p1, p2, p3, p4] = self.points;
        Cardinal::with_range(
            [p4, p3, p2, p1],
            self.tension,
            (1.0 - self.range.1, 1.0 - self.range.0),
        )
    }

    /// The curve mapped by an affine transform (cardinal splines are affine
    /// invariant: map the control points).
    pub fn transformed(&self, m: &Affine) -> Cardinal {
        Cardinal::with_range(self.points.map(|p| *m * p), self.tension, self.range)
    }
}

impl Curve for Cardinal {
    fn eval(&self, t: f64) -> Point {
        self.bez.eval(t)
    }
    fn deriv(&self, t: f64) -> Vec2 {
        self.bez.deriv().eval(t).to_vec2()
    }
    fn arclen(&self, accuracy: f64) -> f64 {
        self.bez.arclen(accuracy)
    }
    fn inv_arclen(&self, s: f64, accuracy: f64) -> f64 {
        self.bez.inv_arclen(s, accuracy)
    }
    fn start(&self) -> Point {
        self.bez.p0
    }
    fn end(&self) -> Point {
        self.bez.p3
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn s_top() -> Cardinal {
        // 001 app. A, TSspline: px = (0, 2, 4, 2), py = (6, −0.2, 6, 8), a = 1.
        Cardinal::new(
            [
                (0.0, 6.0).into(),
                (2.0, -0.2).into(),
                (4.0, 6.0).into(),
                (2.0, 8.0).into(),
            ],
            1.0,
        )
    }

    #[test]
    fn interpolates_second_and_third_points() {
        let c = s_top();
        assert!((c.eval(0.0) - Point::new(2.0, -0.2)).hypot() < 1e-12);
        assert!((c.eval(1.0) - Point::new(4.0, 6.0)).hypot() < 1e-12);
        assert!((c.eval_matrix(0.0) - Point::new(2.0, -0.2)).hypot() < 1e-12);
        assert!((c.eval_matrix(1.0) - Point::new(4.0, 6.0)).hypot() < 1e-12);
        // End tangents a(P3 − P1) and a(P4 − P2).
        assert!((c.deriv(0.0) - Vec2::new(4.0, 0.0)).hypot() < 1e-12);
        assert!((c.deriv(1.0) - Vec2::new(0.0, 8.2)).hypot() < 1e-12);
    }

    /// Appendix A's polynomial, written out term by term as in the C code.
    fn appendix_a(p: [f64; 4], a: f64, t: f64) -> f64 {
        ((-a * t * t * t) + (2.0 * a * t * t) + (-a * t)) * p[0]
            + (((2.0 - a) * t * t * t) + ((a - 3.0) * t * t) + 1.0) * p[1]
            + (((a - 2.0) * t * t * t) + ((3.0 - 2.0 * a) * t * t) + (a * t)) * p[2]
            + ((a * t * t * t) + (-a * t * t)) * p[3]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(128))]
        #[test]
        fn matches_eq_2_1(
            xs in prop::array::uniform4(-10.0f64..10.0),
            ys in prop::array::uniform4(-10.0f64..10.0),
            a in 0.1f64..2.0,
            t in 0.0f64..1.0,
        ) {
            let pts = [0, 1, 2, 3].map(|i| Point::new(xs[i], ys[i]));
            let c = Cardinal::new(pts, a);
            let want = Point::new(appendix_a(xs, a, t), appendix_a(ys, a, t));
            prop_assert!((c.eval(t) - want).hypot() < 1e-9);
            prop_assert!((c.eval_matrix(t) - want).hypot() < 1e-9);
        }

        /// `deriv` is the derivative of `eval`: a central difference at a
        /// random t agrees, whole spline or a kept range of it.
        #[test]
        fn derivative_matches_a_finite_difference(
            xs in prop::array::uniform4(-10.0f64..10.0),
            ys in prop::array::uniform4(-10.0f64..10.0),
            a in 0.1f64..2.0,
            t in 0.001f64..0.999,
            range in (0.0f64..0.4, 0.6f64..1.0),
        ) {
            let pts = [0, 1, 2, 3].map(|i| Point::new(xs[i], ys[i]));
            for c in [Cardinal::new(pts, a), Cardinal::with_range(pts, a, range)] {
                let h = 1e-6;
                let fd = (c.eval(t + h) - c.eval(t - h)) / (2.0 * h);
                let d = c.deriv(t);
                // Truncation h²/6 · |P‴| ~ 1e-10, rounding ~ 1e-16 · |P| / h ~ 1e-9.
                prop_assert!(
                    (fd - d).hypot() <= 1e-6 * (1.0 + d.hypot()),
                    "t = {}: deriv {:?}, finite difference {:?}", t, d, fd
                );
            }
        }

        #[test]
        fn range_and_reverse_keep_the_curve(
            xs in prop::array::uniform4(-10.0f64..10.0),
            ys in prop::array::uniform4(-10.0f64..10.0),
            t0 in 0.0f64..0.5, t1 in 0.5f64..1.0, u in 0.0f64..1.0,
        ) {
            let pts = [0, 1, 2, 3].map(|i| Point::new(xs[i], ys[i]));
            let c = Cardinal::with_range(pts, 1.0, (t0, t1));
            let full = Cardinal::new(pts, 1.0);
            prop_assert!((c.eval(u) - full.eval(t0 + u * (t1 - t0))).hypot() < 1e-9);
            prop_assert!((c.reversed().eval(1.0 - u) - c.eval(u)).hypot() < 1e-9);
        }
    }
}
