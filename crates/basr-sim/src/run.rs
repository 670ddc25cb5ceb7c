//! One closed-loop run as stages, each with one typed input and output:
//!
//! - [`prepare`]: job, models, options and faults → [`Setup`] (everything
//!   checked, the job's nozzle path in each station's base frame);
//! - per control tick, [`Setup::references`] (t → [`Refs`]),
//!   [`Setup::measure`] (the plant's state → the controller's
//!   [`Measurement`]), the controller and the safety monitor, then
//!   [`Arm::advance`] (held [`Inputs`] → the plant one period on);
//! - [`Tally::observe`] (in `tally`): one tick's [`Tick`] → the running figures;
//! - [`Tally::report`]: the figures → the `Report`.

use super::control::{Command, Controller, Measurement, Reference};
use super::fault::{self, Active, Fault};
use super::lockstep;
use super::model::{ServoAxis, SimModel};
use super::plant::{self, Inputs, State};
use super::reference::{curve, within, NutTable, Pose};
use super::report::Place;
use super::tally::{Logged, Logs, Tally, Tick};
use super::{ee, nozzle_base, safety, validate_job, Options, Outcome, SimError};
use basr_job::{Job, Samples};
use basr_robot::{Joints, Robot};

/// A checked run, ready to tick.
pub(super) struct Setup<'a> {
    pub(super) samples: &'a Samples,
    pub(super) robot: &'a Robot,
    /// The controller is built for `nominal`; `model` is the plant.
    pub(super) nominal: &'a SimModel,
    pub(super) model: &'a SimModel,
    pub(super) opts: &'a Options,
    pub(super) faults: &'a [Fault],
    pub(super) poses: Vec<Pose>,
    /// The job's nozzle path in its stations' base frames.
    pub(super) base_x: Vec<f64>,
    pub(super) base_y: Vec<f64>,
    pub(super) nut_to_tilt: NutTable,
    pub(super) dt_job: f64,
    pub(super) period: f64,
    pub(super) substeps: u32,
    pub(super) h: f64,
    pub(super) ticks: u64,
    pub(super) duration: f64,
    /// Encoder and pressure-ADC quanta.
    pub(super) base_q: f64,
    pub(super) pressure_q: f64,
    pub(super) r_max: f64,
}

/// Stage 1: check everything a run needs and lay the job out for it.
pub(super) fn prepare<'a>(
    job: &'a Job,
    nominal: &'a SimModel,
    model: &'a SimModel,
    opts: &'a Options,
    faults: &'a [Fault],
) -> Result<Setup<'a>, SimError> {
    validate_job(job)?;
    // The hydraulic plant is BASR's; the electric kinds have theirs (`servo_job`).
    let robot = job.robot.basr().ok_or_else(|| {
        SimError::Job(format!(
            "its robot is of the {} kind, which the hydraulic plant does not model",
            job.robot.kind().name()
        ))
    })?;
    nominal
        .validate()
        .map_err(|e| SimError::Model(e.to_string()))?;
    model
        .validate()
        .map_err(|e| SimError::Model(e.to_string()))?;
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
    .map_err(|e| SimError::Option(e.to_string()))?;
    let s = &job.samples;
    let n = s.len();
    let dt_job = job.control_period_s;
    let period = model.control.period_s;
    let duration = (n - 1) as f64 * dt_job;
    let poses: Vec<Pose> = job.stations.iter().map(Pose::new).collect();
    let (mut base_x, mut base_y) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for i in 0..n {
        let b = poses[s.station[i] as usize].to_base([s.x_m[i], s.y_m[i]]);
        base_x.push(b[0]);
        base_y.push(b[1]);
    }
    let sens = &model.sensors;
    Ok(Setup {
        samples: s,
        robot,
        nominal,
        model,
        opts,
        faults,
        poses,
        base_x,
        base_y,
        nut_to_tilt: NutTable::new(robot),
        dt_job,
        period,
        substeps,
        h: period / substeps as f64,
        ticks: (duration / period + 1e-9).floor() as u64 + 1,
        duration,
        base_q: std::f64::consts::TAU / sens.base_counts_per_turn,
        pressure_q: sens.adc_step_v * sens.pressure_pa_per_volt,
        r_max: model.arm.r_of_x(model.arm.x_max_m()),
    })
}

