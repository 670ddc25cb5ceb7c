//! Trajectories played back to back and sampled at the control period.

use super::{TimingError, Trajectory};

/// Trajectories played back to back, sampled at a fixed period.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Samples<const N: usize> {
    /// t = k·period exactly.
    pub t_s: Vec<f64>,
    /// Index of the trajectory each sample falls in.
    pub piece: Vec<usize>,
    /// Time since that trajectory's start.
    pub local_t_s: Vec<f64>,
    pub q: Vec<[f64; N]>,
    pub qd: Vec<[f64; N]>,
    /// Path parameter (see [`State::s`]).
    pub s: Vec<f64>,
    /// Its rate (see [`State::sd`]).
    pub sd: Vec<f64>,
}

impl<const N: usize> Samples<N> {
    pub fn len(&self) -> usize {
        self.t_s.len()
    }
    pub fn is_empty(&self) -> bool {
        self.t_s.is_empty()
    }
}

/// Most setpoints one job holds. assumed: 10^7 is 2.8 hours at the
/// shortest control period (1 ms, `robot::ranges`), past any stop's work
/// (a long message paints in minutes), and about 1.2 GB of samples here.
pub const MAX_SAMPLES: usize = 10_000_000;

/// Samples `pieces` played one after another (each from rest to rest) at
/// t = k·`period_s`, from 0 through the first multiple of the period at or
/// after the end, which holds the final pose.
pub fn resample<const N: usize>(
    pieces: &[Trajectory<N>],
    period_s: f64,
) -> Result<Samples<N>, TimingError> {
    if !(period_s.is_finite() && period_s > 0.0) {
        return Err(TimingError::BadOption {
            field: "period_s",
            value: period_s,
            why: "must be a positive time",
        });
    }
    let mut out = Samples::default();
    if pieces.is_empty() {
        return Ok(out);
    }
    let starts = super::start_times(pieces);
    let total: f64 = pieces.iter().map(|p| p.duration_s).sum();
    // A hair of slack so a total that is an exact multiple does not gain a sample from rounding.
    let count = (total / period_s - 1e-9).ceil().max(0.0) + 1.0;
    // Sized by the robot's limits: bounded before it is allocated (a
    // telescopic joint at 1e-12 rad/s asked 84 TB here, issue 31 R3).
    // NaN (an infinite total over a period) is refused with the rest.
    if count.is_nan() || count > MAX_SAMPLES as f64 {
        return Err(TimingError::TooLong {
            duration_s: total,
            samples: count,
            period_s,
        });
    }
    let count = count as usize;
    for v in [&mut out.t_s, &mut out.local_t_s, &mut out.s, &mut out.sd] {
        v.reserve(count);
    }
    out.piece.reserve(count);
    out.q.reserve(count);
    out.qd.reserve(count);
    let mut p = 0;
    let mut cursor = 0;
    for k in 0..count {
        let t = k as f64 * period_s;
        while p + 1 < pieces.len() && t >= starts[p + 1] {
            p += 1;
            cursor = 0;
        }
        let local = (t - starts[p]).min(pieces[p].duration_s);
        let st = pieces[p].state_with_cursor(local, &mut cursor);
        out.t_s.push(t);
        out.piece.push(p);
        out.local_t_s.push(local);
        out.q.push(st.q);
        out.qd.push(st.qd);
        out.s.push(st.s);
        out.sd.push(st.sd);
    }
    Ok(out)
}
