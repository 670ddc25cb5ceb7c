//! The controller program of 000 section III: PID, SJCT + PID (the best on
//! the real robot), dynamic inversion + PID, and SCCT (section II §5), each a
//! value with its own state and `step(&Measurement) -> Command`, run every
//! 5 ms. Torque/force demands go to the valves through the Sohl–Bobrow
//! nonlinear pressure law (000 eq. 26–31).
//!
//! Two additions to the seed's code, both documented where they are used:
//! joint rates and accelerations come from a fading-memory polynomial filter
//! (the seed's raw second difference of an 88 000-count encoder is
//! 2.9 rad/s² of noise at 5 ms, more than the motor's torque can follow at
//! full reach), and the extension PID gets a flow feed-forward from the
//! planned speed (the job gives it; the seed's hand-driven moves did not).

use super::model::{Actuator, SimModel};
use super::plant::{mass_matrix, volumes};

/// The trajectory generator's output at one tick: desired joint positions,
/// rates and accelerations, and the desired nozzle point in the base frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Reference {
    /// θ1, θ̇1, θ̈1 (rad, rad/s, rad/s²).
    pub base_rot: [f64; 3],
    /// R, Ṙ, R̈ (m, m/s, m/s²).
    pub extension: [f64; 3],
    /// Nozzle (x, y) in the base frame, its velocity and acceleration.
    pub nozzle: [[f64; 2]; 3],
}

/// What the controller reads at one tick (000 section III `readValues`):
/// quantised encoders, transducer pressures, and the reference.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Measurement {
    pub t_s: f64,
    /// θ1 from the base encoder (rad).
    pub base_rot_rad: f64,
    /// R from the extension encoder (m).
    pub extension_m: f64,
    /// Motor chamber pressures A, B (Pa).
    pub motor_pa: [f64; 2],
    /// Cylinder chamber pressures A, B (Pa).
    pub cylinder_pa: [f64; 2],
    /// Supply pressure at the valves' manifold (Pa): the low-pressure switch.
    pub supply_pa: f64,
    pub reference: Reference,
}

/// Valve commands (000 section III `writeDA`), already limited.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Command {
    pub u_motor: f64,
    pub u_cyl: f64,
}

/// A discrete-time controller.
pub trait Controller: Send {
    /// One sampling period: read, compute, write.
    fn step(&mut self, m: &Measurement) -> Command;
    /// A copy with the same state (a resumable run keeps one per
    /// checkpoint).
    fn boxed_clone(&self) -> Box<dyn Controller>;
}

/// Which controller (`--controller`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ControllerKind {
    /// PID on both joints (000 section III `/pid`): stable, less accurate.
    Pid,
    /// SJCT on θ1 with the Sohl–Bobrow law, PID on extension (`/sjct`).
    Sjct,
    /// Cartesian SCCT on both joints (section II §5; `/scct`: unstable as is).
    Scct,
    /// Dynamic inversion on θ1, PID on extension (`/dynInv`).
    Dyninv,
}

impl ControllerKind {
    pub const ALL: [ControllerKind; 4] = [
        ControllerKind::Pid,
        ControllerKind::Sjct,
        ControllerKind::Scct,
        ControllerKind::Dyninv,
    ];

    pub fn name(self) -> &'static str {
        match self {
            ControllerKind::Pid => "pid",
            ControllerKind::Sjct => "sjct",
            ControllerKind::Scct => "scct",
            ControllerKind::Dyninv => "dyninv",
        }
    }

    /// Build the controller for `model`, starting at rest at `m0`.
    pub fn build(self, model: &SimModel, m0: &Measurement) -> Box<dyn Controller> {
        match self {
            ControllerKind::Pid => Box::new(PidPid::new(model, m0)),
            ControllerKind::Sjct => Box::new(SjctPid::new(model, m0)),
            ControllerKind::Scct => Box::new(Scct::new(model, m0)),
            ControllerKind::Dyninv => Box::new(DynInvPid::new(model, m0)),
        }
    }
}

/// A controller name that is not one of [`ControllerKind::ALL`].
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown controller {0:?}: use pid, sjct, scct or dyninv")]
pub struct UnknownController(pub String);

impl std::str::FromStr for ControllerKind {
    type Err = UnknownController;
    fn from_str(s: &str) -> Result<Self, UnknownController> {
        ControllerKind::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| UnknownController(s.to_string()))
    }
}

