//! Air moves: rest-to-rest, jerk-limited, all joints along one line in
//! joint space (a "double S" profile of the line's parameter).

use super::{JointLimits, Kind, TimingError, Trajectory};

/// Rest-to-rest jerk-limited profile of a parameter p from 0 to 1.
#[derive(Clone, Debug)]
pub(super) struct DoubleS {
    /// Per phase: start time, p, ṗ, p̈ at its start, and its jerk.
    phases: Vec<(f64, f64, f64, f64, f64)>,
    pub(super) duration: f64,
}

impl DoubleS {
    /// Biagiotti & Melchiorri, "Trajectory Planning for Automatic Machines
    /// and Robots" §3.4, for a unit displacement from rest to rest.
    pub(super) fn new(v: f64, a: f64, j: f64) -> Self {
        let (mut tj, mut ta);
        if v * j >= a * a {
            tj = a / j;
            ta = tj + v / a;
        } else {
            tj = (v / j).sqrt();
            ta = 2.0 * tj;
        }
        let mut tv = 1.0 / v - ta;
        if tv < 0.0 {
            // The top speed is never reached: no cruise phase.
            tv = 0.0;
            tj = a / j;
            ta = 0.5 * (tj + (tj * tj + 4.0 / a).sqrt());
            if ta < 2.0 * tj {
                // Nor the top acceleration.
                tj = (0.5 / j).cbrt();
                ta = 2.0 * tj;
            }
        }
        let durations = [tj, ta - 2.0 * tj, tj, tv, tj, ta - 2.0 * tj, tj];
        let jerks = [j, 0.0, -j, 0.0, -j, 0.0, j];
        let (mut t, mut p, mut pd, mut pdd) = (0.0, 0.0, 0.0, 0.0);
        let mut phases = Vec::with_capacity(7);
        for (&d, &jk) in durations.iter().zip(jerks.iter()) {
            let d = d.max(0.0);
            phases.push((t, p, pd, pdd, jk));
            p += pd * d + 0.5 * pdd * d * d + jk * d * d * d / 6.0;
            pd += pdd * d + 0.5 * jk * d * d;
            pdd += jk * d;
            t += d;
        }
        DoubleS {
            phases,
            duration: t,
        }
    }

    pub(super) fn eval(&self, t: f64) -> (f64, f64) {
        if t >= self.duration {
            return (1.0, 0.0);
        }
        if t <= 0.0 {
            return (0.0, 0.0);
        }
        let i = self
            .phases
            .partition_point(|ph| ph.0 <= t)
            .saturating_sub(1);
        let (t0, p, pd, pdd, jk) = self.phases[i];
        let d = t - t0;
        let pos = p + pd * d + 0.5 * pdd * d * d + jk * d * d * d / 6.0;
        let vel = pd + pdd * d + 0.5 * jk * d * d;
        (pos.clamp(0.0, 1.0), vel.max(0.0))
    }
}

/// Jerk-limited, synchronised point-to-point move from rest at `q0` to rest at `q1`.
pub fn air_move<const N: usize>(
    q0: [f64; N],
    q1: [f64; N],
    limits: &JointLimits<N>,
    margin: f64,
) -> Result<Trajectory<N>, TimingError> {
    limits.validate()?;
    if !(margin.is_finite() && (0.0..0.5).contains(&margin)) {
        return Err(TimingError::BadOption {
            field: "margin",
            value: margin,
            why: "must lie in [0, 0.5)",
        });
    }
    if q0.iter().chain(q1.iter()).any(|v| !v.is_finite()) {
        return Err(TimingError::NotFinite { index: 0 });
    }
    let dq: [f64; N] = std::array::from_fn(|j| q1[j] - q0[j]);
    let keep = 1.0 - margin;
    // The slowest joint sets the line parameter's limits.
    let (mut v, mut a, mut jk) = (f64::INFINITY, f64::INFINITY, f64::INFINITY);
    for (j, d) in dq.iter().map(|d| d.abs()).enumerate() {
        if d > 0.0 {
            v = v.min(limits.vel[j] * keep / d);
            a = a.min(limits.acc[j] * keep / d);
            jk = jk.min(limits.jerk[j] * keep / d);
        }
    }
    if !v.is_finite() {
        // Nothing moves: an empty move.
        let profile = DoubleS {
            phases: vec![(0.0, 1.0, 0.0, 0.0, 0.0)],
            duration: 0.0,
        };
        return Ok(Trajectory {
            kind: Kind::Air {
                q0,
                q1,
                dq,
                profile,
            },
            duration_s: 0.0,
            slowdowns: Vec::new(),
        });
    }
    let profile = DoubleS::new(v, a, jk);
    let duration_s = profile.duration;
    Ok(Trajectory {
        kind: Kind::Air {
            q0,
            q1,
            dq,
            profile,
        },
        duration_s,
        slowdowns: Vec::new(),
    })
}
