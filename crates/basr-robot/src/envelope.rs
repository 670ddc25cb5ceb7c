//! Seed 002's algebraic workspace of a 2R+P (telescopic) arm: the torus
//! each stroke value traces (eq. 1–3), the height of the reference point
//! (eq. 4), the envelope of the tori over the stroke (eq. 5–6), and the
//! quartic in the stroke that inverse kinematics solves.
//!
//! Frames as 002 §2 and standard Denavit–Hartenberg: the point H is
//! `Rz(θ1)·Tz(h1)·Tx(a1)·Rx(α1)·Rz(θ2)·Tz(h2)·Tx(a2)·Rx(α2)·Tz(d)` applied
//! to the origin. Eq. 1–6 take h1 = 0 (002: it only shifts the workspace);
//! heights here are measured from the first frame's origin.

/// The workspace-shaping DH parameters of seed 002 §2 (h1 left out).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dh {
    pub a1: f64,
    pub alpha1: f64,
    pub h2: f64,
    pub a2: f64,
    pub alpha2: f64,
}

/// The structural coefficients of eq. 2 at one stroke.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coefficients {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub d: f64,
}

impl Dh {
    /// Radial and axial reach of H about the second axis (002 eq. 3).
    pub fn r2_z2(&self, d: f64) -> (f64, f64) {
        let (s2, c2) = self.alpha2.sin_cos();
        (self.a2.hypot(d * s2), d * c2)
    }

    /// Structural coefficients A, B, C, D (002 eq. 2).
    pub fn coefficients(&self, d: f64) -> Coefficients {
        let (s1, c1) = self.alpha1.sin_cos();
        let (r2, z2) = self.r2_z2(d);
        let a1 = self.a1;
        Coefficients {
            a: a1 * a1 + r2 * r2 + (z2 + self.h2).powi(2),
            b: -4.0 * a1 * a1 * r2 * r2,
            c: 2.0 * a1 / s1,
            d: -2.0 * a1 * (z2 + self.h2) * c1 / s1,
        }
    }

    /// Eq. 1's left side at (r, z) for stroke d: zero on the torus.
    pub fn torus(&self, r: f64, z: f64, d: f64) -> f64 {
        let k = self.coefficients(d);
        (r * r + z * z - k.a).powi(2) + (k.c * z + k.d).powi(2) + k.b
    }

    /// d-derivatives A′, B′, D′ as 002 eq. 6 prints them. A′ and D′ are the
    /// true derivatives of eq. 2; the printed B′ = −4a1²·d·sin²α2 is HALF
    /// the true dB/dd = −8a1²·d·sin²α2 (B = −4a1²r2², r2² = a2² + d²sin²α2).
    /// Eq. 5 holds as printed only with this halved B′: it is the true
    /// derivative of eq. 1 divided by 2, whose B-term is (dB/dd)/2.
    pub fn derivatives_as_printed(&self, d: f64) -> (f64, f64, f64) {
        let (s1, c1) = self.alpha1.sin_cos();
        let (s2, c2) = self.alpha2.sin_cos();
        let a1 = self.a1;
        (
            2.0 * (d + self.h2 * c2),
            -4.0 * a1 * a1 * d * s2 * s2,
            -2.0 * a1 * c2 * c1 / s1,
        )
    }

    /// Eq. 5's left side with eq. 6's printed derivatives: zero where the
    /// torus of stroke d touches the envelope. Equals half of
    /// [`Dh::torus_dd`].
    pub fn eq5(&self, r: f64, z: f64, d: f64) -> f64 {
        let k = self.coefficients(d);
        let (ap, bp, dp) = self.derivatives_as_printed(d);
        -(r * r + z * z - k.a) * ap + (k.c * z + k.d) * dp + bp
    }

    /// The true d-derivative of eq. 1's left side (central difference free:
    /// chain rule on eq. 2–3).
    pub fn torus_dd(&self, r: f64, z: f64, d: f64) -> f64 {
        let k = self.coefficients(d);
        let (ap, bp_half, dp) = self.derivatives_as_printed(d);
        -2.0 * (r * r + z * z - k.a) * ap + 2.0 * (k.c * z + k.d) * dp + 2.0 * bp_half
    }