/// Gains, tuned on the default robot with the synthetic jobs of the tests
/// and STOP (see README "Simulate").
pub mod gains {
    /// Fading-memory factor θ of the rate/acceleration filter: bandwidth
    /// ≈ (1 − θ)/T ≈ 6 Hz, acceleration noise ≈ 0.02 rad/s².
    pub const FILTER_THETA: f64 = 0.8;
    /// Extension PID (per metre of R error → valve command), as the seed's
    /// velocity form: proportional, integral per second, derivative·s.
    /// Lowered from 8 and 16 with the hoses and boom modes of the plant
    /// (issue 12): at full reach the stiffer loop rang the 12 Hz link and
    /// 9 Hz linkage modes (STOP at 3.6 m letters: 7.8 → 4.8 mm; STOP 3.1 mm).
    pub const EXT_KP: f64 = 4.0;
    pub const EXT_KI: f64 = 8.0;
    pub const EXT_KD: f64 = 0.0;
    /// Learning rate of the extension's flow feed-forward scale (per metre
    /// of R error per m/s of planned R rate, per second). The feed-forward
    /// trusts the description's valve gain and supply pressure; a plant
    /// 10 % off either (`--plants`) lags every fast move by the loop's
    /// 10 %·Ṙ/K_v, 7 mm at the stroke starts after air moves. Learning the
    /// scale from the error correlated with the planned rate (a gradient
    /// step, as in model-reference adaptive control) takes STOP's 40-plant
    /// p95 (±10 %, seed 7) from 8.5 to 4.9 mm; 20 left 5.9 mm, 400 rang (6.3).
    pub const FF_LEARN: f64 = 100.0;
    /// The scale stays within what a worn or mis-set valve can be.
    /// assumed: −30 %…+50 % of the description's.
    pub const FF_SCALE_MIN: f64 = 0.7;
    pub const FF_SCALE_MAX: f64 = 1.5;
    /// Dynamic pressure feedback on the cylinder (valve command per newton of
    /// high-passed load force): the hydraulic resonance of the arm's mass on
    /// the oil column is almost undamped (valve without leakage, 000 eq.
    /// 15–16), so position feedback alone cannot be stiff; feeding back the
    /// *change* of the measured force adds the damping an underlapped valve
    /// would. The high-pass leaves the static holding force alone. Raised
    /// from 4e-6 to 1e-5 on the compiled "SO" job, where the cylinder's
    /// 10 Hz resonance rang the 9 Hz end-effector linkage up to 8.7 mm.
    pub const EXT_KPF: f64 = 1.0e-5;
    /// Time constant of that high-pass (s).
    pub const PF_TAU: f64 = 0.1;
    /// θ1 PID (valve command per rad; integral per second; derivative·s),
    /// the `/pid` controller, on top of the flow feed-forward (`PidPid`).
    /// The arm's inertia on the motor's oil column resonates at 0.4–1.5 Hz,
    /// damped only by the counterbalance valves' bleed, so the position loop
    /// must stay far below it: Kp 0.2 with Kd ≤ 0.1 grows without bound on
    /// STOP, Kd 1.6 at full reach. The seed gives no gains for `/pid`.
    /// Changed from 0.02 / 0.02 / 0 (issue 12): those left the arm on its
    /// feed-forward alone (a 4 s time constant), and what that model misses
    /// (a 2 % pressure shortfall after each reversal of the air moves'
    /// torque) grew to 25 mm and tripped the safety monitor 0.7 s into STOP.
    /// The derivative (velocity) term is what holds the arm on the planned
    /// speed; a grid of Kp 0.02–0.8, Ki 0.02–0.1, Kd 0–1.6 on STOP, SCHOOL
    /// and STOP at full reach (`--letter-height 3.6`) gave 7–11 mm max for
    /// Kd 0.3–0.4 and Kp 0.05–0.1, a flat region (with the friction and
    /// Coriolis terms fed forward since: 5.6–7.5 mm); Kp 0.4 still stays
    /// bounded at Kd ≥ 0.2 (4× margin), Kd 1.6 does not (5×). Pressure
    /// feedback (static or high-passed, 0.003–0.1 per MPa) made every point
    /// worse: it turns the valve into a torque source the position PID
    /// cannot hold.
    pub const ROT_PID_KP: f64 = 0.1;
    pub const ROT_PID_KI: f64 = 0.02;
    pub const ROT_PID_KD: f64 = 0.3;
    /// Acceleration law of SJCT and dynamic inversion:
    /// θ̈_cmd = θ̈_d + KV·ė + KP·e + KI·∫e, a 2.5 Hz critically damped loop
    /// (raised from 2 Hz on STOP: 6.52 → 6.41 mm).
    pub const ACC_KP: f64 = 250.0;
    pub const ACC_KV: f64 = 32.0;
    pub const ACC_KI: f64 = 100.0;
    /// SJCT inertia estimate Ā = m·R (seed `A1 = m*q2_a`), kg·m. Stable
    /// while 0 < Ā/A11 < 2 over the whole reach (1.5 retracted, 0.5 at full
    /// reach). 150 left STOP at 6.41 mm; 250 gave 5.69 mm before the plant
    /// had hoses and boom modes; with them 250 saturates the motor valve for
    /// 14 s at full reach, 180 (with k_F 45) gives STOP 3.1 mm, 4.8 mm at
    /// full reach.
    pub const SJCT_M: f64 = 180.0;
    /// Low-pass of the time-delay estimate (Hz): quantisation noise of the
    /// encoder's second difference drops to ≈0.01 rad/s² (20 Hz tripled
    /// the STOP error).
    pub const TDE_LP_HZ: f64 = 10.0;
    /// Sohl–Bobrow force-error gain k_F (1/s); 60 before the hoses made the
    /// pressure loop see their 180 Hz line mode (30–120 tried; 45 best).
    pub const KF: f64 = 45.0;
    /// SCCT Cartesian gains (section II eq. 24): 2 Hz critically damped was
    /// 46 mm on STOP; 1.6 Hz (100, 20) 15 mm. Higher (130–250) saturated
    /// the motor valve on the delay estimate's noise.
    pub const SCCT_KP: f64 = 100.0;
    pub const SCCT_KD: f64 = 20.0;
    /// Where in the stroke SCCT's constant base inertia Ā11 is taken (0 =
    /// retracted, 1 = full reach). Changed from mid reach (0.5): the delay
    /// estimate's noise, Ā·q̈ of a quantised encoder, saturated the motor
    /// valve for 6 s on STOP; at 0.35 (R ≈ 2.9 m) it is 0.7 s (0.2 loses
    /// the base's tracking: 13.7 mm; 0.4: SCHOOL 5.2, full reach 13 mm).
    pub const SCCT_A11_STROKE: f64 = 0.35;
    /// Share of the planned extension rate in the flow term ẋ·M of the
    /// cylinder's pressure law (000 eq. 29 has the measured ẋ only, 0).
    /// Changed: with the measured rate alone the extension overshot every
    /// reversal of an air move by 13 mm (the force loop answers the oil's
    /// compression a tick late); half the planned rate feeds the flow
    /// forward as the extension PID of SJCT does: STOP 14.1 → 4.8 mm
    /// (0.3: 8.5 mm, 0.7: 6.6 mm, 1: 8.3 mm).
    pub const SCCT_PLANNED_RATE: f64 = 0.5;
}

