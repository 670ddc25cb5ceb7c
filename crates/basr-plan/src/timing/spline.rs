//! The joints' shape along a painting path: a shape-preserving cubic
//! (PCHIP) through the waypoints in s, and the grid the speed profile is
//! found on.

use super::PathPoint;

/// Shape-preserving cubic Hermite interpolation (PCHIP) of the waypoints in s.
#[derive(Clone, Debug)]
pub(super) struct Spline<const N: usize> {
    s: Vec<f64>,
    q: Vec<[f64; N]>,
    m: Vec<[f64; N]>,
}

impl<const N: usize> Spline<N> {
    // Index loops read like the formulas (per joint j, per waypoint k).
    #[allow(clippy::needless_range_loop)]
    pub(super) fn new(points: &[PathPoint<N>]) -> Self {
        let n = points.len();
        let s: Vec<f64> = points.iter().map(|p| p.s_m).collect();
        let q: Vec<[f64; N]> = points.iter().map(|p| p.q).collect();
        let slope = |k: usize| -> [f64; N] {
            let h = s[k + 1] - s[k];
            std::array::from_fn(|j| (q[k + 1][j] - q[k][j]) / h)
        };
        let mut m = vec![[0.0; N]; n];
        for j in 0..N {
            let d = |k: usize| slope(k)[j];
            let h = |k: usize| s[k + 1] - s[k];
            if n == 2 {
                m[0][j] = d(0);
                m[1][j] = d(0);
                continue;
            }
            for k in 1..n - 1 {
                let (d0, d1) = (d(k - 1), d(k));
                // Fritsch–Carlson: flat at a local extremum, else a weighted
                // harmonic mean of the neighbouring chords.
                m[k][j] = if d0 * d1 > 0.0 {
                    let (w1, w2) = (2.0 * h(k) + h(k - 1), h(k) + 2.0 * h(k - 1));
                    (w1 + w2) / (w1 / d0 + w2 / d1)
                } else {
                    0.0
                };
            }
            // Ends: the one-sided three-point slope, kept shape-preserving.
            let end = |h0: f64, h1: f64, d0: f64, d1: f64| {
                let v = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
                if v * d0 <= 0.0 {
                    0.0
                } else if d0 * d1 <= 0.0 && v.abs() > 3.0 * d0.abs() {
                    3.0 * d0
                } else {
                    v
                }
            };
            m[0][j] = end(h(0), h(1), d(0), d(1));
            m[n - 1][j] = end(h(n - 2), h(n - 3), d(n - 2), d(n - 3));
        }
        for (mk, p) in m.iter_mut().zip(points) {
            if let Some(d) = p.dq_ds {
                *mk = d;
            }
        }
        Spline { s, q, m }
    }

    /// q, dq/ds, d²q/ds² at `s` on segment `k` (s may be at either end).
    pub(super) fn eval(&self, k: usize, s: f64) -> ([f64; N], [f64; N], [f64; N]) {
        let h = self.s[k + 1] - self.s[k];
        let t = ((s - self.s[k]) / h).clamp(0.0, 1.0);
        let (t2, t3) = (t * t, t * t * t);
        let (q0, q1, m0, m1) = (&self.q[k], &self.q[k + 1], &self.m[k], &self.m[k + 1]);
        let mut q = [0.0; N];
        let mut d1 = [0.0; N];
        let mut d2 = [0.0; N];
        for j in 0..N {
            q[j] = (2.0 * t3 - 3.0 * t2 + 1.0) * q0[j]
                + (t3 - 2.0 * t2 + t) * h * m0[j]
                + (-2.0 * t3 + 3.0 * t2) * q1[j]
                + (t3 - t2) * h * m1[j];
            d1[j] = ((6.0 * t2 - 6.0 * t) * q0[j]
                + (3.0 * t2 - 4.0 * t + 1.0) * h * m0[j]
                + (-6.0 * t2 + 6.0 * t) * q1[j]
                + (3.0 * t2 - 2.0 * t) * h * m1[j])
                / h;
            d2[j] = ((12.0 * t - 6.0) * q0[j]
                + (6.0 * t - 4.0) * h * m0[j]
                + (-12.0 * t + 6.0) * q1[j]
                + (6.0 * t - 2.0) * h * m1[j])
                / (h * h);
        }
        // Waypoints exactly, not as the sum of the basis terms.
        if t == 0.0 {
            q = *q0;
        } else if t == 1.0 {
            q = *q1;
        }
        (q, d1, d2)
    }

    /// Largest |dq_j/ds| over [s0, s1] within segment k, per joint: dq/ds is
    /// a quadratic there, so its extremes are at the ends or at its vertex.
    pub(super) fn max_slope(&self, k: usize, s0: f64, s1: f64) -> [f64; N] {
        let h = self.s[k + 1] - self.s[k];
        let (t0, t1) = (
            ((s0 - self.s[k]) / h).clamp(0.0, 1.0),
            ((s1 - self.s[k]) / h).clamp(0.0, 1.0),
        );
        let (q0, q1, m0, m1) = (&self.q[k], &self.q[k + 1], &self.m[k], &self.m[k + 1]);
        std::array::from_fn(|j| {
            let a = (6.0 * q0[j] - 6.0 * q1[j]) / h + 3.0 * m0[j] + 3.0 * m1[j];
            let b = (-6.0 * q0[j] + 6.0 * q1[j]) / h - 4.0 * m0[j] - 2.0 * m1[j];
            let c = m0[j];
            let f = |t: f64| (a * t * t + b * t + c).abs();
            let mut best = f(t0).max(f(t1));
            if a != 0.0 {
                let tv = -b / (2.0 * a);
                if tv > t0 && tv < t1 {
                    best = best.max(f(tv));
                }
            }
            best
        })
    }
}

/// Grid point of a timed path: s, the spline segment of the step that
/// starts here, ṡ here, s̈ over the step, and the time here.
#[derive(Clone, Copy, Debug)]
pub(super) struct GridPoint {
    pub(super) s: f64,
    pub(super) seg: usize,
    pub(super) sd: f64,
    pub(super) sdd: f64,
    pub(super) t: f64,
}