    /// Height of H from its angle φ about the second axis (002 eq. 4 with
    /// h1 = 0). Eq. 4 prints θ2 where φ belongs: H sits at angle
    /// φ = θ2 + atan2(y, a2) about that axis, (a2, y) being H's coordinates
    /// across the axis at θ2 = 0. With the DH twist Rx(α2) used here
    /// y = −d·sin α2, so φ = θ2 − atan2(d·sin α2, a2); the issue's
    /// `+ atan2(d sin α2, a2)` is the same slip read with the opposite twist
    /// sense.
    pub fn eq4_z(&self, phi: f64, d: f64) -> f64 {
        let (s1, c1) = self.alpha1.sin_cos();
        let (r2, z2) = self.r2_z2(d);
        r2 * phi.sin() * s1 + (self.h2 + z2) * c1
    }

    /// φ of eq. 4 for joint angle θ2 at stroke d.
    pub fn phi(&self, theta2: f64, d: f64) -> f64 {
        theta2 - (d * self.alpha2.sin()).atan2(self.a2)
    }

    /// DH forward kinematics of H (h1 = 0).
    pub fn point(&self, theta1: f64, theta2: f64, d: f64) -> [f64; 3] {
        let (s1, c1) = self.alpha1.sin_cos();
        let (s2, c2) = self.alpha2.sin_cos();
        let (st, ct) = theta2.sin_cos();
        // In frame 2: Rz(θ2)·(a2, −d·sin α2, h2 + d·cos α2).
        let (px, py, pz) = (self.a2, -d * s2, self.h2 + d * c2);
        let x2 = ct * px - st * py;
        let y2 = st * px + ct * py;
        // Frame 2 in frame 1: Tx(a1)·Rx(α1).
        let u = [self.a1 + x2, c1 * y2 - s1 * pz, s1 * y2 + c1 * pz];
        let (sa, ca) = theta1.sin_cos();
        [ca * u[0] - sa * u[1], sa * u[0] + ca * u[1], u[2]]
    }

    /// Envelope points (r, z ≥ any) of the tori at stroke d: eq. 1 and 5
    /// together. With u = r² + z² − A and w = Cz + D, eq. 1 is the circle
    /// u² + w² = −B and eq. 5 the line −A′u + D′w + B′ = 0: up to two points.
    pub fn envelope_points(&self, d: f64) -> Vec<[f64; 2]> {
        let k = self.coefficients(d);
        let (ap, bp, dp) = self.derivatives_as_printed(d);
        let (nx, ny) = (-ap, dp);
        let n2 = nx * nx + ny * ny;
        let rho2 = -k.b;
        if n2 <= 1e-300 || k.c == 0.0 {
            return vec![];
        }
        // Line n·(u, w) = −B′; its foot from the origin and the chord.
        let c = -bp;
        let (fu, fw) = (c * nx / n2, c * ny / n2);
        let h2 = rho2 - c * c / n2;
        if h2 < 0.0 {
            return vec![];
        }
        let h = (h2 / n2).sqrt();
        let mut out = Vec::new();
        for s in [-1.0, 1.0] {
            let u = fu + s * h * ny;
            let w = fw - s * h * nx;
            let z = (w - k.d) / k.c;
            let r2 = u + k.a - z * z;
            if r2 >= 0.0 {
                out.push([r2.sqrt(), z]);
            }
        }
        out
    }