/// Fading-memory (discounted least squares) second-order polynomial filter:
/// position, rate and acceleration from quantised samples.
#[derive(Clone, Debug)]
pub struct RateFilter {
    q: f64,
    v: f64,
    a: f64,
    alpha: f64,
    beta: f64,
    gamma: f64,
    t: f64,
}

impl RateFilter {
    pub fn new(q0: f64, theta: f64, period: f64) -> RateFilter {
        let o = 1.0 - theta;
        RateFilter {
            q: q0,
            v: 0.0,
            a: 0.0,
            alpha: 1.0 - theta * theta * theta,
            beta: 1.5 * (1.0 - theta * theta) * o,
            gamma: 0.5 * o * o * o,
            t: period,
        }
    }

    /// Take one sample; returns (q, q̇, q̈).
    pub fn update(&mut self, meas: f64) -> (f64, f64, f64) {
        let t = self.t;
        let qp = self.q + self.v * t + 0.5 * self.a * t * t;
        let vp = self.v + self.a * t;
        let r = meas - qp;
        self.q = qp + self.alpha * r;
        self.v = vp + self.beta * r / t;
        self.a += 2.0 * self.gamma * r / (t * t);
        (self.q, self.v, self.a)
    }
}

/// Incremental PID (seed form `ys += kP·Δe + kI·e + kD·Δ²e`) with the
/// command itself as the state, so clamping it is the anti-windup.
#[derive(Clone, Debug)]
struct IncrementalPid {
    kp: f64,
    ki_t: f64,
    kd_t: f64,
    e1: f64,
    e2: f64,
    u: f64,
    limit: f64,
}

impl IncrementalPid {
    fn new(kp: f64, ki: f64, kd: f64, period: f64, limit: f64) -> IncrementalPid {
        IncrementalPid {
            kp,
            ki_t: ki * period,
            kd_t: kd / period,
            e1: 0.0,
            e2: 0.0,
            u: 0.0,
            limit,
        }
    }
    fn step(&mut self, e: f64) -> f64 {
        self.u +=
            self.kp * (e - self.e1) + self.ki_t * e + self.kd_t * (e - 2.0 * self.e1 + self.e2);
        self.u = self.u.clamp(-self.limit, self.limit);
        self.e2 = self.e1;
        self.e1 = e;
        self.u
    }
}

/// Valve command that makes the actuator move at `vel` given the measured
/// chamber pressures (inverse of eq. 15–16 for the inflow side).
fn flow_feedforward(model: &SimModel, act: &Actuator, vel: f64, pa: f64, pb: f64) -> f64 {
    let h = &model.hydraulics;
    // extending fills A from supply; retracting fills B from supply
    let (area, dp) = if vel >= 0.0 {
        (act.area, h.supply_pa - pa)
    } else {
        (act.alpha * act.area, h.supply_pa - pb)
    };
    area * vel / (act.valve_gain * dp.max(1.0e5).sqrt())
}