/// The trajectory generator's output at one tick: the arm's reference and
/// the end-effector axes' (position, rate).
#[derive(Clone, Copy, Debug)]
pub(super) struct Refs {
    pub(super) arm: Reference,
    pub(super) yaw: [f64; 3],
    pub(super) nut: [f64; 3],
    pub(super) vert: [f64; 3],
}

impl Setup<'_> {
    /// The reference at `t`, held within the joints' ranges.
    fn references(&self, t: f64) -> Refs {
        let (s, dt, arm) = (self.samples, self.dt_job, &self.model.arm);
        let nx = curve(&self.base_x, dt, t);
        let ny = curve(&self.base_y, dt, t);
        let (th_lo, th_hi) = (arm.theta_min_rad, arm.theta_max_rad);
        Refs {
            arm: Reference {
                base_rot: within(curve(&s.base_rot_rad, dt, t), th_lo, th_hi),
                extension: within(curve(&s.extension_m, dt, t), arm.r_min_m, self.r_max),
                nozzle: [[nx[0], ny[0]], [nx[1], ny[1]], [nx[2], ny[2]]],
            },
            yaw: curve(&s.ee_yaw_rad, dt, t),
            nut: curve(&s.tilt_nut_m, dt, t),
            vert: curve(&s.vertical_m, dt, t),
        }
    }

    /// What the controller reads: quantised encoders, pressures through the
    /// transducers' volts and the ADC's steps.
    fn measure(&self, st: &State, t: f64, reference: Reference, f: &Active) -> Measurement {
        let (model, sens) = (self.model, &self.model.sensors);
        let quant = |v: f64, q: f64| if sens.exact { v } else { (v / q).round() * q };
        let pres = |p: f64| quant(p * sens.pressure_gain, self.pressure_q);
        let r = model.arm.r_of_x(st[plant::X]);
        Measurement {
            t_s: t,
            base_rot_rad: quant(st[plant::TH] + f.encoder_offset_rad, self.base_q),
            extension_m: model.arm.r_min_m
                + quant(r - model.arm.r_min_m, sens.extension_m_per_count),
            motor_pa: [pres(st[plant::PA1]), pres(st[plant::PB1])],
            cylinder_pa: [pres(st[plant::PA2]), pres(st[plant::PB2])],
            supply_pa: pres(st[plant::PS]),
            reference,
        }
    }

    fn active(&self, t: f64) -> Active {
        Active::at(self.faults, t, self.model.sensors.base_counts_per_turn)
    }

    /// The job's row at `t`.
    fn row(&self, t: f64) -> usize {
        ((t / self.dt_job + 1e-9).floor() as usize).min(self.samples.len() - 1)
    }
}

/// The plant: arm and hydraulics, and the end-effector's servo axes.
#[derive(Clone)]
pub(super) struct Arm {
    pub(super) state: State,
    pub(super) yaw: ee::Servo,
    pub(super) nut: ee::Servo,
    pub(super) vert: ee::Servo,
}

/// Which end-effector axes hit a rate or acceleration limit in a period.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct ServoLimited {
    pub(super) yaw: bool,
    pub(super) nut: bool,
    pub(super) vert: bool,
}

impl Arm {
    fn at_rest(setup: &Setup) -> Arm {
        let s = setup.samples;
        Arm {
            state: plant::rest_state(setup.model, s.base_rot_rad[0], s.extension_m[0]),
            yaw: ee::Servo::at(s.ee_yaw_rad[0]),
            nut: ee::Servo::at(s.tilt_nut_m[0]),
            vert: ee::Servo::at(s.vertical_m[0]),
        }
    }

    /// The nozzle now (base frame): the robot's FK of the actual joints
    /// plus the linkage's deflection and the links' bending; and that
    /// deflection alone.
    fn nozzle(&self, setup: &Setup) -> ([f64; 2], [f64; 2]) {
        let st = &self.state;
        let pose = setup.robot.fk(&Joints {
            base_rot_rad: st[plant::TH],
            extension_m: setup.model.arm.r_of_x(st[plant::X]),
            vertical_m: self.vert.pos,
            ee_yaw_rad: self.yaw.pos,
            tilt_rad: setup.nut_to_tilt.tilt(self.nut.pos),
        });
        let bend = plant::boom_offset(st);
        (
            [
                pose.x_m + st[plant::DX] + bend[0],
                pose.y_m + st[plant::DY] + bend[1],
            ],
            [st[plant::DX] + bend[0], st[plant::DY] + bend[1]],
        )
    }