    /// Coefficients (of d⁰ … d⁴) of eq. 1 at (r, z) as a polynomial in d:
    /// the strokes whose torus passes through the point.
    pub fn quartic(&self, r: f64, z: f64) -> [f64; 5] {
        let (s1, c1) = self.alpha1.sin_cos();
        let (s2, c2) = self.alpha2.sin_cos();
        let (a1, a2, h2) = (self.a1, self.a2, self.h2);
        // r² + z² − A = −d² + p1·d + p0; Cz + D = q1·d + q0; B = b0 + b2·d².
        let p1 = -2.0 * h2 * c2;
        let p0 = r * r + z * z - a1 * a1 - a2 * a2 - h2 * h2;
        let q1 = -2.0 * a1 * c1 * c2 / s1;
        let q0 = 2.0 * a1 * (z - c1 * h2) / s1;
        let b0 = -4.0 * a1 * a1 * a2 * a2;
        let b2 = -4.0 * a1 * a1 * s2 * s2;
        [
            p0 * p0 + q0 * q0 + b0,
            2.0 * p0 * p1 + 2.0 * q0 * q1,
            p1 * p1 - 2.0 * p0 + q1 * q1 + b2,
            -2.0 * p1,
            1.0,
        ]
    }
}

/// Value of the polynomial Σ c[i]·xⁱ.
pub fn poly_eval(c: &[f64], x: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &k| acc * x + k)
}

/// Coefficients of the derivative of Σ c[i]·xⁱ.
pub fn poly_derivative(c: &[f64]) -> Vec<f64> {
    (1..c.len()).map(|i| c[i] * i as f64).collect()
}

/// Σ |c[i]|·|x|ⁱ: the size of the terms Horner's rule adds at `x`, which
/// its rounding is relative to.
fn term_scale(c: &[f64], x: f64) -> f64 {
    c.iter()
        .enumerate()
        .map(|(i, k)| k.abs() * x.abs().powi(i as i32))
        .sum()
}

/// Every real root of Σ c[i]·xⁱ in [lo, hi], increasing. Written here: the
/// roots between a derivative's roots are bracketed exactly (the
/// polynomial is monotone there), so no root pair closer than a sampling
/// step is lost, as it would be by scanning; double roots are found at the
/// derivative's roots.
pub fn real_roots(c: &[f64], lo: f64, hi: f64) -> Vec<f64> {
    let n = c.iter().rposition(|&k| k != 0.0).unwrap_or(0);
    if n == 0 || lo > hi {
        return vec![];
    }
    let c = &c[..=n];
    if n == 1 {
        let x = -c[0] / c[1];
        return if x >= lo && x <= hi { vec![x] } else { vec![] };
    }
    let deriv = poly_derivative(c);
    let mut knots = vec![lo];
    knots.extend(real_roots(&deriv, lo, hi));
    knots.push(hi);
    let scale = |x: f64| term_scale(c, x);
    let mut out: Vec<f64> = Vec::new();
    let push = |x: f64, out: &mut Vec<f64>| {
        if out.last().is_none_or(|&l| x - l > 1e-12 * (1.0 + x.abs())) {
            out.push(x);
        }
    };
    for w in knots.windows(2) {
        let (a, b) = (w[0], w[1]);
        let (fa, fb) = (poly_eval(c, a), poly_eval(c, b));
        // A value within Horner's rounding (≈ n·ε·Σ|cᵢxⁱ|) is a root.
        if fa.abs() <= 4e-15 * scale(a) {
            push(a, &mut out);
        }
        if fa.signum() == fb.signum() || fa == 0.0 || fb == 0.0 {
            continue;
        }
        push(monotone_root(c, &deriv, (a, b), fa), &mut out);
    }
    if let Some(&last) = knots.last() {
        if poly_eval(c, last).abs() <= 4e-15 * scale(last) {
            push(last, &mut out);
        }
    }
    out
}

