//! What a run accumulates tick by tick: each limit's violations, error
//! statistics, the waviness of a painting segment, and the tally of a whole
//! run ([`Tally`]: one [`Tick`] at a time in, the [`Report`] out).

use super::control::Command;
use super::plant;
use super::report::{
    self, AxisErrors, LimitViolation, PeakPressures, Place, Report, Saturation, StrokeError,
    TraceRow, Unit, VerdictOn, Waviness,
};
use super::run::{Arm, Refs, ServoLimited, Setup};
use super::{safety, Outcome};

/// Accumulates one limit's violations.
#[derive(Clone)]
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
    /// Record a job row's `value` outside `[lo, hi]` at `place`, within
    /// `slack` (float rounding of a row the planner clamped onto a limit).
    fn outside(&mut self, value: f64, lo: f64, hi: f64, slack: f64, place: &Place) {
        let limit = if value < lo { lo } else { hi };
        self.hit((lo - value).max(value - hi) - slack, value, limit, place);
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
            kind: self.kind,
            fails: self.fails,
            first,
            duration_s: self.ticks as f64 * period,
            worst_value: self.worst,
            limit: self.limit,
            message,
        })
    }
}

#[derive(Clone, Default)]
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

/// One control tick as the tally sees it.
pub(super) struct Tick<'a> {
    pub(super) row: usize,
    pub(super) place: Place,
    /// Painting, and the arm not yet stopped.
    pub(super) painting: bool,
    pub(super) before_stop: bool,
    pub(super) refs: &'a Refs,
    pub(super) arm: &'a Arm,
    pub(super) cmd: Command,
    /// Nozzle, its deflection and error (base frame).
    pub(super) nozzle: [f64; 2],
    pub(super) deflection: [f64; 2],
    pub(super) error: [f64; 2],
}

/// The limits a run watches.
#[derive(Clone)]
struct Limits {
    window: LimitTrack,
    stroke: LimitTrack,
    set_rot: LimitTrack,
    set_ext: LimitTrack,
    tilt: LimitTrack,
    vert: LimitTrack,
    relief: LimitTrack,
}

impl Limits {
    fn new() -> Limits {
        Limits {
            window: LimitTrack::new(
                "base_rot_window",
                "base rotation left its safety window",
                Unit::Angle,
                true,
            ),
            stroke: LimitTrack::new(
                "cylinder_stroke",
                "extension cylinder hit its end of stroke",
                Unit::Length,
                true,
            ),
            set_rot: LimitTrack::new(
                "setpoint_base_rot",
                "setpoint base rotation is outside the safety window",
                Unit::Angle,
                true,
            ),
            set_ext: LimitTrack::new(
                "setpoint_extension",
                "setpoint extension is outside the arm's reach",
                Unit::Length,
                true,
            ),
            tilt: LimitTrack::new(
                "tilt_travel",
                "tilt nut setpoint past its travel",
                Unit::Length,
                true,
            ),
            vert: LimitTrack::new(
                "vertical_travel",
                "vertical joint setpoint past its stroke",
                Unit::Length,
                true,
            ),
            relief: LimitTrack::new(
                "relief_valve",
                "a relief valve opened (force demand above what the supply can give)",
                Unit::Pressure,
                false,
            ),
        }
    }