    /// Stage: the plant one control period on under held `inputs`, the
    /// end-effector axes towards their references (clipped to travel).
    pub(super) fn advance(&mut self, setup: &Setup, inputs: &Inputs, refs: &Refs) -> ServoLimited {
        let model = setup.model;
        let clip = |v: f64, a: &ServoAxis| v.clamp(a.min, a.max);
        let (ay, an, av) = (&model.yaw, &model.tilt_nut, &model.vertical);
        let mut lim = ServoLimited::default();
        for _ in 0..setup.substeps {
            plant::rk4_step(model, &mut self.state, inputs, setup.h);
            lim.yaw |= self
                .yaw
                .step(ay, clip(refs.yaw[0], ay), refs.yaw[1], setup.h);
            lim.nut |= self
                .nut
                .step(an, clip(refs.nut[0], an), refs.nut[1], setup.h);
            lim.vert |= self
                .vert
                .step(av, clip(refs.vert[0], av), refs.vert[1], setup.h);
        }
        lim
    }
}

/// Simulated time between checkpoints of a resumable run (s), over its
/// last [`COARSE_CHECKPOINT_S`]; before that only every
/// `COARSE_CHECKPOINT_S` is kept. assumed: a failed run is re-timed for
/// a join or move just before its failure, so a resumed run starts from
/// at most this much before the first changed row, and a station of STOP
/// (144 s) keeps 33 copies of the run's state at most. Measured (control
/// ticks of all seven runs, 2026-12-06): `basr fit`'s re-plan of STOP in
/// `benches/fit.rs`, whose plants fail once at 24.2 s, 204 998 ticks with
/// this and 209 198 with every 5 s alone; compile STOP 204 152 and
/// 205 352. Every second kept all along raised the 200-letter compile's
/// peak memory from 1.35× to 1.69× its job file (the failed runs'
/// checkpoints wait for their next round). A resumed run's report is the
/// same at any spacing (`Checkpoints`), so the spacing changes no job's
/// bytes.
pub(crate) const CHECKPOINT_S: f64 = 1.0;

/// Simulated time between the checkpoints a run keeps further back than
/// this from its newest (s): a multiple of [`CHECKPOINT_S`]. assumed: the
/// spacing every checkpoint had before the finer one, whose memory the
/// 200-letter compile was measured with.
const COARSE_CHECKPOINT_S: f64 = 5.0;

/// A run's state at points along it, kept so that a run of the same job
/// whose rows changed only from some row on resumes at the last point
/// before that row instead of from the start: compile re-times one join
/// or one move at a time, and the rows before it do not change. The
/// resumed run's report is the one a whole run gives, bit for bit (the
/// rows before the change are the same, and so is every tick that reads
/// only them).
pub struct Checkpoints {
    /// What the run was: its plant and controller's models, options,
    /// faults and the job's stations and row period. A run of anything
    /// else does not resume from these.
    of: RunKey,
    marks: Vec<Mark>,
    /// The tally's logs as the run left them; each mark's are a prefix.
    logs: Logs,
}

/// What a run's state depends on besides the job's rows.
#[derive(Clone, Debug, PartialEq)]
struct RunKey {
    nominal: SimModel,
    model: SimModel,
    controller: super::ControllerKind,
    tolerance_m: f64,
    substeps: u32,
    stop_over_m: Option<f64>,
    waviness: bool,
    faults: Vec<Fault>,
    stations: Vec<basr_job::Station>,
    dt_job: f64,
}

impl RunKey {
    fn of(setup: &Setup, job: &Job) -> RunKey {
        RunKey {
            nominal: setup.nominal.clone(),
            model: setup.model.clone(),
            controller: setup.opts.controller,
            tolerance_m: setup.opts.tolerance_m,
            substeps: setup.substeps,
            stop_over_m: setup.opts.stop_over_m,
            waviness: setup.opts.waviness,
            faults: setup.faults.to_vec(),
            stations: job.stations.clone(),
            dt_job: setup.dt_job,
        }
    }
}

/// The run's whole state before one tick (the tally's logs as far as
/// `logged`, kept once in `Checkpoints::logs`).
struct Mark {
    tick: u64,
    arm: Arm,
    ctrl: Box<dyn Controller>,
    tally: Tally,
    logged: Logged,
    monitor: safety::Monitor,
}