/// Sohl–Bobrow nonlinear pressure law (000 eq. 27–29; seed code for the
/// motor): valve command that drives the fluid force `f` towards `f_d`.
/// `pos` is the actuator position from the volume origin, `vel` its rate.
/// The controller's model uses a constant E (the seed's 6.1782 = E·D²).
#[allow(clippy::too_many_arguments)]
pub fn sohl_bobrow(
    model: &SimModel,
    act: &Actuator,
    pos: f64,
    vel: f64,
    pa: f64,
    pb: f64,
    f_d: f64,
    f_d_dot: f64,
) -> f64 {
    let h = &model.hydraulics;
    let e = h.bulk_modulus_pa;
    let (va, vb) = volumes(act, pos);
    let (a, al) = (act.area, act.alpha);
    let f = a * (pa - al * pb);
    let m = e * a * a * (1.0 / va + al * al / vb);
    let num = f_d_dot - gains::KF * (f - f_d) + vel * m;
    let root = |p: f64| p.max(0.0).sqrt();
    let z = if num >= 0.0 {
        e * a * act.valve_gain * (root(h.supply_pa - pa) / va + al * root(pb - h.tank_pa) / vb)
    } else {
        e * a * act.valve_gain * (root(pa - h.tank_pa) / va + al * root(h.supply_pa - pb) / vb)
    };
    if z <= 0.0 {
        return 0.0;
    }
    (num / z).clamp(-act.command_limit, act.command_limit)
}

/// Measurements turned into joint estimates shared by all controllers.
#[derive(Clone, Debug)]
struct Estimates {
    th: RateFilter,
    r: RateFilter,
}

impl Estimates {
    fn new(model: &SimModel, m0: &Measurement) -> Estimates {
        let t = model.control.period_s;
        Estimates {
            th: RateFilter::new(m0.base_rot_rad, gains::FILTER_THETA, t),
            r: RateFilter::new(m0.extension_m, gains::FILTER_THETA, t),
        }
    }
}

/// First-order high-pass of a measured force (for pressure feedback).
#[derive(Clone, Debug)]
struct HighPass {
    prev_in: f64,
    out: f64,
    a: f64,
}

impl HighPass {
    fn new(x0: f64, tau: f64, period: f64) -> HighPass {
        HighPass {
            prev_in: x0,
            out: 0.0,
            a: tau / (tau + period),
        }
    }
    fn step(&mut self, x: f64) -> f64 {
        self.out = self.a * (self.out + x - self.prev_in);
        self.prev_in = x;
        self.out
    }
}

/// The seed's extension loop: PID on the R error with flow feed-forward and
/// dynamic pressure feedback.
#[derive(Clone, Debug)]
struct ExtensionLoop {
    pid: IncrementalPid,
    force_hp: HighPass,
    /// Learned scale of the flow feed-forward (1 = the description's valve).
    ff_scale: f64,
    period: f64,
}

impl ExtensionLoop {
    fn new(model: &SimModel, m0: &Measurement) -> ExtensionLoop {
        ExtensionLoop {
            force_hp: HighPass::new(cyl_force(model, m0), gains::PF_TAU, model.control.period_s),
            pid: IncrementalPid::new(
                gains::EXT_KP,
                gains::EXT_KI,
                gains::EXT_KD,
                model.control.period_s,
                model.cylinder.command_limit,
            ),
            ff_scale: 1.0,
            period: model.control.period_s,
        }
    }
    fn step(&mut self, model: &SimModel, m: &Measurement) -> f64 {
        let e = m.reference.extension[0] - m.extension_m;
        let xd = m.reference.extension[1] / model.arm.k;
        let ff = flow_feedforward(
            model,
            &model.cylinder,
            xd,
            m.cylinder_pa[0],
            m.cylinder_pa[1],
        );
        let lim = model.cylinder.command_limit;
        // the feed-forward learns the valve it drives: its scale grows
        // while the arm lags the planned motion and shrinks while it leads
        self.ff_scale = (self.ff_scale
            + gains::FF_LEARN * e * m.reference.extension[1] * self.period)
            .clamp(gains::FF_SCALE_MIN, gains::FF_SCALE_MAX);
        let ff = self.ff_scale * ff;
        let damp = gains::EXT_KPF * self.force_hp.step(cyl_force(model, m));
        (self.pid.step(e) + ff - damp).clamp(-lim, lim)
    }
}

fn cyl_force(model: &SimModel, m: &Measurement) -> f64 {
    model.cylinder.area * (m.cylinder_pa[0] - model.cylinder.alpha * m.cylinder_pa[1])
}

fn motor_torque(model: &SimModel, m: &Measurement) -> f64 {
    model.motor.area * (m.motor_pa[0] - m.motor_pa[1])
}

