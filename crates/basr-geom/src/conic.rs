//! Conic arc: a rational quadratic Bézier (Farin), exact for elliptical arcs.

use kurbo::{Affine, Point, Vec2};

use super::{integrate, solve_inv_arclen, Curve};

/// A rational quadratic Bézier with end weights 1 and middle weight `w`:
/// P(t) = (B0·P0 + w·B1·P1 + B2·P2) / (B0 + w·B1 + B2) with the Bernstein
/// polynomials B0 = (1−t)², B1 = 2t(1−t), B2 = t². w < 1 gives an elliptical
/// arc, w = 1 a parabola, w > 1 a hyperbola (Farin, *Curves and Surfaces for
/// CAGD*, ch. on conics). Affine maps keep the weight, so an ellipse is an
/// affine image of a circular arc with the same w.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Conic {
    pub p0: Point,
    pub p1: Point,
    pub p2: Point,
    pub weight: f64,
}

impl Conic {
    pub fn new(p0: Point, p1: Point, p2: Point, weight: f64) -> Conic {
        Conic { p0, p1, p2, weight }
    }

    /// Arcs of the ellipse centre + (rx·cos φ, ry·sin φ) from `from` to `to`
    /// (radians, either direction), split into pieces of at most 90° so each
    /// piece's weight cos(Δ/2) stays well away from zero.
    pub fn elliptical_arc(center: Point, radii: Vec2, from: f64, to: f64) -> Vec<Conic> {
        let sweep = to - from;
        let pieces = ((sweep.abs() / std::f64::consts::FRAC_PI_2).ceil() as usize).max(1);
        let step = sweep / pieces as f64;
        let map = Affine::translate(center.to_vec2()) * Affine::scale_non_uniform(radii.x, radii.y);
        (0..pieces)
            .map(|i| {
                let a0 = from + step * i as f64;
                let a1 = a0 + step;
                let half = 0.5 * step;
                let mid = a0 + half;
                // Unit circle: tangents at the ends meet at distance 1/cos(Δ/2)
                // along the bisector; the weight is cos(Δ/2).
                let w = half.cos();
                let p0 = Point::new(a0.cos(), a0.sin());
                let p1 = Point::new(mid.cos() / w, mid.sin() / w);
                let p2 = Point::new(a1.cos(), a1.sin());
                Conic::new(map * p0, map * p1, map * p2, w)
            })
            .collect()
    }

    fn numer_denom(&self, t: f64) -> (Vec2, f64, Vec2, f64) {
        let mt = 1.0 - t;
        let (b0, b1, b2) = (mt * mt, 2.0 * t * mt, t * t);
        let (d0, d1, d2) = (-2.0 * mt, 2.0 - 4.0 * t, 2.0 * t);
        let w = self.weight;
        let (p0, p1, p2) = (self.p0.to_vec2(), self.p1.to_vec2(), self.p2.to_vec2());
        let n = p0 * b0 + p1 * (w * b1) + p2 * b2;
        let d = b0 + w * b1 + b2;
        let dn = p0 * d0 + p1 * (w * d1) + p2 * d2;
        let dd = d0 + w * d1 + d2;
        (n, d, dn, dd)
    }

    fn speed(&self, t: f64) -> f64 {
        self.deriv(t).hypot()
    }

    fn partial_arclen(&self, t: f64, accuracy: f64) -> f64 {
        integrate(|u| self.speed(u), 0.0, t, accuracy)
    }

    pub fn reversed(&self) -> Conic {
        Conic::new(self.p2, self.p1, self.p0, self.weight)
    }

    pub fn transformed(&self, m: &Affine) -> Conic {
        Conic::new(*m * self.p0, *m * self.p1, *m * self.p2, self.weight)
    }
}