impl Checkpoints {
    /// How many of the run's rows decide where a later run resumes from
    /// these: a first changed row at or past this count leaves every mark
    /// usable, as the count itself does. A caller that keeps a run's rows
    /// to compare the next rows with keeps these and no more.
    pub fn rows_that_matter(&self) -> usize {
        self.marks.last().map_or(0, |m| {
            rows_read_before(m, &self.of).ceil().max(0.0) as usize
        })
    }

    /// The marks before which no tick read row `first_changed` or later
    /// (each tick reads the rows from one before to two after its own:
    /// `reference::curve`), for a run `of` the same models, options,
    /// faults, stations and row period (none otherwise); the last of them
    /// is where the run resumes.
    fn usable(mut self, first_changed: usize, of: &RunKey) -> (Vec<Mark>, Logs) {
        if self.of != *of {
            return (vec![], Logs::default());
        }
        self.marks
            .retain(|m| rows_read_before(m, of) <= first_changed as f64);
        (self.marks, self.logs)
    }
}

/// The row no tick before mark `m` of a run `of` read, nor any after it
/// (each tick reads the rows from one before to two after its own).
fn rows_read_before(m: &Mark, of: &RunKey) -> f64 {
    m.tick as f64 * of.model.control.period_s / of.dt_job + 3.0
}