/// True when the seed's safety test refuses to drive (θ1 outside the window).
fn outside_window(model: &SimModel, th: f64) -> bool {
    th < model.arm.theta_min_rad || th > model.arm.theta_max_rad
}

fn off(model: &SimModel) -> Command {
    Command {
        u_motor: model.motor.off_command,
        u_cyl: model.cylinder.off_command,
    }
}

/// `/pid`: PID on both joints, each with a feed-forward of the flow its
/// planned motion needs.
#[derive(Clone)]
pub struct PidPid {
    model: SimModel,
    est: Estimates,
    ext: ExtensionLoop,
    rot: IncrementalPid,
    /// Oil-column wind-up τ_d/K_h of the last tick (rad).
    windup_prev: Option<f64>,
}

impl PidPid {
    pub fn new(model: &SimModel, m0: &Measurement) -> PidPid {
        PidPid {
            model: model.clone(),
            est: Estimates::new(model, m0),
            ext: ExtensionLoop::new(model, m0),
            rot: IncrementalPid::new(
                gains::ROT_PID_KP,
                gains::ROT_PID_KI,
                gains::ROT_PID_KD,
                model.control.period_s,
                model.motor.command_limit,
            ),
            windup_prev: None,
        }
    }

    /// How far the motor's oil column must be compressed to give the
    /// torque `tau`, as an angle: τ/K_h with the column's stiffness
    /// K_h = D²·(1/C_A + 1/C_B), each side's compliance C = V/E'(p) plus its
    /// hose's V_l/E_l (000 eq. 13's modulus at the measured pressure). The
    /// seed's 6.1782·(1/vA + 1/vB) is the same with pure oil and no hoses; it
    /// over-states the stiffness by 45 % at half supply, and the arm ended
    /// every air move 20 mm off.
    fn windup(&self, m: &Measurement, tau: f64) -> f64 {
        let md = &self.model;
        let (h, c) = (&md.hydraulics, &md.circuit);
        let (va, vb) = volumes(&md.motor, m.base_rot_rad);
        let hose = c.line_volume_m3 / c.line_bulk_pa;
        let ca = va / h.bulk(m.motor_pa[0]) + hose;
        let cb = vb / h.bulk(m.motor_pa[1]) + hose;
        let d = md.motor.area;
        tau / (d * d * (1.0 / ca + 1.0 / cb))
    }
}

impl Controller for PidPid {
    fn boxed_clone(&self) -> Box<dyn Controller> {
        Box::new(self.clone())
    }

    fn step(&mut self, m: &Measurement) -> Command {
        self.est.th.update(m.base_rot_rad);
        self.est.r.update(m.extension_m);
        let md = &self.model;
        if outside_window(md, m.base_rot_rad) {
            return off(md);
        }
        let e = m.reference.base_rot[0] - m.base_rot_rad;
        // The feed-forward flow moves the motor at the planned speed,
        // compresses its oil column as the planned torque needs (a flow for
        // speed alone leaves the arm behind by τ/K_h, 0.036 rad or 180 mm at
        // full reach at 0.3 rad/s², for the slow loop to recover) and makes
        // up what the counterbalance valves' bleed and the seals pass at that
        // torque (a third of the flow while accelerating at full reach; left
        // out, the arm ended air moves up to 150 mm off).
        // The torque: inertia, the Coriolis term of an extending arm (the
        // C(q, q̇)·q̇ of 000 eq. 8, ∂A11/∂x·ẋ·θ̇: 2.4 MPa when an air move
        // swings at 0.3 rad/s while extending at 0.8 m/s, which left SLOW
        // 25 mm off) and friction.
        let [_, w_d, a_d] = m.reference.base_rot;
        let mm = mass_matrix(md, md.arm.x_of_r(m.extension_m));
        let x_rate = m.reference.extension[1] / md.arm.k;
        let tau = mm.a11 * a_d + mm.a11_dx * x_rate * w_d + md.motor.friction.force(w_d);
        let w = self.windup(m, tau);
        let wind_rate = self
            .windup_prev
            .map_or(0.0, |p| (w - p) / md.control.period_s);
        self.windup_prev = Some(w);
        let d = md.motor.area;
        let leak = (md.motor.leakage + md.circuit.cb_bleed) * tau / (d * d);
        let ff = flow_feedforward(
            md,
            &md.motor,
            w_d + wind_rate + leak,
            m.motor_pa[0],
            m.motor_pa[1],
        );
        let lim = md.motor.command_limit;
        Command {
            u_motor: (self.rot.step(e) + ff).clamp(-lim, lim),
            u_cyl: self.ext.step(md, m),
        }
    }
}

/// The acceleration command shared by SJCT and dynamic inversion.
#[derive(Clone, Debug, Default)]
struct AccelLaw {
    integral: f64,
}