impl Curve for Conic {
    fn eval(&self, t: f64) -> Point {
        let (n, d, _, _) = self.numer_denom(t);
        (n / d).to_point()
    }
    fn deriv(&self, t: f64) -> Vec2 {
        let (n, d, dn, dd) = self.numer_denom(t);
        (dn * d - n * dd) / (d * d)
    }
    fn arclen(&self, accuracy: f64) -> f64 {
        self.partial_arclen(1.0, accuracy)
    }
    fn inv_arclen(&self, s: f64, accuracy: f64) -> f64 {
        let total = self.arclen(accuracy * 0.1);
        solve_inv_arclen(
            |t| self.partial_arclen(t, accuracy * 0.1),
            total,
            s,
            accuracy,
        )
    }
    fn start(&self) -> Point {
        self.p0
    }
    fn end(&self) -> Point {
        self.p2
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    /// Complete elliptic integral of the second kind times a, i.e. a quarter
    /// of the perimeter of an ellipse with semi-axes a ≥ b, by the
    /// arithmetic–geometric mean (Abramowitz & Stegun 17.6):
    /// E = K·(1 − Σ 2^(n−1) c_n²) with c_0² = 1 − b²/a², K = π/(2·AGM).
    fn quarter_perimeter(a: f64, b: f64) -> f64 {
        let (mut an, mut bn) = (a, b);
        let mut sum = 0.5 * (a * a - b * b); // 2^(−1)·c_0²
        let mut pow = 0.5;
        for _ in 0..30 {
            let cn = 0.5 * (an - bn);
            let (a1, b1) = (0.5 * (an + bn), (an * bn).sqrt());
            an = a1;
            bn = b1;
            pow *= 2.0;
            sum += pow * cn * cn;
            if cn.abs() < 1e-300 {
                break;
            }
        }
        PI / (2.0 * an) * (a * a - sum)
    }

    #[test]
    fn agm_reference_is_right() {
        // Circle, and the degenerate ellipse (a flat segment of length 4a).
        assert!((quarter_perimeter(2.0, 2.0) - PI).abs() < 1e-14);
        assert!((quarter_perimeter(1.0, 1e-12) - 1.0).abs() < 1e-9);
        // A known value: perimeter of the 2:1 ellipse ≈ 9.688448220547675.
        assert!((4.0 * quarter_perimeter(2.0, 1.0) - 9.688448220547675).abs() < 1e-12);
    }

    #[test]
    fn circular_arc_length_is_r_theta() {
        for &(r, from, to) in &[(2.0, FRAC_PI_2, 0.0), (1.0, 0.0, 3.0), (0.7, -1.0, 0.2)] {
            let arcs = Conic::elliptical_arc(Point::new(1.0, 19.0), Vec2::new(r, r), from, to);
            let len: f64 = arcs.iter().map(|c| c.arclen(1e-13)).sum();
            let want = r * (to - from).abs();
            assert!(((len - want) / want).abs() < 1e-9, "{len} vs {want}");
            for c in &arcs {
                for i in 0..=10 {
                    let p = c.eval(i as f64 / 10.0);
                    assert!(((p - Point::new(1.0, 19.0)).hypot() - r).abs() < 1e-12);
                }
            }
        }
    }

    #[test]
    fn elliptical_arc_length_matches_agm() {
        // 001 app. A `arcs`: the quarter ellipse rx = 1, ry = 2.
        for &(rx, ry) in &[(1.0, 2.0), (2.0, 1.0), (1.0, 7.0), (3.0, 2.5)] {
            let arcs = Conic::elliptical_arc(Point::ORIGIN, Vec2::new(rx, ry), 0.0, FRAC_PI_2);
            let len: f64 = arcs.iter().map(|c| c.arclen(1e-13)).sum();
            let want = quarter_perimeter(f64::max(rx, ry), f64::min(rx, ry));
            assert!(
                ((len - want) / want).abs() < 1e-9,
                "{rx}x{ry}: {len} vs {want}"
            );
            // Full ellipse in four pieces.
            let arcs = Conic::elliptical_arc(Point::ORIGIN, Vec2::new(rx, ry), 0.0, 2.0 * PI);
            assert_eq!(arcs.len(), 4);
            let len: f64 = arcs.iter().map(|c| c.arclen(1e-13)).sum();
            assert!(((len - 4.0 * want) / want).abs() < 4e-9);
            for c in &arcs {
                for i in 0..=10 {
                    let p = c.eval(i as f64 / 10.0);
                    let e = (p.x / rx).powi(2) + (p.y / ry).powi(2);
                    assert!((e - 1.0).abs() < 1e-12);
                }
            }
        }
    }

    #[test]
    fn derivative_matches_finite_difference() {
        let c = Conic::elliptical_arc(Point::new(2.0, 19.0), Vec2::new(1.0, 2.0), 0.0, 1.4)[0];
        for i in 1..10 {
            let t = i as f64 / 10.0;
            let h = 1e-6;
            let fd = (c.eval(t + h) - c.eval(t - h)) / (2.0 * h);
            assert!((fd - c.deriv(t)).hypot() < 1e-7);
        }
    }

    #[test]
    fn inverse_arc_length_round_trips() {
        let c = Conic::elliptical_arc(Point::ORIGIN, Vec2::new(1.0, 2.0), 0.0, FRAC_PI_2)[0];
        let total = c.arclen(1e-12);
        for i in 0..=8 {
            let s = total * i as f64 / 8.0;
            let t = c.inv_arclen(s, 1e-11);
            let back = integrate(|u| c.deriv(u).hypot(), 0.0, t, 1e-13);
            assert!((back - s).abs() < 1e-9, "{back} vs {s}");
        }
    }
}