/// The root of Σ c[i]·xⁱ in `(a, b)`, where it is monotone and changes
/// sign (`fa` its value at `a`); `dc` its derivative's coefficients.
/// Newton's steps kept inside a bracket that every evaluation narrows,
/// halving the bracket where a step would leave it or gain too little
/// (the safeguarded Newton of Press et al., Numerical Recipes §9.4,
/// `rtsafe`): about 6 evaluations where plain halving took about 55
/// (a telescopic arm's inverse kinematics solves a quartic per setpoint;
/// halving was 64 % of compiling STOP for that kind). It ends at a zero,
/// at a bracket of adjacent floats, or at a step within an ulp or two.
fn monotone_root(c: &[f64], dc: &[f64], (mut a, mut b): (f64, f64), fa: f64) -> f64 {
    let mut x = 0.5 * (a + b);
    let mut last_step = b - a;
    for _ in 0..200 {
        let fx = poly_eval(c, x);
        if fx == 0.0 {
            return x;
        }
        if fx.signum() == fa.signum() {
            a = x;
        } else {
            b = x;
        }
        let mid = 0.5 * (a + b);
        if mid <= a || mid >= b {
            return mid;
        }
        let newton = x - fx / poly_eval(dc, x);
        let step = if newton > a && newton < b && (newton - x).abs() <= 0.5 * last_step {
            newton
        } else {
            mid
        };
        last_step = (step - x).abs();
        if last_step <= 2.0 * f64::EPSILON * x.abs().max(f64::MIN_POSITIVE) {
            return step;
        }
        x = step;
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn dh() -> impl Strategy<Value = Dh> {
        (
            0.1f64..2.0,
            0.3f64..2.8,
            -1.0f64..1.0,
            0.0f64..1.0,
            0.2f64..2.9,
        )
            .prop_map(|(a1, alpha1, h2, a2, alpha2)| Dh {
                a1,
                alpha1,
                h2,
                a2,
                alpha2,
            })
    }

    proptest! {
        /// Eq. 1–3 hold on the DH forward kinematics, and eq. 4 with φ.
        #[test]
        fn torus_holds_on_dh_points(k in dh(), t1 in -3.0f64..3.0, t2 in -3.0f64..3.0, d in 0.1f64..5.0) {
            let p = k.point(t1, t2, d);
            let r = p[0].hypot(p[1]);
            let scale = (k.coefficients(d).a).powi(2);
            prop_assert!(k.torus(r, p[2], d).abs() <= 1e-12 * scale);
            prop_assert!((k.eq4_z(k.phi(t2, d), d) - p[2]).abs() < 1e-12);
        }

        /// Envelope points satisfy eq. 1 and its true d-derivative (= 2·eq. 5),
        /// and are extremes of the reach: FK at the point's stroke and angle
        /// puts H there.
        #[test]
        fn envelope_points_satisfy_eq1_and_its_derivative(k in dh(), d in 0.1f64..5.0) {
            let scale = (k.coefficients(d).a).powi(2);
            for [r, z] in k.envelope_points(d) {
                prop_assert!(k.torus(r, z, d).abs() <= 1e-9 * scale, "eq1 {}", k.torus(r, z, d));
                prop_assert!(k.torus_dd(r, z, d).abs() <= 1e-9 * scale, "d/dd {}", k.torus_dd(r, z, d));
                prop_assert!((k.torus_dd(r, z, d) - 2.0 * k.eq5(r, z, d)).abs() <= 1e-9 * scale);
                // Numerical d-derivative agrees: the point is on the envelope.
                let h = 1e-5;
                let num = (k.torus(r, z, d + h) - k.torus(r, z, d - h)) / (2.0 * h);
                prop_assert!((num - k.torus_dd(r, z, d)).abs() <= 1e-6 * scale);
                // The DH chain puts H there at stroke d: φ from eq. 1's
                // cos φ and eq. 4's sin φ, θ2 from φ, then forward kinematics.
                let (s1, c1) = k.alpha1.sin_cos();
                let (r2, z2) = k.r2_z2(d);
                let cos = (r * r + z * z - k.coefficients(d).a) / (2.0 * k.a1 * r2);
                let sin = (z - (k.h2 + z2) * c1) / (r2 * s1);
                prop_assert!((cos * cos + sin * sin - 1.0).abs() < 1e-6);
                let t2 = sin.atan2(cos) + (d * k.alpha2.sin()).atan2(k.a2);
                let p = k.point(0.0, t2, d);
                prop_assert!((p[0].hypot(p[1]) - r).abs() < 1e-6 && (p[2] - z).abs() < 1e-6);
            }
        }

        /// Every root of a quartic with separated roots is found, to within
        /// rounding scaled by how close its neighbours are.
        #[test]
        fn every_root_of_a_quartic_is_found_to_near_full_precision(
            mut r in proptest::collection::vec(-50.0f64..50.0, 4),
            lead in prop_oneof![-3.0f64..-0.1, 0.1f64..3.0],
        ) {
            // Four roots at least 1e-3 apart (a closer pair is the
            // known-quartic test's): each found within a few times what
            // rounding the coefficients alone moves it (ε·Σ|cᵢ||r|ⁱ/|p'(r)|,
            // the root's condition): what halving to adjacent floats gave.
            r.sort_by(f64::total_cmp);
            prop_assume!(r.windows(2).all(|w| w[1] - w[0] > 1e-3));
            let c = with_roots(lead, &r);
            let found = real_roots(&c, -60.0, 60.0);
            prop_assert_eq!(found.len(), 4, "{:?} for {:?}", found, r);
            for (f, t) in found.iter().zip(&r) {
                let slope = poly_eval(&poly_derivative(&c), *t);
                let tol = 16.0 * f64::EPSILON * term_scale(&c, *t) / slope.abs();
                prop_assert!((f - t).abs() <= tol, "{} vs {} (tol {})", f, t, tol);
            }
        }

        /// The quartic's roots are the strokes whose torus meets the point,
        /// the sampled point's own stroke among them.
        #[test]
        fn quartic_roots_contain_the_stroke(k in dh(), t2 in -3.0f64..3.0, d in 0.1f64..5.0) {
            let p = k.point(0.0, t2, d);
            let r = p[0].hypot(p[1]);
            let q = k.quartic(r, p[2]);
            for x in [0.3, 1.7, d] {
                let scale = (k.coefficients(x).a).powi(2);
                prop_assert!((poly_eval(&q, x) - k.torus(r, p[2], x)).abs() <= 1e-9 * scale);
            }
            let roots = real_roots(&q, 0.0, 6.0);
            prop_assert!(roots.iter().any(|x| (x - d).abs() < 1e-6), "{roots:?} vs {d}");
        }
    }

    #[test]
    fn printed_b_prime_is_half_the_derivative() {
        let k = Dh {
            a1: 0.7,
            alpha1: 1.1,
            h2: 0.2,
            a2: 0.3,
            alpha2: 0.9,
        };
        let d = 1.3;
        let h = 1e-6;
        let db = (k.coefficients(d + h).b - k.coefficients(d - h).b) / (2.0 * h);
        let (_, bp, _) = k.derivatives_as_printed(d);
        assert!((db - 2.0 * bp).abs() < 1e-6, "{db} vs 2·{bp}");
        let da = (k.coefficients(d + h).a - k.coefficients(d - h).a) / (2.0 * h);
        let (ap, _, dp) = k.derivatives_as_printed(d);
        assert!((da - ap).abs() < 1e-6);
        let dd = (k.coefficients(d + h).d - k.coefficients(d - h).d) / (2.0 * h);
        assert!((dd - dp).abs() < 1e-6);
    }

    /// The coefficients (constant first) of lead·Π(x − rᵢ).
    fn with_roots(lead: f64, roots: &[f64]) -> Vec<f64> {
        let mut c = vec![lead];
        for &root in roots {
            let mut n = vec![0.0; c.len() + 1];
            for (i, k) in c.iter().enumerate() {
                n[i + 1] += k;
                n[i] -= root * k;
            }
            c = n;
        }
        c
    }

    #[test]
    fn roots_of_a_known_quartic() {
        // (x − 1)(x − 2)(x − 2.000001)(x + 3): close pair kept apart.
        let c = with_roots(1.0, &[1.0, 2.0, 2.000001, -3.0]);
        let found = real_roots(&c, -5.0, 5.0);
        assert_eq!(found.len(), 4, "{found:?}");
        assert!((found[0] + 3.0).abs() < 1e-9);
        assert!(
            (found[2] - 2.0).abs() < 1e-7 && (found[3] - 2.000001).abs() < 1e-7,
            "{found:?}"
        );
        // A double root: (x − 1)².
        assert_eq!(real_roots(&[1.0, -2.0, 1.0], 0.0, 3.0).len(), 1);
    }
}