/// The run: prepare, then tick (measure, control, monitor, tally, advance)
/// until the job ends, the loop diverges or the stopped arm is at rest;
/// resumed from `resume` (the checkpoints of a run of the same models and
/// options, and the first row at which this job's rows differ from that
/// run's), keeping checkpoints of its own when `keep` (else none but those
/// it resumed from).
#[allow(clippy::too_many_arguments)]
pub(super) fn run_resumable(
    job: &Job,
    nominal: &SimModel,
    model: &SimModel,
    opts: &Options,
    faults: &[Fault],
    progress: &mut dyn FnMut(u64, u64),
    resume: Option<(Checkpoints, usize)>,
    keep: bool,
    mut gate: Option<&mut lockstep::Gate>,
) -> Result<(Outcome, Checkpoints), SimError> {
    let setup = prepare(job, nominal, model, opts, faults)?;
    let (s, period, ticks) = (setup.samples, setup.period, setup.ticks);
    let key = RunKey::of(&setup, job);
    let (mut marks, logs) = resume
        .map(|(c, row)| c.usable(row, &key))
        .unwrap_or_default();
    marks.retain(|m| m.tick < ticks);
    let every = ((CHECKPOINT_S / period).round() as u64).max(1);
    let coarse = every * ((COARSE_CHECKPOINT_S / CHECKPOINT_S).round() as u64).max(1);
    let (start, mut arm, mut ctrl, mut tally, mut monitor) = match marks.last() {
        Some(m) => (
            m.tick,
            m.arm.clone(),
            m.ctrl.boxed_clone(),
            m.tally.restored(m.logged, &logs),
            m.monitor.clone(),
        ),
        None => {
            let arm = Arm::at_rest(&setup);
            let m0 = setup.measure(
                &arm.state,
                0.0,
                setup.references(0.0).arm,
                &setup.active(0.0),
            );
            let ctrl = opts.controller.build(setup.nominal, &m0);
            (
                0,
                arm,
                ctrl,
                Tally::new(),
                safety::Monitor::new(model, faults),
            )
        }
    };
    for k in start..ticks {
        if keep && k % every == 0 && marks.last().is_none_or(|m| m.tick < k) {
            let (t, logged) = tally.checkpoint();
            marks.push(Mark {
                tick: k,
                arm: arm.clone(),
                ctrl: ctrl.boxed_clone(),
                tally: t,
                logged,
                monitor: monitor.clone(),
            });
            // further back, the coarse ones only
            marks.retain(|m| m.tick % coarse == 0 || m.tick + coarse > k);
        }
        // In step with the other runs of its group (`lockstep`): at each
        // checkpoint it waits for them, and ends once one has failed. The
        // checkpoint a run resumes at is one of them: resumed past a
        // failure of the group (a set kept from a round its description
        // failed), it ends there as a whole run in step would.
        if k > 0 && k % every == 0 {
            if let Some(g) = gate.as_deref_mut() {
                if !g.go_on(k as f64 * period) {
                    break;
                }
            }
        }
        let t = k as f64 * period;
        let row = setup.row(t);
        let refs = setup.references(t);
        let active = setup.active(t);
        let meas = setup.measure(&arm.state, t, refs.arm, &active);
        let cmd = ctrl.step(&meas);
        let station = s.station[row];
        let station_pose = &setup.poses[station as usize];
        let (nozzle, deflection) = arm.nozzle(&setup);
        let des = refs.arm.nozzle[0];
        let error = [nozzle[0] - des[0], nozzle[1] - des[1]];
        let des_road = station_pose.to_road(des);
        let place = Place {
            t_s: t,
            stroke: s.stroke[row],
            station,
            x_m: des_road[0],
            y_m: des_road[1],
        };
        // the safety monitor: the nozzle off its path by the encoders
        monitor.note_faults(t, period, &place);
        let w_meas = nozzle_base(model, meas.base_rot_rad, meas.extension_m);
        let w_ref = nozzle_base(model, refs.arm.base_rot[0], refs.arm.extension[0]);
        let follow = (w_meas[0] - w_ref[0]).hypot(w_meas[1] - w_ref[1]);
        let before_stop = !monitor.stopped();
        let estop = monitor.check(model, &meas, follow, &place);
        let painting = s.paint[row] != 0;
        let gun = monitor.gun_open(painting, follow, opts.tolerance_m);
        let err = error[0].hypot(error[1]);
        monitor.nozzle(t, station_pose.to_road(nozzle), err, gun, opts.tolerance_m);
        let cmd = if estop { Command::default() } else { cmd };
        tally.observe(
            &setup,
            &Tick {
                row,
                place,
                // the job's painting ends where the arm was stopped
                painting: painting && before_stop,
                before_stop,
                refs: &refs,
                arm: &arm,
                cmd,
                nozzle,
                deflection,
                error,
            },
        );
        if k + 1 == ticks {
            break;
        }
        let painted = painting && before_stop;
        if painted && opts.stop_over_m.is_some_and(|b| err > b) {
            tally.cut_short_at_s = Some(t);
            break;
        }
        let inputs = Inputs {
            u_motor: cmd.u_motor,
            u_cyl: cmd.u_cyl,
            estop,
            faults: active,
        };
        let lim = arm.advance(&setup, &inputs, &refs);
        tally.servo_limited(lim, period);
        if arm.state.iter().any(|v| !v.is_finite()) {
            // an unstable loop: a failed run, judged on what it did so far
            tally.diverged = Some(t);
            break;
        }
        if k % 2000 == 0 {
            progress(k, ticks);
        }
        if monitor.done(t) {
            break;
        }
    }
    if let Some(g) = gate {
        if let Some(t) = tally.cut_short_at_s {
            g.failed(t);
        }
        g.leave();
    }
    progress(ticks, ticks);
    // The marks resumed from and taken here all lie before the run's end:
    // its logs hold each one's as a prefix.
    let kept = Checkpoints {
        of: key,
        logs: if marks.is_empty() {
            Logs::default()
        } else {
            tally.logs()
        },
        marks,
    };
    Ok((tally.report(&setup, monitor.finish()), kept))
}

#[cfg(test)]
mod tests {
    use crate::{simulate, simulate_resumable, synthetic, Options, SimModel};

    /// `letter_job` with its base rotation bumped by `bump` rad over 40
    /// rows from `at` (a share of its rows) on.
    fn bumped(at: f64, bump: f64) -> (basr_job::Job, usize) {
        let mut j = synthetic::letter_job();
        let n = j.samples.len();
        let r = (at * n as f64) as usize;
        for v in &mut j.samples.base_rot_rad[r..(r + 40).min(n)] {
            *v += bump;
        }
        (j, r)
    }

