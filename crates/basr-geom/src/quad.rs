//! Adaptive Gauss–Legendre quadrature (for arc lengths kurbo cannot measure).

use kurbo::common::GAUSS_LEGENDRE_COEFFS_16;

fn gauss16(f: &impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    let half = 0.5 * (b - a);
    let mid = 0.5 * (a + b);
    half * GAUSS_LEGENDRE_COEFFS_16
        .iter()
        .map(|&(w, x)| w * f(mid + half * x))
        .sum::<f64>()
}

/// Most bisections one integral may make. A smooth integrand needs a
/// handful; one that never meets the tolerance (round-off noise when a curve
/// lies far from the origin, e.g. a line gap of 10⁹ m, or non-finite values)
/// would otherwise bisect to depth 40, some 10¹² pieces: a hang.
const MAX_SPLITS: u32 = 4096;

fn rec(
    f: &impl Fn(f64) -> f64,
    (a, b): (f64, f64),
    whole: f64,
    tol: f64,
    depth: u32,
    splits_left: &mut u32,
) -> f64 {
    let m = 0.5 * (a + b);
    let left = gauss16(f, a, m);
    let right = gauss16(f, m, b);
    let both = left + right;
    // 16-point rule on smooth integrands: the halves' sum is far more accurate
    // than the whole, so their difference bounds the error of the halves.
    if (both - whole).abs() <= tol || depth >= 40 || !both.is_finite() || *splits_left == 0 {
        return both;
    }
    *splits_left -= 1;
    rec(f, (a, m), left, 0.5 * tol, depth + 1, splits_left)
        + rec(f, (m, b), right, 0.5 * tol, depth + 1, splits_left)
}

/// ∫ f over [a, b] to within `tolerance` (absolute), by adaptive bisection
/// with a 16-point Gauss–Legendre rule on each piece.
pub fn integrate(f: impl Fn(f64) -> f64, a: f64, b: f64, tolerance: f64) -> f64 {
    if b <= a {
        return 0.0;
    }
    let whole = gauss16(&f, a, b);
    rec(&f, (a, b), whole, tolerance.max(1e-15), 0, &mut {
        MAX_SPLITS
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polynomial_and_transcendental() {
        assert!((integrate(|x| x * x * x, 0.0, 2.0, 1e-14) - 4.0).abs() < 1e-13);
        let v = integrate(|x| x.sin(), 0.0, std::f64::consts::PI, 1e-14);
        assert!((v - 2.0).abs() < 1e-13);
        // A kinked integrand needs the adaptive split.
        let v = integrate(|x: f64| (x - 0.3).abs(), 0.0, 1.0, 1e-12);
        assert!((v - (0.045 + 0.245)).abs() < 1e-10, "{v}");
    }

    #[test]
    fn an_integrand_that_never_converges_still_ends() {
        // Noise no tolerance can meet (as round-off far from the origin is),
        // and a non-finite integrand: a bounded number of pieces, then done.
        let noisy = |x: f64| 1.0 + ((x * 1e9).sin() * 1e6).fract() * 1e-3;
        let v = integrate(noisy, 0.0, 1.0, 1e-15);
        assert!((v - 1.0).abs() < 1e-2, "{v}");
        assert!(integrate(|_| f64::INFINITY, 0.0, 1.0, 1e-9).is_infinite());
        assert!(integrate(|_| f64::NAN, 0.0, 1.0, 1e-9).is_nan());
    }
}