    /// Record this tick against every limit.
    fn observe(&mut self, setup: &Setup, tick: &Tick) {
        let (model, s, row, place) = (setup.model, setup.samples, tick.row, &tick.place);
        let state = &tick.arm.state;
        let th = state[plant::TH];
        let (tlo, thi) = (model.arm.theta_min_rad, model.arm.theta_max_rad);
        self.window.outside(th, tlo, thi, 0.0, place);
        let x = state[plant::X];
        let tol_x = 5e-4;
        let (xlo, xhi) = (model.arm.x_min_m, model.arm.x_max_m());
        let r_lim = if x < xlo {
            model.arm.r_min_m
        } else {
            setup.r_max
        };
        self.stroke.hit(
            (xlo - tol_x - x).max(x - xhi - tol_x),
            model.arm.r_of_x(x),
            r_lim,
            place,
        );
        // Setpoint ranges are judged on the job's own rows, within 1 µm or
        // 1 µrad (float rounding of a row the planner clamped onto a limit),
        // not on the interpolated reference between them, which may
        // overshoot a row that sits on a limit.
        let rlo = model.arm.r_min_m;
        self.set_rot
            .outside(s.base_rot_rad[row], tlo, thi, 1e-6, place);
        self.set_ext
            .outside(s.extension_m[row], rlo, setup.r_max, 1e-6, place);
        let relief = model.hydraulics.relief_pa;
        for p in [plant::PA1, plant::PB1, plant::PA2, plant::PB2] {
            self.relief.hit(state[p] - relief, state[p], relief, place);
        }
        // end-effector travel, judged on the job's own rows within 1 µm
        let (ax, av) = (&model.tilt_nut, &model.vertical);
        self.tilt
            .outside(s.tilt_nut_m[row], ax.min, ax.max, 1e-6, place);
        self.vert
            .outside(s.vertical_m[row], av.min, av.max, 1e-6, place);
    }

    fn finish(self, period: f64) -> Vec<LimitViolation> {
        [
            self.set_rot,
            self.set_ext,
            self.window,
            self.stroke,
            self.tilt,
            self.vert,
            self.relief,
        ]
        .into_iter()
        .filter_map(|l| l.finish(period))
        .collect()
    }
}

/// The tally's logs that only grow (painting errors, turn rates). A
/// checkpoint keeps their lengths, and its run keeps them once: a copy in
/// every checkpoint made a station's memory and time quadratic in its
/// length (cloning them was 39 % of a 25-letter compile's page faults).
#[derive(Clone, Default)]
pub(super) struct Logs {
    wav: Vec<(u32, f64, f64)>,
    turn_rates: Vec<f64>,
}

/// How far a tally's `Logs` ran when a checkpoint was taken.
#[derive(Clone, Copy, Debug)]
pub(super) struct Logged {
    wav: usize,
    turn_rates: usize,
}

/// What a run accumulates.
pub(super) struct Tally {
    all: ErrStats,
    paint: ErrStats,
    per_stroke: std::collections::BTreeMap<i64, ErrStats>,
    sat: Saturation,
    peaks: PeakPressures,
    axis: AxisErrors,
    limits: Limits,
    /// Painting segments for waviness: (segment id, ex, ey).
    wav: Vec<(u32, f64, f64)>,
    seg: u32,
    was_painting: bool,
    turn_rates: Vec<f64>,
    trace: Vec<TraceRow>,
    painting_ticks: u64,
    pub(super) diverged: Option<f64>,
    /// The tick the run ended at, its painting error over
    /// `Options::stop_over_m`.
    pub(super) cut_short_at_s: Option<f64>,
}

impl Tally {
    /// The tally for a checkpoint: everything but its logs, and how far
    /// they ran (`restored` puts them back).
    pub(super) fn checkpoint(&self) -> (Tally, Logged) {
        let t = Tally {
            all: self.all.clone(),
            paint: self.paint.clone(),
            per_stroke: self.per_stroke.clone(),
            sat: self.sat.clone(),
            peaks: self.peaks.clone(),
            axis: self.axis.clone(),
            limits: self.limits.clone(),
            wav: Vec::new(),
            seg: self.seg,
            was_painting: self.was_painting,
            turn_rates: Vec::new(),
            // copied whole: only runs asked for a trace keep one
            // (`Options::keep_trace`), and those the commands run take no
            // checkpoints; compile's resumable runs keep no trace
            trace: self.trace.clone(),
            painting_ticks: self.painting_ticks,
            diverged: self.diverged,
            cut_short_at_s: self.cut_short_at_s,
        };
        let logged = Logged {
            wav: self.wav.len(),
            turn_rates: self.turn_rates.len(),
        };
        (t, logged)
    }

