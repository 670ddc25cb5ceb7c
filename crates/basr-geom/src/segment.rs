//! One piece of an edge: a line, a cardinal spline or a conic arc.

use kurbo::{Affine, Line, ParamCurve, ParamCurveArclen, Point, Vec2};

use super::{Cardinal, Conic, Curve};

/// The three curve kinds of 001 §2.4.
#[derive(Debug, Clone, PartialEq)]
pub enum Segment {
    Line(Line),
    Cardinal(Cardinal),
    Conic(Conic),
}

impl Segment {
    /// A straight segment from `a` to `b`.
    pub fn line(a: impl Into<Point>, b: impl Into<Point>) -> Segment {
        Segment::Line(Line::new(a, b))
    }

    /// The same segment run the other way.
    pub fn reversed(&self) -> Segment {
        match self {
            Segment::Line(l) => Segment::Line(Line::new(l.p1, l.p0)),
            Segment::Cardinal(c) => Segment::Cardinal(c.reversed()),
            Segment::Conic(c) => Segment::Conic(c.reversed()),
        }
    }

    /// The segment mapped by an affine transform (all three kinds are affine
    /// invariant: their control points map and the curve follows exactly).
    pub fn transformed(&self, m: &Affine) -> Segment {
        match self {
            Segment::Line(l) => Segment::Line(*m * *l),
            Segment::Cardinal(c) => Segment::Cardinal(c.transformed(m)),
            Segment::Conic(c) => Segment::Conic(c.transformed(m)),
        }
    }

    /// Whether every defining number is finite.
    pub fn is_finite(&self) -> bool {
        let pts: Vec<Point> = match self {
            Segment::Line(l) => vec![l.p0, l.p1],
            Segment::Cardinal(c) => c.points().to_vec(),
            Segment::Conic(c) => vec![c.p0, c.p1, c.p2],
        };
        let extra = match self {
            Segment::Line(_) => 0.0,
            Segment::Cardinal(c) => c.tension() + c.range().0 + c.range().1,
            Segment::Conic(c) => c.weight,
        };
        pts.iter().all(|p| p.is_finite()) && extra.is_finite()
    }
}

impl Curve for Segment {
    fn eval(&self, t: f64) -> Point {
        match self {
            Segment::Line(l) => l.eval(t),
            Segment::Cardinal(c) => c.eval(t),
            Segment::Conic(c) => c.eval(t),
        }
    }
    fn deriv(&self, t: f64) -> Vec2 {
        match self {
            Segment::Line(l) => l.p1 - l.p0,
            Segment::Cardinal(c) => c.deriv(t),
            Segment::Conic(c) => c.deriv(t),
        }
    }
    fn arclen(&self, accuracy: f64) -> f64 {
        match self {
            Segment::Line(l) => l.arclen(accuracy),
            Segment::Cardinal(c) => c.arclen(accuracy),
            Segment::Conic(c) => c.arclen(accuracy),
        }
    }
    fn inv_arclen(&self, s: f64, accuracy: f64) -> f64 {
        match self {
            Segment::Line(l) => {
                let len = l.arclen(accuracy);
                if len > 0.0 {
                    (s / len).clamp(0.0, 1.0)
                } else {
                    0.0
                }
            }
            Segment::Cardinal(c) => c.inv_arclen(s, accuracy),
            Segment::Conic(c) => c.inv_arclen(s, accuracy),
        }
    }
    fn start(&self) -> Point {
        match self {
            Segment::Line(l) => l.p0,
            Segment::Cardinal(c) => c.start(),
            Segment::Conic(c) => c.p0,
        }
    }
    fn end(&self) -> Point {
        match self {
            Segment::Line(l) => l.p1,
            Segment::Cardinal(c) => c.end(),
            Segment::Conic(c) => c.p2,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_length_is_exact() {
        let s = Segment::line((1.0, 2.0), (4.0, 6.0));
        assert!((s.arclen(1e-12) - 5.0).abs() < 5.0 * 1e-12);
        let s = Segment::line((0.0, 0.0), (1e-3, 3e7));
        let want = (1e-6f64 + 9e14).sqrt();
        assert!(((s.arclen(1e-12) - want) / want).abs() < 1e-12);
        assert!((s.inv_arclen(want / 4.0, 1e-9) - 0.25).abs() < 1e-12);
    }
}
