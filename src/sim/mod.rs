//! Closed-loop simulation: arm and hydraulics plant, sensors, controllers, integrator, report.
//!
//! `simulate(job, model, options, progress)` plays a job's setpoints through
//! the controller of 000 section III into the plant of section II, every
//! 5 ms with RK4 sub-steps, and measures where the nozzle actually went.

pub mod circuit;
pub mod control;
pub mod ee;
pub mod fault;
pub mod model;
pub mod plant;
pub mod plants;
mod reference;
pub mod report;
pub mod safety;
pub mod servo;
pub mod servo_job;
pub mod svg;
pub mod synthetic;
mod tally;

pub use control::{Command, Controller, ControllerKind, Measurement, Reference};
pub use model::SimModel;
pub use report::{Report, TraceRow};

use crate::job::Job;
use crate::robot::Joints;
use plant::{Inputs, State};
use reference::{curve, within, NutTable, Pose};
use report::{AxisErrors, LimitViolation, PeakPressures, Place, Saturation, StrokeError, Unit};
use tally::{ErrStats, LimitTrack};

/// Errors from setting up a simulation (bad input: exit 2).
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    #[error("job cannot be simulated: {0}")]
    Job(String),
    #[error("robot dynamics invalid: {0}; fix the robot description's [dynamics] table")]
    Model(String),
    #[error("simulation option invalid: {0}")]
    Option(String),
}

/// How to run.
#[derive(Clone, Debug)]
pub struct Options {
    pub controller: ControllerKind,
    /// Verdict threshold on the nozzle error while painting (m).
    pub tolerance_m: f64,
    /// Keep one `TraceRow` per control tick.
    pub keep_trace: bool,
    /// Override the model's RK4 sub-steps per control period (convergence checks).
    pub substeps: Option<u32>,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            controller: ControllerKind::Sjct,
            tolerance_m: 6.35e-3, // SPEC §4: 1/4 in
            keep_trace: false,
            substeps: None,
        }
    }
}

/// What a run returns.
#[derive(Clone, Debug)]
pub struct Outcome {
    pub report: Report,
    /// Empty unless `Options::keep_trace`.
    pub trace: Vec<TraceRow>,
}

/// Yaw axis meets the road: W = R·(cos θ1, sin θ1) + a2·(sin θ1, −cos θ1) (SPEC §2).
pub fn nozzle_base(model: &SimModel, theta: f64, r: f64) -> [f64; 2] {
    let (s, c) = theta.sin_cos();
    let a2 = model.arm.a2_m;
    [r * c + a2 * s, r * s - a2 * c]
}

/// Check the job's numbers before running (bad input → exit 2).
fn validate_job(job: &Job) -> Result<(), SimError> {
    let s = &job.samples;
    let n = s.check_lengths().map_err(SimError::Job)?;
    if n < 2 {
        return Err(SimError::Job(format!(
            "it has {n} setpoint rows; at least 2 are needed"
        )));
    }
    if !(job.control_period_s.is_finite() && job.control_period_s > 0.0) {
        return Err(SimError::Job(format!(
            "control_period_s = {} must be a positive number of seconds",
            job.control_period_s
        )));
    }
    let cols: [(&str, &Vec<f64>); 8] = [
        ("x_m", &s.x_m),
        ("y_m", &s.y_m),
        ("base_rot_rad", &s.base_rot_rad),
        ("extension_m", &s.extension_m),
        ("vertical_m", &s.vertical_m),
        ("ee_yaw_rad", &s.ee_yaw_rad),
        ("tilt_nut_m", &s.tilt_nut_m),
        ("t_s", &s.t_s),
    ];
    for (name, col) in cols {
        if let Some(i) = col.iter().position(|v| !v.is_finite()) {
            return Err(SimError::Job(format!(
                "samples.{name}[{i}] is not a finite number"
            )));
        }
    }
    for (i, st) in s.station.iter().enumerate() {
        if *st as usize >= job.stations.len() {
            return Err(SimError::Job(format!(
                "samples.station[{i}] = {st} but the job has {} stations",
                job.stations.len()
            )));
        }
    }
    for (i, st) in job.stations.iter().enumerate() {
        if ![st.x_m, st.y_m, st.heading_rad]
            .iter()
            .all(|v| v.is_finite())
        {
            return Err(SimError::Job(format!(
                "stations[{i}] has a non-finite value"
            )));
        }
    }
    Ok(())
}