impl AccelLaw {
    fn step(&mut self, reference: &[f64; 3], q: f64, qd: f64, period: f64) -> f64 {
        let e = reference[0] - q;
        self.integral += e * period;
        reference[2]
            + gains::ACC_KV * (reference[1] - qd)
            + gains::ACC_KP * e
            + gains::ACC_KI * self.integral
    }
}

fn lambda_steps(model: &SimModel) -> usize {
    ((model.control.lambda_s / model.control.period_s).round() as usize).max(1)
}

/// `/sjct`: Simplified Joint Computed Torque on θ1 (time-delay estimate of
/// everything but Ā·θ̈, Ā = m·R), torque to valve by Sohl–Bobrow; PID on R.
#[derive(Clone)]
pub struct SjctPid {
    model: SimModel,
    est: Estimates,
    ext: ExtensionLoop,
    acc: AccelLaw,
    tde: TimeDelayEstimate,
    tau_prev: f64,
}

impl SjctPid {
    pub fn new(model: &SimModel, m0: &Measurement) -> SjctPid {
        let tau0 = motor_torque(model, m0);
        SjctPid {
            model: model.clone(),
            est: Estimates::new(model, m0),
            ext: ExtensionLoop::new(model, m0),
            acc: AccelLaw::default(),
            tde: TimeDelayEstimate::new(model, m0.base_rot_rad, tau0),
            tau_prev: tau0,
        }
    }
}

impl Controller for SjctPid {
    fn boxed_clone(&self) -> Box<dyn Controller> {
        Box::new(self.clone())
    }

    fn step(&mut self, m: &Measurement) -> Command {
        let md = &self.model;
        let t = md.control.period_s;
        let (q, qd, _) = self.est.th.update(m.base_rot_rad);
        self.est.r.update(m.extension_m);
        let a_bar = gains::SJCT_M * m.extension_m;
        let eta = self.tde.step(m.base_rot_rad, motor_torque(md, m), a_bar);
        if outside_window(md, m.base_rot_rad) {
            return off(md);
        }
        let u = self.acc.step(&m.reference.base_rot, q, qd, t);
        // τ = Ā·u + η̂  (000 eq. 22)
        let tau_d = a_bar * u + eta;
        let tau_dot = (tau_d - self.tau_prev) / t;
        self.tau_prev = tau_d;
        let u_motor = sohl_bobrow(
            md,
            &md.motor,
            q,
            qd,
            m.motor_pa[0],
            m.motor_pa[1],
            tau_d,
            tau_dot,
        );
        Command {
            u_motor,
            u_cyl: self.ext.step(md, m),
        }
    }
}

/// Time-delay estimate of one joint's disturbance (000 eq. 21–23):
/// η̂(t) = τ(t−λ) − Ā·q̈(t−λ), with q̈(t−λ) the central difference of the
/// encoder around t−λ and τ(t−λ) the *measured* fluid torque at that instant
/// (the seed uses the desired torque, which equals it only when the pressure
/// loop is instantaneous; with k_F = 60/s it lags by more than λ, and the
/// mismatch destabilises the loop). A second-order low-pass (cut-off
/// `TDE_LP_HZ`) removes the encoder's quantisation noise from q̈.
#[derive(Clone, Debug)]
struct TimeDelayEstimate {
    q: Vec<f64>,
    tau: Vec<f64>,
    n: usize,
    period: f64,
    lp: [f64; 2],
    a: f64,
    primed: usize,
}

impl TimeDelayEstimate {
    fn new(model: &SimModel, q0: f64, tau0: f64) -> TimeDelayEstimate {
        let n = lambda_steps(model);
        let t = model.control.period_s;
        let w = std::f64::consts::TAU * gains::TDE_LP_HZ;
        TimeDelayEstimate {
            q: vec![q0; n + 2],
            tau: vec![tau0; n + 2],
            n,
            period: t,
            lp: [tau0, tau0],
            a: (w * t) / (1.0 + w * t),
            primed: 0,
        }
    }

    /// Push this tick's encoder and torque; return η̂ for inertia `a_bar`.
    fn step(&mut self, q: f64, tau: f64, a_bar: f64) -> f64 {
        self.q.rotate_right(1);
        self.q[0] = q;
        self.tau.rotate_right(1);
        self.tau[0] = tau;
        self.primed = (self.primed + 1).min(self.n + 2);
        let n = self.n;
        let t2 = self.period * self.period;
        // centred at k − n: samples k−n+1, k−n, k−n−1
        let qdd = if self.primed >= n + 2 {
            (self.q[n - 1] - 2.0 * self.q[n] + self.q[n + 1]) / t2
        } else {
            0.0
        };
        let raw = self.tau[n] - a_bar * qdd;
        self.lp[0] += self.a * (raw - self.lp[0]);
        self.lp[1] += self.a * (self.lp[0] - self.lp[1]);
        self.lp[1]
    }
}

