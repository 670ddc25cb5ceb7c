//! What a run accumulates tick by tick: each limit's violations, error
//! statistics, and the waviness of a painting segment.

use super::report::{self, LimitViolation, Place, Unit, Waviness};

/// Accumulates one limit's violations.
pub(super) struct LimitTrack {
    kind: &'static str,
    fails: bool,
    limit: f64,
    first: Option<Place>,
    worst: f64,
    ticks: u64,
    what: &'static str,
    unit: Unit,
}

impl LimitTrack {
    pub(super) fn new(
        kind: &'static str,
        what: &'static str,
        unit: Unit,
        fails: bool,
    ) -> LimitTrack {
        LimitTrack {
            kind,
            fails,
            limit: 0.0,
            first: None,
            worst: 0.0,
            ticks: 0,
            what,
            unit,
        }
    }
    /// Record `value` past `limit` by `excess` > 0 at `place`.
    pub(super) fn hit(&mut self, excess: f64, value: f64, limit: f64, place: &Place) {
        if excess <= 0.0 {
            return;
        }
        self.ticks += 1;
        if self.first.is_none() || excess > (self.worst - self.limit).abs() {
            self.worst = value;
            self.limit = limit;
        }
        if self.first.is_none() {
            self.first = Some(place.clone());
        }
    }
    pub(super) fn finish(self, period: f64) -> Option<LimitViolation> {
        let first = self.first?;
        let message = format!(
            "{} (reached {} against {}) first at {}, for {:.3} s",
            self.what,
            self.unit.show(self.worst),
            self.unit.show(self.limit),
            first.describe(),
            self.ticks as f64 * period
        );
        Some(LimitViolation {
            kind: self.kind.into(),
            fails: self.fails,
            first,
            duration_s: self.ticks as f64 * period,
            worst_value: self.worst,
            limit: self.limit,
            message,
        })
    }
}

#[derive(Default)]
pub(super) struct ErrStats {
    pub(super) max: f64,
    sum2: f64,
    pub(super) n: u64,
    pub(super) worst: Place,
}

impl ErrStats {
    pub(super) fn add(&mut self, e: f64, p: &Place) {
        if e > self.max || self.n == 0 {
            self.max = e;
            self.worst = p.clone();
        }
        self.sum2 += e * e;
        self.n += 1;
    }
    pub(super) fn rms(&self) -> f64 {
        if self.n == 0 {
            0.0
        } else {
            (self.sum2 / self.n as f64).sqrt()
        }
    }
}

fn highpass_and_measure(
    ex: &mut [f64],
    ey: &mut [f64],
    cutoff: f64,
    dt: f64,
    max: &mut f64,
    sum2: &mut f64,
    n: &mut u64,
) {
    report::highpass_zero_phase(ex, cutoff, dt);
    report::highpass_zero_phase(ey, cutoff, dt);
    for (a, b) in ex.iter().zip(ey.iter()) {
        let e = a.hypot(*b);
        *max = max.max(e);
        *sum2 += e * e;
        *n += 1;
    }
}

/// Waviness: each painting segment's error `(segment, ex, ey)` high-passed
/// above 4× the path's 95th-percentile turning rate (0.5–5 Hz).
pub(super) fn waviness(wav: &[(u32, f64, f64)], turn_rates: &mut [f64], period: f64) -> Waviness {
    // waviness: high-pass each painting segment's error above the path's content
    turn_rates.sort_by(f64::total_cmp);
    let f_path = turn_rates
        .get(((turn_rates.len() as f64) * 0.95) as usize)
        .or(turn_rates.last())
        .copied()
        .unwrap_or(0.0)
        / std::f64::consts::TAU;
    let cutoff = (4.0 * f_path).clamp(0.5, 5.0);
    let mut waviness = Waviness {
        cutoff_hz: cutoff,
        ..Default::default()
    };
    let (mut w2, mut wn) = (0.0, 0u64);
    let mut i = 0;
    while i < wav.len() {
        let id = wav[i].0;
        let j = wav[i..]
            .iter()
            .position(|w| w.0 != id)
            .map_or(wav.len(), |p| i + p);
        let mut ex: Vec<f64> = wav[i..j].iter().map(|w| w.1).collect();
        let mut ey: Vec<f64> = wav[i..j].iter().map(|w| w.2).collect();
        highpass_and_measure(
            &mut ex,
            &mut ey,
            cutoff,
            period,
            &mut waviness.max_m,
            &mut w2,
            &mut wn,
        );
        i = j;
    }
    waviness.rms_m = if wn > 0 { (w2 / wn as f64).sqrt() } else { 0.0 };
    waviness
}