/// Run `job` through `model` in closed loop. `progress(done, total)` is called
/// now and then with control ticks.
pub fn simulate(
    job: &Job,
    model: &SimModel,
    opts: &Options,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<Outcome, SimError> {
    simulate_plant(job, model, model, opts, progress)
}

/// [`simulate`] with hardware faults injected (`--fault`): the report's
/// `safety` says what happened, when and where, and how the arm stopped.
pub fn simulate_faulted(
    job: &Job,
    model: &SimModel,
    opts: &Options,
    faults: &[fault::Fault],
    progress: &mut dyn FnMut(u64, u64),
) -> Result<Outcome, SimError> {
    run(job, model, model, opts, faults, progress)
}

/// [`simulate`] with the controller built for the `nominal` model (the
/// robot description) driving another `model` (a plant drawn around it).
pub fn simulate_plant(
    job: &Job,
    nominal: &SimModel,
    model: &SimModel,
    opts: &Options,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<Outcome, SimError> {
    run(job, nominal, model, opts, &[], progress)
}

fn run(
    job: &Job,
    nominal: &SimModel,
    model: &SimModel,
    opts: &Options,
    faults: &[fault::Fault],
    progress: &mut dyn FnMut(u64, u64),
) -> Result<Outcome, SimError> {
    validate_job(job)?;
    // The hydraulic plant is BASR's; the electric kinds have theirs (`servo_job`).
    let robot = job.robot.basr().ok_or_else(|| {
        SimError::Job(format!(
            "its robot is of the {} kind, which the hydraulic plant does not model",
            job.robot.kind().name()
        ))
    })?;
    nominal.validate().map_err(SimError::Model)?;
    model.validate().map_err(SimError::Model)?;
    if !(opts.tolerance_m.is_finite() && opts.tolerance_m > 0.0) {
        return Err(SimError::Option(format!(
            "tolerance {} m must be positive",
            opts.tolerance_m
        )));
    }
    if let Some(n) = opts.substeps.filter(|n| !(1..=100).contains(n)) {
        return Err(SimError::Option(format!(
            "substeps = {n} must be 1–100 RK4 steps per control period"
        )));
    }
    let substeps = opts.substeps.unwrap_or(model.substeps);
    fault::check(
        faults,
        (job.samples.len().saturating_sub(1)) as f64 * job.control_period_s,
    )
    .map_err(SimError::Option)?;
    let s = &job.samples;
    let n = s.len();
    let dt_job = job.control_period_s;
    let period = model.control.period_s;
    let h = period / substeps as f64;
    let duration = (n - 1) as f64 * dt_job;
    let ticks = (duration / period + 1e-9).floor() as u64 + 1;

    let poses: Vec<Pose> = job.stations.iter().map(Pose::new).collect();
    // desired nozzle per row in its station's base frame
    let (mut bx, mut by) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for i in 0..n {
        let b = poses[s.station[i] as usize].to_base([s.x_m[i], s.y_m[i]]);
        bx.push(b[0]);
        by.push(b[1]);
    }

    let mut state: State = plant::rest_state(model, s.base_rot_rad[0], s.extension_m[0]);
    let mut yaw = ee::Servo::at(s.ee_yaw_rad[0]);
    let mut nut = ee::Servo::at(s.tilt_nut_m[0]);
    let mut vert = ee::Servo::at(s.vertical_m[0]);

    let sens = &model.sensors;
    let base_q = std::f64::consts::TAU / sens.base_counts_per_turn;
    let p_q = sens.adc_step_v * sens.pressure_pa_per_volt;
    let measure = |st: &State, t: f64, reference: Reference, f: &fault::Active| -> Measurement {
        let quant = |v: f64, q: f64| if sens.exact { v } else { (v / q).round() * q };
        // pressures go through the transducer's volts and the ADC's steps
        let pres = |p: f64| quant(p * sens.pressure_gain, p_q);
        let r = model.arm.r_of_x(st[plant::X]);
        Measurement {
            t_s: t,
            base_rot_rad: quant(st[plant::TH] + f.encoder_offset_rad, base_q),
            extension_m: model.arm.r_min_m
                + quant(r - model.arm.r_min_m, sens.extension_m_per_count),
            motor_pa: [pres(st[plant::PA1]), pres(st[plant::PB1])],
            cylinder_pa: [pres(st[plant::PA2]), pres(st[plant::PB2])],
            supply_pa: pres(st[plant::PS]),
            reference,
        }
    };
    let (r_lo, r_hi) = (model.arm.r_min_m, model.arm.r_of_x(model.arm.x_max_m()));
    let (th_lo, th_hi) = (model.arm.theta_min_rad, model.arm.theta_max_rad);
    let reference_at = |t: f64| -> Reference {
        let nx = curve(&bx, dt_job, t);
        let ny = curve(&by, dt_job, t);
        Reference {
            base_rot: within(curve(&s.base_rot_rad, dt_job, t), th_lo, th_hi),
            extension: within(curve(&s.extension_m, dt_job, t), r_lo, r_hi),
            nozzle: [[nx[0], ny[0]], [nx[1], ny[1]], [nx[2], ny[2]]],
        }
    };

    let nut_to_tilt = NutTable::new(robot);
    let m0 = measure(
        &state,
        0.0,
        reference_at(0.0),
        &fault::Active::at(faults, 0.0, sens.base_counts_per_turn),
    );
    let mut ctrl = opts.controller.build(nominal, &m0);

    let mut all = ErrStats::default();
    let mut paint = ErrStats::default();
    let mut per_stroke: std::collections::BTreeMap<i64, ErrStats> = Default::default();
    let mut sat = Saturation::default();
    let mut peaks = PeakPressures::default();
    let mut axis = AxisErrors::default();
    let mut lim_window = LimitTrack::new(
        "base_rot_window",
        "base rotation left its safety window",
        Unit::Angle,
        true,
    );
    let mut lim_stroke = LimitTrack::new(
        "cylinder_stroke",
        "extension cylinder hit its end of stroke",
        Unit::Length,
        true,
    );
    let mut lim_set_rot = LimitTrack::new(
        "setpoint_base_rot",
        "setpoint base rotation is outside the safety window",
        Unit::Angle,
        true,
    );
    let mut lim_set_ext = LimitTrack::new(
        "setpoint_extension",
        "setpoint extension is outside the arm's reach",
        Unit::Length,
        true,
    );
    let mut lim_tilt = LimitTrack::new(
        "tilt_travel",
        "tilt nut setpoint past its travel",
        Unit::Length,
        true,
    );
    let mut lim_vert = LimitTrack::new(
        "vertical_travel",
        "vertical joint setpoint past its stroke",
        Unit::Length,
        true,
    );
    let mut lim_relief = LimitTrack::new(
        "relief_valve",
        "a relief valve opened (force demand above what the supply can give)",
        Unit::Pressure,
        false,
    );
    // painting segments for waviness: (segment id, ex, ey)
    let mut wav: Vec<(u32, f64, f64)> = Vec::new();
    let mut seg: u32 = 0;
    let mut was_painting = false;
    let mut turn_rates: Vec<f64> = Vec::new();
    let mut trace = Vec::new();
    let mut painting_ticks: u64 = 0;
    let r_max = model.arm.r_of_x(model.arm.x_max_m());

    let mut diverged: Option<f64> = None;
    let mut monitor = safety::Monitor::new(model, faults);
    for k in 0..ticks {
        let t = k as f64 * period;
        let row = ((t / dt_job + 1e-9).floor() as usize).min(n - 1);
        let reference = reference_at(t);
        let active = fault::Active::at(faults, t, sens.base_counts_per_turn);
        let meas = measure(&state, t, reference, &active);
        let cmd = ctrl.step(&meas);
        let station = s.station[row];
        let station_pose = &poses[station as usize];
        // the nozzle now: the robot's FK of the actual joints plus the
        // linkage's deflection
        let r_act = model.arm.r_of_x(state[plant::X]);
        let tilt = nut_to_tilt.tilt(nut.pos);
        let pose = robot.fk(&Joints {
            base_rot_rad: state[plant::TH],
            extension_m: r_act,
            vertical_m: vert.pos,
            ee_yaw_rad: yaw.pos,
            tilt_rad: tilt,
        });
        let bend = plant::boom_offset(&state);
        let act = [
            pose.x_m + state[plant::DX] + bend[0],
            pose.y_m + state[plant::DY] + bend[1],
        ];
        let des = reference.nozzle[0];
        let (ex, ey) = (act[0] - des[0], act[1] - des[1]);
        let err = ex.hypot(ey);
        let des_road = station_pose.to_road(des);
        let place = Place {
            t_s: t,
            stroke: s.stroke[row],
            station,
            x_m: des_road[0],
            y_m: des_road[1],
        };
        let painting = s.paint[row] != 0;
        // the safety monitor: the nozzle off its path by the encoders
        monitor.note_faults(t, period, &place);
        let w_meas = nozzle_base(model, meas.base_rot_rad, meas.extension_m);
        let w_ref = nozzle_base(model, reference.base_rot[0], reference.extension[0]);
        let follow = (w_meas[0] - w_ref[0]).hypot(w_meas[1] - w_ref[1]);
        let before_stop = !monitor.stopped();
        let estop = monitor.check(model, &meas, follow, &place);
        let gun = monitor.gun_open(painting, follow, opts.tolerance_m);
        monitor.nozzle(t, station_pose.to_road(act), err, gun, opts.tolerance_m);
        let cmd = if estop { Command::default() } else { cmd };
        // the job's painting ends where the arm was stopped
        let painting = painting && before_stop;
        if before_stop {
            all.add(err, &place);
        }
        if painting {
            painting_ticks += 1;
            paint.add(err, &place);
            per_stroke
                .entry(s.stroke[row])
                .or_default()
                .add(err, &place);
            if !was_painting {
                seg += 1;
            }
            wav.push((seg, ex, ey));
            let [_, v, a] = reference.nozzle;
            let v2 = v[0] * v[0] + v[1] * v[1];
            if v2 > 1e-6 {
                turn_rates.push((v[0] * a[1] - v[1] * a[0]).abs() / v2);
            }
        }
        was_painting = painting;
        // limits
        let th = state[plant::TH];
        let (tlo, thi) = (model.arm.theta_min_rad, model.arm.theta_max_rad);
        lim_window.hit(
            (tlo - th).max(th - thi),
            th,
            if th < tlo { tlo } else { thi },
            &place,
        );
        let x = state[plant::X];
        let tol_x = 5e-4;
        let (xlo, xhi) = (model.arm.x_min_m, model.arm.x_max_m());
        lim_stroke.hit(
            (xlo - tol_x - x).max(x - xhi - tol_x),
            r_act,
            if x < xlo { model.arm.r_min_m } else { r_max },
            &place,
        );
        // Setpoint ranges are judged on the job's own rows, within 1 µm or
        // 1 µrad (float rounding of a row the planner clamped onto a limit),
        // not on the interpolated reference between them, which may
        // overshoot a row that sits on a limit.
        let thd = s.base_rot_rad[row];
        lim_set_rot.hit(
            (tlo - thd).max(thd - thi) - 1e-6,
            thd,
            if thd < tlo { tlo } else { thi },
            &place,
        );
        let rd = s.extension_m[row];
        let rlo = model.arm.r_min_m;
        lim_set_ext.hit(
            (rlo - rd).max(rd - r_max) - 1e-6,
            rd,
            if rd < rlo { rlo } else { r_max },
            &place,
        );
        for p in [plant::PA1, plant::PB1, plant::PA2, plant::PB2] {
            lim_relief.hit(
                state[p] - model.hydraulics.relief_pa,
                state[p],
                model.hydraulics.relief_pa,
                &place,
            );
        }
        peaks.motor_a_pa = peaks.motor_a_pa.max(state[plant::PA1]);
        peaks.motor_b_pa = peaks.motor_b_pa.max(state[plant::PB1]);
        peaks.cylinder_a_pa = peaks.cylinder_a_pa.max(state[plant::PA2]);
        peaks.cylinder_b_pa = peaks.cylinder_b_pa.max(state[plant::PB2]);
        if cmd.u_motor.abs() >= model.motor.command_limit * 0.999 {
            sat.motor_valve_s += period;
        }
        if cmd.u_cyl.abs() >= model.cylinder.command_limit * 0.999 {
            sat.cylinder_valve_s += period;
        }
        // end-effector setpoints, clipped to their travel (noted if past it)
        let yaw_ref = curve(&s.ee_yaw_rad, dt_job, t);
        let nut_ref = curve(&s.tilt_nut_m, dt_job, t);
        let vert_ref = curve(&s.vertical_m, dt_job, t);
        // travel is judged on the job's own rows (the interpolation may
        // overshoot a setpoint that sits exactly on a limit), within 1 µm
        let ax = &model.tilt_nut;
        let nut_row = s.tilt_nut_m[row];
        lim_tilt.hit(
            (ax.min - nut_row).max(nut_row - ax.max) - 1e-6,
            nut_row,
            if nut_row < ax.min { ax.min } else { ax.max },
            &place,
        );
        let av = &model.vertical;
        let vert_row = s.vertical_m[row];
        lim_vert.hit(
            (av.min - vert_row).max(vert_row - av.max) - 1e-6,
            vert_row,
            if vert_row < av.min { av.min } else { av.max },
            &place,
        );
        axis.yaw_rad = axis.yaw_rad.max((yaw.pos - yaw_ref[0]).abs());
        axis.tilt_nut_m = axis.tilt_nut_m.max((nut.pos - nut_ref[0]).abs());
        axis.vertical_m = axis.vertical_m.max((vert.pos - vert_ref[0]).abs());
        if opts.keep_trace {
            let a_road = station_pose.to_road(act);
            trace.push(TraceRow {
                t_s: t,
                station,
                stroke: s.stroke[row],
                paint: s.paint[row],
                x_desired_m: des_road[0],
                y_desired_m: des_road[1],
                x_m: a_road[0],
                y_m: a_road[1],
                error_m: err,
                deflection_m: (state[plant::DX] + bend[0]).hypot(state[plant::DY] + bend[1]),
                base_rot_desired_rad: reference.base_rot[0],
                base_rot_rad: th,
                extension_desired_m: reference.extension[0],
                extension_m: r_act,
                motor_a_pa: state[plant::PA1],
                motor_b_pa: state[plant::PB1],
                cylinder_a_pa: state[plant::PA2],
                cylinder_b_pa: state[plant::PB2],
                u_motor: cmd.u_motor,
                u_cylinder: cmd.u_cyl,
                ee_yaw_desired_rad: yaw_ref[0],
                ee_yaw_rad: yaw.pos,
                tilt_nut_desired_m: nut_ref[0],
                tilt_nut_m: nut.pos,
                vertical_desired_m: vert_ref[0],
                vertical_m: vert.pos,
            });
        }
        if k + 1 == ticks {
            break;
        }
        // advance one control period
        let inputs = Inputs {
            u_motor: cmd.u_motor,
            u_cyl: cmd.u_cyl,
            estop,
            faults: active,
        };
        let (mut ys, mut ts, mut vs) = (false, false, false);
        let clip = |v: f64, a: &model::ServoAxis| v.clamp(a.min, a.max);
        for _ in 0..substeps {
            plant::rk4_step(model, &mut state, &inputs, h);
            ys |= yaw.step(&model.yaw, clip(yaw_ref[0], &model.yaw), yaw_ref[1], h);
            ts |= nut.step(ax, clip(nut_ref[0], ax), nut_ref[1], h);
            vs |= vert.step(av, clip(vert_ref[0], av), vert_ref[1], h);
        }
        if ys {
            sat.yaw_s += period;
        }
        if ts {
            sat.tilt_s += period;
        }
        if vs {
            sat.vertical_s += period;
        }
        if state.iter().any(|v| !v.is_finite()) {
            // an unstable loop: a failed run, judged on what it did so far
            diverged = Some(t);
            break;
        }
        if k % 2000 == 0 {
            progress(k, ticks);
        }
        if monitor.done(t) {
            break;
        }
    }
    progress(ticks, ticks);

    let waviness = tally::waviness(&wav, &mut turn_rates, period);

    let verdict_stats = if paint.n > 0 { &paint } else { &all };
    let mut reasons = Vec::new();
    if let Some(t) = diverged {
        reasons.push(format!(
            "the closed loop diverged (the arm's state grew without bound) at t = {t:.3} s: \
             the {} controller is unstable on this job",
            opts.controller.name()
        ));
    }
    let safety = monitor.finish();
    if let Some(stop) = safety.as_ref().and_then(|s| s.stop.as_ref()) {
        reasons.push(format!(
            "the safety monitor stopped the arm at {}: {}",
            stop.at.describe(),
            stop.cause
        ));
    }
    if verdict_stats.max > opts.tolerance_m {
        let w = &verdict_stats.worst;
        reasons.push(format!(
            "nozzle error {:.3} mm exceeds the tolerance {:.3} mm at {}",
            verdict_stats.max * 1e3,
            opts.tolerance_m * 1e3,
            w.describe()
        ));
    }
    let limits: Vec<LimitViolation> = [
        lim_set_rot,
        lim_set_ext,
        lim_window,
        lim_stroke,
        lim_tilt,
        lim_vert,
        lim_relief,
    ]
    .into_iter()
    .filter_map(|l| l.finish(period))
    .collect();
    for l in limits.iter().filter(|l| l.fails) {
        reasons.push(l.message.clone());
    }
    let strokes = per_stroke
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
        verdict: if reasons.is_empty() { "pass" } else { "fail" }.into(),
        reasons,
        max_error_m: verdict_stats.max,
        rms_error_m: verdict_stats.rms(),
        worst: verdict_stats.worst.clone(),
        max_error_all_m: all.max,
        rms_error_all_m: all.rms(),
        strokes,
        waviness,
        saturation: sat,
        peak_pressures: peaks,
        axis_errors: axis,
        limits,
        duration_s: duration,
        painting_s: painting_ticks as f64 * period,
        control_period_s: period,
        integrator_step_s: h,
        plants: None,
        safety,
    };
    Ok(Outcome { report, trace })
}