/// `/dynInv`: θ1 torque from the full model inertia and Coriolis term
/// (no disturbance estimate), Sohl–Bobrow to the valve; PID on R.
#[derive(Clone)]
pub struct DynInvPid {
    /// The inertia the controller's model gives, identified at mid reach:
    /// (J there, R there).
    nominal: (f64, f64),
    model: SimModel,
    est: Estimates,
    ext: ExtensionLoop,
    acc: AccelLaw,
    tau_prev: f64,
}

impl DynInvPid {
    pub fn new(model: &SimModel, m0: &Measurement) -> DynInvPid {
        // What a real identification gives (000 §III's dynamic inversion uses
        // a model, the seed does not say which): swing tests at mid reach
        // measure J there, and the model scales it as a point mass at the
        // nozzle, J·(R/R_mid)². That is exact at mid reach and over-states J
        // towards full reach (the links' inertia grows slower than R², the
        // turntable's not at all), so the inversion's loop gain grows with
        // the reach until the oil column's resonance is no longer damped.
        let r_mid = model
            .arm
            .r_of_x(model.arm.x_min_m + 0.5 * model.arm.stroke_m);
        let j_mid = mass_matrix(model, model.arm.x_of_r(r_mid)).a11;
        DynInvPid {
            nominal: (j_mid, r_mid),
            model: model.clone(),
            est: Estimates::new(model, m0),
            ext: ExtensionLoop::new(model, m0),
            acc: AccelLaw::default(),
            tau_prev: model.motor.area * (m0.motor_pa[0] - m0.motor_pa[1]),
        }
    }
}

impl Controller for DynInvPid {
    fn boxed_clone(&self) -> Box<dyn Controller> {
        Box::new(self.clone())
    }

    fn step(&mut self, m: &Measurement) -> Command {
        let md = &self.model;
        let t = md.control.period_s;
        let (q, qd, _) = self.est.th.update(m.base_rot_rad);
        let (r, rd, _) = self.est.r.update(m.extension_m);
        if outside_window(md, m.base_rot_rad) {
            return off(md);
        }
        let u = self.acc.step(&m.reference.base_rot, q, qd, t);
        // the identified model (see `DynInvPid::nominal`): J(R) = J_mid·(R/R_mid)^n
        let (j_mid, r_mid) = self.nominal;
        let a11 = j_mid * (r / r_mid) * (r / r_mid);
        let a11_dr = 2.0 * a11 / r;
        let tau_d = a11 * u + a11_dr * rd * qd + md.motor.friction.force(m.reference.base_rot[1]);
        let tau_dot = (tau_d - self.tau_prev) / t;
        self.tau_prev = tau_d;
        let u_motor = sohl_bobrow(
            md,
            &md.motor,
            q,
            qd,
            m.motor_pa[0],
            m.motor_pa[1],
            tau_d,
            tau_dot,
        );
        Command {
            u_motor,
            u_cyl: self.ext.step(md, m),
        }
    }
}

/// SCCT (000 section II eq. 18–25): Cartesian PD on the nozzle point,
/// joint accelerations through J⁻¹, constant inertia Ā (the model's A at
/// a third of the stroke: "only the bounds of the inertia matrix"),
/// time-delay estimate of the rest, Sohl–Bobrow on both actuators.
#[derive(Clone)]
pub struct Scct {
    model: SimModel,
    est: Estimates,
    a_bar: [f64; 2],
    tde: [TimeDelayEstimate; 2],
    tau_prev: [f64; 2],
}

impl Scct {
    pub fn new(model: &SimModel, m0: &Measurement) -> Scct {
        // Ā: "only knowledge of the bounds of the inertia matrix" (000 §II
        // 5.1): the base's A at `SCCT_A11_STROKE`, the extension's at full
        // retraction (its A grows without bound as the pantograph opens).
        // The seed's code pairs Ā·q̈ with the *desired* τ of λ ago, which
        // diverged on every job (000 §III: "very unstable … should not be
        // used without changes"); changed as in SJCT to the measured
        // efforts, with the low-pass of the delay estimate.
        let lo = mass_matrix(model, model.arm.x_min_m);
        let base = mass_matrix(
            model,
            model.arm.x_min_m + gains::SCCT_A11_STROKE * model.arm.stroke_m,
        );
        let tau0 = [motor_torque(model, m0), cyl_force(model, m0)];
        let x0 = model.arm.x_of_r(m0.extension_m);
        Scct {
            model: model.clone(),
            est: Estimates::new(model, m0),
            a_bar: [base.a11, lo.a22],
            tde: [
                TimeDelayEstimate::new(model, m0.base_rot_rad, tau0[0]),
                TimeDelayEstimate::new(model, x0, tau0[1]),
            ],
            tau_prev: tau0,
        }
    }
}

impl Controller for Scct {
    fn boxed_clone(&self) -> Box<dyn Controller> {
        Box::new(self.clone())
    }