    /// A checkpoint's tally with its logs as far as `logged` from `logs`:
    /// those of the run that took it, or of a later run that resumed
    /// before it (the same ticks, so the same entries).
    pub(super) fn restored(&self, logged: Logged, logs: &Logs) -> Tally {
        let (mut t, _) = self.checkpoint();
        t.wav = logs.wav[..logged.wav].to_vec();
        t.turn_rates = logs.turn_rates[..logged.turn_rates].to_vec();
        t
    }

    /// The logs so far (kept once with a run's checkpoints).
    pub(super) fn logs(&self) -> Logs {
        Logs {
            wav: self.wav.clone(),
            turn_rates: self.turn_rates.clone(),
        }
    }

    pub(super) fn new() -> Tally {
        Tally {
            all: ErrStats::default(),
            paint: ErrStats::default(),
            per_stroke: Default::default(),
            sat: Saturation::default(),
            peaks: PeakPressures::default(),
            axis: AxisErrors::default(),
            limits: Limits::new(),
            wav: Vec::new(),
            seg: 0,
            was_painting: false,
            turn_rates: Vec::new(),
            trace: Vec::new(),
            painting_ticks: 0,
            diverged: None,
            cut_short_at_s: None,
        }
    }

    /// Stage: one tick into the running figures.
    pub(super) fn observe(&mut self, setup: &Setup, tick: &Tick) {
        let (model, period) = (setup.model, setup.period);
        let err = tick.error[0].hypot(tick.error[1]);
        if tick.before_stop {
            self.all.add(err, &tick.place);
        }
        if tick.painting {
            self.painting_ticks += 1;
            self.paint.add(err, &tick.place);
            self.per_stroke
                .entry(tick.place.stroke)
                .or_default()
                .add(err, &tick.place);
            if !self.was_painting {
                self.seg += 1;
            }
            if setup.opts.waviness {
                self.wav.push((self.seg, tick.error[0], tick.error[1]));
                let [_, v, a] = tick.refs.arm.nozzle;
                let v2 = v[0] * v[0] + v[1] * v[1];
                if v2 > 1e-6 {
                    self.turn_rates.push((v[0] * a[1] - v[1] * a[0]).abs() / v2);
                }
            }
        }
        self.was_painting = tick.painting;
        self.limits.observe(setup, tick);
        let st = &tick.arm.state;
        let pk = &mut self.peaks;
        pk.motor_a_pa = pk.motor_a_pa.max(st[plant::PA1]);
        pk.motor_b_pa = pk.motor_b_pa.max(st[plant::PB1]);
        pk.cylinder_a_pa = pk.cylinder_a_pa.max(st[plant::PA2]);
        pk.cylinder_b_pa = pk.cylinder_b_pa.max(st[plant::PB2]);
        if tick.cmd.u_motor.abs() >= model.motor.command_limit * 0.999 {
            self.sat.motor_valve_s += period;
        }
        if tick.cmd.u_cyl.abs() >= model.cylinder.command_limit * 0.999 {
            self.sat.cylinder_valve_s += period;
        }
        let (arm, refs) = (tick.arm, tick.refs);
        let ax = &mut self.axis;
        ax.yaw_rad = ax.yaw_rad.max((arm.yaw.pos - refs.yaw[0]).abs());
        ax.tilt_nut_m = ax.tilt_nut_m.max((arm.nut.pos - refs.nut[0]).abs());
        ax.vertical_m = ax.vertical_m.max((arm.vert.pos - refs.vert[0]).abs());
        if setup.opts.keep_trace {
            self.trace.push(trace_row(setup, tick, err));
        }
    }

    pub(super) fn servo_limited(&mut self, lim: ServoLimited, period: f64) {
        for (hit, s) in [
            (lim.yaw, &mut self.sat.yaw_s),
            (lim.nut, &mut self.sat.tilt_s),
            (lim.vert, &mut self.sat.vertical_s),
        ] {
            if hit {
                *s += period;
            }
        }
    }