    #[test]
    fn a_resumed_run_reports_what_a_whole_run_does() {
        let model = SimModel::basr();
        let opts = Options::default();
        let (first, _) = bumped(0.0, 0.0);
        let (_, kept) = simulate_resumable(&first, &model, &opts, None).unwrap();
        assert!(kept.marks.len() > 3, "{} checkpoints", kept.marks.len());
        let (second, row) = bumped(0.7, 0.004);
        let whole = simulate(&second, &model, &opts, &mut |_, _| {}).unwrap();
        let unbumped = simulate(&first, &model, &opts, &mut |_, _| {}).unwrap();
        assert_ne!(
            whole.report, unbumped.report,
            "the bump shows in the report"
        );
        let key = kept.of.clone();
        let (usable, _) = kept.usable(row, &key);
        assert!(!usable.is_empty(), "a checkpoint before row {row}");
        let (_, kept) = simulate_resumable(&first, &model, &opts, None).unwrap();
        let (resumed, again) =
            simulate_resumable(&second, &model, &opts, Some((kept, row))).unwrap();
        assert_eq!(resumed.report, whole.report);
        // Its own checkpoints resume a third run as well.
        let (third, row3) = bumped(0.85, -0.003);
        let whole3 = simulate(&third, &model, &opts, &mut |_, _| {}).unwrap();
        let (resumed3, _) =
            simulate_resumable(&third, &model, &opts, Some((again, row3.min(row)))).unwrap();
        assert_eq!(resumed3.report, whole3.report);
    }

    /// A run keeps a checkpoint every second over its last five seconds,
    /// where a re-timed join before its failure changes its rows, and one
    /// every five seconds further back.
    #[test]
    fn checkpoints_are_fine_near_the_run_s_end_and_coarse_behind() {
        use super::{CHECKPOINT_S, COARSE_CHECKPOINT_S};
        let model = SimModel::basr();
        let (job, _) = bumped(0.0, 0.0);
        let (_, kept) = simulate_resumable(&job, &model, &Options::default(), None).unwrap();
        let period = model.control.period_s;
        let [fine, coarse] =
            [CHECKPOINT_S, COARSE_CHECKPOINT_S].map(|s| (s / period).round() as u64);
        let ticks: Vec<u64> = kept.marks.iter().map(|m| m.tick).collect();
        let last = *ticks.last().expect("checkpoints");
        assert!(last > 3 * coarse, "a run of {last} ticks");
        let (behind, near): (Vec<u64>, Vec<u64>) = ticks.iter().partition(|&&t| t + coarse <= last);
        let want_behind: Vec<u64> = (0..)
            .map(|i| i * coarse)
            .take_while(|&t| t + coarse <= last)
            .collect();
        assert_eq!(behind, want_behind, "every {coarse} ticks further back");
        let want_near: Vec<u64> = (0..=last / fine)
            .map(|i| i * fine)
            .filter(|&t| t + coarse > last)
            .collect();
        assert_eq!(near, want_near, "every {fine} ticks over the last {coarse}");
    }

    /// A run reads row i at i × the control period, never the row's clock:
    /// the same rows with their clock moved (as a station's are when a
    /// station before it is re-timed) compare equal to the end
    /// (`Samples::first_difference`), and a run resumed from the first
    /// run's last checkpoint reports what a whole run of them does.
    #[test]
    fn a_station_whose_clock_moved_resumes_from_its_last_checkpoint() {
        let model = SimModel::basr();
        let opts = Options::default();
        let (first, _) = bumped(0.3, 0.004);
        let mut moved = first.clone();
        for t in &mut moved.samples.t_s {
            *t += 137.25;
        }
        let n = first.samples.len();
        assert_eq!(moved.samples.first_difference(&first.samples), n);
        // a change in any other column is still found
        let mut other = moved.clone();
        other.samples.x_m[n / 2] += 1e-9;
        assert_eq!(other.samples.first_difference(&first.samples), n / 2);
        let whole = simulate(&moved, &model, &opts, &mut |_, _| {}).unwrap();
        let (_, kept) = simulate_resumable(&first, &model, &opts, None).unwrap();
        let last = kept.marks.last().expect("checkpoints").tick;
        assert!(last > 0);
        let (resumed, _) = simulate_resumable(&moved, &model, &opts, Some((kept, n))).unwrap();
        assert_eq!(resumed.report, whole.report);
    }