    fn step(&mut self, m: &Measurement) -> Command {
        let md = &self.model;
        let t = md.control.period_s;
        let (th, thd, thdd) = self.est.th.update(m.base_rot_rad);
        let (r, rd, rdd) = self.est.r.update(m.extension_m);
        if outside_window(md, m.base_rot_rad) {
            return off(md);
        }
        let k = md.arm.k;
        let a2 = md.arm.a2_m;
        let (s, c) = th.sin_cos();
        // W = R(c, s) + a2(s, −c); q = (θ1, x), R = R_min + k(x − x_min)
        let w = [r * c + a2 * s, r * s - a2 * c];
        let j = [[-r * s + a2 * c, k * c], [r * c + a2 * s, k * s]];
        let xd = rd / k;
        let wd = [j[0][0] * thd + j[0][1] * xd, j[1][0] * thd + j[1][1] * xd];
        // J̇q̇ = W_θθ·θ̇² + 2·W_θx·θ̇·ẋ
        let jdqd = [
            (-r * c - a2 * s) * thd * thd + 2.0 * (-k * s) * thd * xd,
            (-r * s + a2 * c) * thd * thd + 2.0 * (k * c) * thd * xd,
        ];
        let rf = &m.reference.nozzle;
        let (kp, kd) = (gains::SCCT_KP, gains::SCCT_KD);
        let nu = [
            rf[2][0] + kd * (rf[1][0] - wd[0]) + kp * (rf[0][0] - w[0]) - jdqd[0],
            rf[2][1] + kd * (rf[1][1] - wd[1]) + kp * (rf[0][1] - w[1]) - jdqd[1],
        ];
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        let u = if det.abs() > 1e-9 {
            [
                (j[1][1] * nu[0] - j[0][1] * nu[1]) / det,
                (-j[1][0] * nu[0] + j[0][0] * nu[1]) / det,
            ]
        } else {
            [0.0, 0.0]
        };
        // η̂ = τ(t−λ) − Ā·q̈(t−λ) (eq. 23) with the measured actuator
        // efforts, as SJCT (the seed's desired τ lags the pressure loop)
        let eta = [
            self.tde[0].step(m.base_rot_rad, motor_torque(md, m), self.a_bar[0]),
            self.tde[1].step(
                md.arm.x_of_r(m.extension_m),
                cyl_force(md, m),
                self.a_bar[1],
            ),
        ];
        let _ = (thdd, rdd);
        let tau = [self.a_bar[0] * u[0] + eta[0], self.a_bar[1] * u[1] + eta[1]];
        let tdot = [
            (tau[0] - self.tau_prev[0]) / t,
            (tau[1] - self.tau_prev[1]) / t,
        ];
        self.tau_prev = tau;
        let x = md.arm.x_of_r(r);
        Command {
            u_motor: sohl_bobrow(
                md,
                &md.motor,
                th,
                thd,
                m.motor_pa[0],
                m.motor_pa[1],
                tau[0],
                tdot[0],
            ),
            u_cyl: sohl_bobrow(
                md,
                &md.cylinder,
                x - md.arm.x_min_m,
                // the flow term ẋ·M of eq. 29 half from the planned rate
                xd + gains::SCCT_PLANNED_RATE * (m.reference.extension[1] / k - xd),
                m.cylinder_pa[0],
                m.cylinder_pa[1],
                tau[1],
                tdot[1],
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rate_filter_tracks_a_parabola_exactly() {
        let mut f = RateFilter::new(0.0, 0.8, 0.005);
        let mut out = (0.0, 0.0, 0.0);
        for i in 0..400 {
            let t = i as f64 * 0.005;
            out = f.update(0.5 * 2.0 * t * t + 0.3 * t);
        }
        let t = 399.0 * 0.005;
        assert!((out.0 - (t * t + 0.3 * t)).abs() < 1e-9);
        assert!((out.1 - (2.0 * t + 0.3)).abs() < 1e-6);
        assert!((out.2 - 2.0).abs() < 1e-4);
    }

    #[test]
    fn sohl_bobrow_sign_follows_force_error() {
        let m = SimModel::basr();
        let p = 0.5 * (m.hydraulics.supply_pa + m.hydraulics.tank_pa);
        let up = sohl_bobrow(&m, &m.motor, 1.5, 0.0, p, p, 100.0, 0.0);
        let dn = sohl_bobrow(&m, &m.motor, 1.5, 0.0, p, p, -100.0, 0.0);
        assert!(up > 0.0 && dn < 0.0);
        assert!(up <= m.motor.command_limit);
    }

    #[test]
    fn controller_names_round_trip() {
        for k in ControllerKind::ALL {
            assert_eq!(k.name().parse::<ControllerKind>().unwrap(), k);
        }
        assert!("lqr".parse::<ControllerKind>().is_err());
    }
}