    /// Last stage: the figures and the safety monitor's account → the report.
    pub(super) fn report(self, setup: &Setup, safety: Option<safety::SafetyReport>) -> Outcome {
        let (opts, period) = (setup.opts, setup.period);
        let mut turn_rates = self.turn_rates;
        let waviness = waviness(&self.wav, &mut turn_rates, period);
        let verdict_stats = if self.paint.n > 0 {
            &self.paint
        } else {
            &self.all
        };
        let mut reasons = Vec::new();
        if let Some(t) = self.diverged {
            reasons.push(format!(
                "the closed loop diverged (the arm's state grew without bound) at t = {t:.3} s: \
                 the {} controller is unstable on this job",
                opts.controller.name()
            ));
        }
        if let Some(stop) = safety.as_ref().and_then(|s| s.stop.as_ref()) {
            reasons.push(format!(
                "the safety monitor stopped the arm at {}: {}",
                stop.at.describe(),
                stop.cause
            ));
        }
        if verdict_stats.max > opts.tolerance_m {
            reasons.push(format!(
                "nozzle error {:.3} mm exceeds the tolerance {:.3} mm at {}",
                verdict_stats.max * 1e3,
                opts.tolerance_m * 1e3,
                verdict_stats.worst.describe()
            ));
        }
        let limits = self.limits.finish(period);
        for l in limits.iter().filter(|l| l.fails) {
            reasons.push(l.message.clone());
        }
        let strokes = self
            .per_stroke
            .into_iter()
            .map(|(stroke, st)| StrokeError {
                stroke,
                max_error_m: st.max,
                rms_error_m: st.rms(),
                worst: st.worst.clone(),
            })
            .collect();
        let report = Report {
            controller: opts.controller.name().into(),
            tolerance_m: opts.tolerance_m,
            verdict: report::Verdict::of(&reasons),
            verdict_on: VerdictOn::Nominal,
            reasons,
            max_error_m: verdict_stats.max,
            rms_error_m: verdict_stats.rms(),
            worst: verdict_stats.worst.clone(),
            max_error_all_m: self.all.max,
            rms_error_all_m: self.all.rms(),
            strokes,
            waviness,
            saturation: self.sat,
            peak_pressures: self.peaks,
            axis_errors: self.axis,
            cut_short_at_s: self.cut_short_at_s,
            limits,
            duration_s: setup.duration,
            painting_s: self.painting_ticks as f64 * period,
            control_period_s: period,
            integrator_step_s: setup.h,
            plants: None,
            safety,
        };
        Outcome {
            report,
            trace: self.trace,
        }
    }
}

/// One `--trace` row.
fn trace_row(setup: &Setup, tick: &Tick, err: f64) -> TraceRow {
    let s = setup.samples;
    let (st, arm, refs) = (&tick.arm.state, tick.arm, tick.refs);
    let pose = &setup.poses[tick.place.station as usize];
    let a_road = pose.to_road(tick.nozzle);
    TraceRow {
        t_s: tick.place.t_s,
        station: tick.place.station,
        stroke: tick.place.stroke,
        paint: s.paint[tick.row],
        x_desired_m: tick.place.x_m,
        y_desired_m: tick.place.y_m,
        x_m: a_road[0],
        y_m: a_road[1],
        error_m: err,
        deflection_m: tick.deflection[0].hypot(tick.deflection[1]),
        base_rot_desired_rad: refs.arm.base_rot[0],
        base_rot_rad: st[plant::TH],
        extension_desired_m: refs.arm.extension[0],
        extension_m: setup.model.arm.r_of_x(st[plant::X]),
        motor_a_pa: st[plant::PA1],
        motor_b_pa: st[plant::PB1],
        cylinder_a_pa: st[plant::PA2],
        cylinder_b_pa: st[plant::PB2],
        u_motor: tick.cmd.u_motor,
        u_cylinder: tick.cmd.u_cyl,
        ee_yaw_desired_rad: refs.yaw[0],
        ee_yaw_rad: arm.yaw.pos,
        tilt_nut_desired_m: refs.nut[0],
        tilt_nut_m: arm.nut.pos,
        vertical_desired_m: refs.vert[0],
        vertical_m: arm.vert.pos,
    }
}