    /// A run's rows kept only as far as `rows_that_matter` find the same
    /// resume as the whole rows: for a change before that count and one
    /// past it, on a run cut short early (as compile's failed runs are).
    #[test]
    fn the_rows_that_matter_resume_as_all_the_rows_do() {
        let model = SimModel::basr();
        let (first, _) = bumped(0.0, 0.0);
        let n = first.samples.len();
        // Cut short where its error first nears its whole run's largest.
        let whole = simulate(&first, &model, &Options::default(), &mut |_, _| {}).unwrap();
        assert!(whole.report.max_error_m > 0.0);
        let opts = Options {
            stop_over_m: Some(whole.report.max_error_m * 0.999),
            ..Options::default()
        };
        let run = || simulate_resumable(&first, &model, &opts, None).unwrap().1;
        let keep = run().rows_that_matter();
        assert!(keep > 0 && keep < n, "{keep} of {n} rows");
        let kept_rows = first.samples.rows(0..keep);
        for at in [0.1, 0.95] {
            let (second, _) = bumped(at, 0.004);
            let all = second.samples.first_difference(&first.samples);
            let short = second.samples.first_difference(&kept_rows);
            assert_eq!(short, all.min(keep), "change at {at}");
            let (a, _) = simulate_resumable(&second, &model, &opts, Some((run(), all))).unwrap();
            let (b, _) = simulate_resumable(&second, &model, &opts, Some((run(), short))).unwrap();
            assert_eq!(a.report, b.report, "change at {at}");
        }
    }

    #[test]
    fn checkpoints_of_another_run_are_not_used() {
        let model = SimModel::basr();
        let opts = Options::default();
        let (first, _) = bumped(0.0, 0.0);
        let (_, kept) = simulate_resumable(&first, &model, &opts, None).unwrap();
        let n = first.samples.len();
        let mut other = kept.of.clone();
        other.dt_job *= 2.0;
        let (_, kept) = simulate_resumable(&first, &model, &opts, None).unwrap();
        assert!(kept.usable(n, &other).0.is_empty(), "another row period");
        let (_, kept) = simulate_resumable(&first, &model, &opts, None).unwrap();
        let mut other = kept.of.clone();
        other.controller = crate::ControllerKind::Pid;
        assert!(kept.usable(n, &other).0.is_empty(), "another controller");
        let (_, kept) = simulate_resumable(&first, &model, &opts, None).unwrap();
        let mut other = kept.of.clone();
        other.stations[0].x_m += 0.01;
        assert!(kept.usable(n, &other).0.is_empty(), "another stop");
        let (_, kept) = simulate_resumable(&first, &model, &opts, None).unwrap();
        let same = kept.of.clone();
        assert!(!kept.usable(n, &same).0.is_empty(), "the same run");
    }

    #[test]
    fn a_run_asked_to_stop_over_a_bound_stops_at_its_first_failure_only() {
        let model = SimModel::basr();
        let whole_opts = Options::default();
        let bound = 0.75 * whole_opts.tolerance_m;
        let opts = Options {
            stop_over_m: Some(bound),
            ..Options::default()
        };
        // A job the arm follows runs to its end: the same report.
        let good = synthetic::letter_job();
        let whole = simulate(&good, &model, &whole_opts, &mut |_, _| {}).unwrap();
        assert!(
            whole.report.max_error_m < bound,
            "{}",
            whole.report.max_error_m
        );
        let bounded = simulate(&good, &model, &opts, &mut |_, _| {}).unwrap();
        assert_eq!(bounded.report, whole.report);
        // A job it cannot follow ends where the error first passes it.
        let bad = synthetic::step_job();
        let whole = simulate(&bad, &model, &whole_opts, &mut |_, _| {}).unwrap();
        let cut = simulate(&bad, &model, &opts, &mut |_, _| {}).unwrap();
        let at = cut.report.cut_short_at_s.expect("cut short");
        assert!(cut.report.max_error_m > bound);
        assert!(cut.report.max_error_m <= whole.report.max_error_m);
        assert!(
            (cut.report.worst.t_s - at).abs() < 1e-9,
            "{} {at}",
            cut.report.worst.t_s
        );
        assert!(at < whole.report.duration_s);
        assert_eq!(whole.report.cut_short_at_s, None);
    }

    /// A run that does not log its waviness (compile's verification) is
    /// the same run: its report differs only in the waviness, which reads
    /// zero.
    #[test]
    fn a_run_without_the_waviness_log_is_the_same_run() {
        let model = SimModel::basr();
        let job = synthetic::letter_job();
        let with = simulate(&job, &model, &Options::default(), &mut |_, _| {}).unwrap();
        let opts = Options {
            waviness: false,
            ..Options::default()
        };
        let without = simulate(&job, &model, &opts, &mut |_, _| {}).unwrap();
        assert!(with.report.waviness.max_m > 0.0);
        assert_eq!(without.report.waviness.max_m, 0.0);
        let mut same = without.report.clone();
        same.waviness = with.report.waviness.clone();
        assert_eq!(same, with.report);
    }
}
