//! The plant: pantograph arm (000 eq. 1–8), hydraulic motor and cylinder
//! (eq. 9–14), servovalves (eq. 15–17), the end-effector linkage mode, and
//! what section I added to the hydraulics and section II left out (supply
//! accumulator and pump, supply check valves, counterbalance valves on the
//! motor's exhaust, the hoses between valves and actuators, one bending mode
//! per main link; `circuit.rs`), as one ODE integrated by fixed-step RK4.
//!
//! Generalised coordinates: θ1 (base rotation) and x, the pantograph's A–C
//! distance (the cylinder moves x; R = R_min + k·(x − x_min)). The kinetic
//! energy of the two main links (slender rods, 000 eq. 1–2), the end-effector
//! point mass and the base gives a diagonal mass matrix A(x); Lagrange's
//! equations (eq. 4) then read
//!   A11·θ̈ = τ1 − A11'·ẋ·θ̇
//!   A22·ẍ = τ2 − ½A22'·ẋ² + ½A11'·θ̇² + F(x)
//! with F(x) = B·x/√(4d² − x²) the gravity pull of App. A eq. 11.

use super::circuit::{series, Circuit};
use super::model::{Actuator, Hydraulics, SimModel};

/// Indices into the state vector.
pub const TH: usize = 0;
pub const THD: usize = 1;
pub const X: usize = 2;
pub const XD: usize = 3;
pub const PA1: usize = 4;
pub const PB1: usize = 5;
pub const PA2: usize = 6;
pub const PB2: usize = 7;
pub const Y1: usize = 8;
pub const Y2: usize = 9;
pub const DX: usize = 10;
pub const DXD: usize = 11;
pub const DY: usize = 12;
pub const DYD: usize = 13;
/// Supply pressure at the accumulator (Pa).
pub const PS: usize = 14;
/// Valve-side pressures of the four hoses: motor A, motor B, cylinder A, B.
pub const LP: usize = 15;
/// Flows in those hoses towards the actuator (m³/s).
pub const LQ: usize = 19;
/// Lateral bending of the two main links (m) and their rates.
pub const B1: usize = 23;
pub const B1D: usize = 24;
pub const B2: usize = 25;
pub const B2D: usize = 26;
/// Number of state variables.
pub const N: usize = 27;

/// The continuous state of arm, hydraulics, valves and linkage mode.
/// (Base frame; δ is the nozzle's deflection from the linkage mode.)
pub type State = [f64; N];

/// Valve commands held over one control period (zero-order hold).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Inputs {
    /// Hydraulic-motor servovalve command.
    pub u_motor: f64,
    /// Extension-cylinder servovalve command.
    pub u_cyl: f64,
    /// The safety monitor's stop: the supply dump valve unloads the valves'
    /// supply to tank (the counterbalance valves, their pilot lost, brake
    /// the motor) and the extension's enable valve (000 §III: open only
    /// while powered) blocks both cylinder ports.
    pub estop: bool,
    /// Injected faults (`--fault`) acting on the plant.
    pub faults: super::fault::Active,
}

/// Mass-matrix diagonal and its x-derivatives at A–C distance `x`.
#[derive(Clone, Copy, Debug)]
pub struct MassMatrix {
    pub a11: f64,
    pub a11_dx: f64,
    pub a22: f64,
    pub a22_dx: f64,
}

/// A(x) of the arm (see module docs).
pub fn mass_matrix(m: &SimModel, x: f64) -> MassMatrix {
    mass_matrix_of(&ArmConsts::of(m), x)
}

/// The arm's and the linkage's numbers that do not change during a run,
/// each computed as [`mass_matrix`] and the derivative always computed it
/// (the same operations in the same order, so the same bits), once per
/// RK4 step rather than once per stage (issue 28: `--plants 100` time).
#[derive(Clone, Copy, Debug)]
pub struct ArmConsts {
    k: f64,
    me: f64,
    e: f64,
    il: f64,
    d2: f64,
    two_d2: f64,
    four_d2: f64,
    /// (10/16)·m·k², (20/16)·m·k², 2·m_e·k, c = m·k²/16, 2c, 9c, m_e·k², 2·I_l.
    c10: f64,
    c20: f64,
    two_me_k: f64,
    c: f64,
    two_c: f64,
    nine_c: f64,
    me_kk: f64,
    two_il: f64,
    ee_inertia: f64,
    base_inertia: f64,
    /// 4·d·d of the holding force F(x), B.
    four_dd: f64,
    holding_b: f64,
    /// The hoses' stiffness per volume.
    kl: f64,
    /// The linkage's γ, 2ζω and ω².
    g: f64,
    z2w: f64,
    ww: f64,
    /// Each main link's 2ζω_b and ω_b².
    boom_z2w: [f64; 2],
    boom_ww: [f64; 2],
}

impl ArmConsts {
    pub fn of(m: &SimModel) -> ArmConsts {
        let arm = &m.arm;
        let k = arm.k;
        let d2 = arm.d_m * arm.d_m;
        let ml = arm.link_mass_kg();
        let il = arm.link_inertia_kgm2();
        let me = arm.ee_mass_kg;
        let c = ml * k * k / 16.0;
        let lc = &m.compliance;
        let w = lc.omega();
        let b = &m.boom;
        ArmConsts {
            k,
            me,
            e: arm.r_min_m - k * arm.x_min_m,
            il,
            d2,
            two_d2: 2.0 * d2,
            four_d2: 4.0 * d2,
            c10: 10.0 / 16.0 * ml * k * k,
            c20: 20.0 / 16.0 * ml * k * k,
            two_me_k: 2.0 * me * k,
            c,
            two_c: 2.0 * c,
            nine_c: 9.0 * c,
            me_kk: me * k * k,
            two_il: 2.0 * il,
            ee_inertia: arm.ee_inertia_kgm2,
            base_inertia: arm.base_inertia_kgm2,
            four_dd: 4.0 * arm.d_m * arm.d_m,
            holding_b: arm.holding_b_n,
            kl: m.circuit.line_bulk_pa / m.circuit.line_volume_m3,
            g: lc.gamma(),
            z2w: 2.0 * lc.damping_ratio * w,
            ww: w * w,
            boom_z2w: std::array::from_fn(|i| 2.0 * b.damping_ratio * b.omega[i]),
            boom_ww: std::array::from_fn(|i| b.omega[i] * b.omega[i]),
        }
    }

    /// The holding force F(x) as `Arm::holding_force_n` computes it.
    #[inline]
    fn holding_force_n(&self, x: f64) -> f64 {
        let s2 = (self.four_dd - x * x).max(1e-6);
        self.holding_b * x / s2.sqrt()
    }
}

#[inline]
fn mass_matrix_of(a: &ArmConsts, x: f64) -> MassMatrix {
    let s2 = (a.four_d2 - x * x).max(1e-6);
    let rr = a.k * x + a.e;
    // links: m(kx/4)² + m(3kx/4)² = (10/16)·m·k²·x²; rotation I·cos²φ each, cos φ = x/2d
    let a11 =
        a.c10 * x * x + a.me * rr * rr + a.il * x * x / a.two_d2 + a.ee_inertia + a.base_inertia;
    let a11_dx = a.c20 * x + a.two_me_k * rr + a.il * x / a.d2;
    // links: c·(4d² + x²)/s² + 9c with c = m·k²/16; pitch rate ẋ/s for each rod
    let num = a.c * (a.four_d2 + x * x) + a.two_il;
    let a22 = num / s2 + a.nine_c + a.me_kk;
    let a22_dx = (a.two_c * x * s2 + 2.0 * x * num) / (s2 * s2);
    MassMatrix {
        a11,
        a11_dx,
        a22,
        a22_dx,
    }
}

/// Signed square root with a small linear (laminar) region so the flow law
/// has a finite slope at zero pressure drop.
#[inline]
fn orifice(dp: f64) -> f64 {
    const LAMINAR_PA: f64 = 2.0e4;
    if dp.abs() >= LAMINAR_PA {
        dp.signum() * dp.abs().sqrt()
    } else {
        dp / LAMINAR_PA.sqrt()
    }
}

/// Servovalve flows out of ports A and B for spool `y` (000 eq. 15–16) at
/// port pressures `pa`, `pb` and supply `ps`, and the flow drawn from
/// supply. The inlet side takes oil through its supply check valve (none
/// flows back into supply, 000 §I); with `counterbalance` the exhaust side
/// passes the counterbalance valve, piloted by the inlet, in series with the
/// spool's metering edge (000 §I: "on the exhaust side of the motors").
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn valve_flows(
    h: &Hydraulics,
    c: &Circuit,
    act: &Actuator,
    y: f64,
    ps: f64,
    pa: f64,
    pb: f64,
    counterbalance: bool,
) -> (f64, f64, f64) {
    let a = act.valve_gain * y.abs();
    let inlet = |p: f64| a * orifice((ps - p - c.check_crack_pa).max(0.0));
    let exhaust = |p: f64, pilot: f64| {
        let e = if counterbalance {
            series(a, c.cb_gain * c.cb_opening(p, pilot))
        } else {
            a
        };
        e * orifice(p - h.tank_pa)
    };
    if y >= 0.0 {
        let q = inlet(pa);
        (q, -exhaust(pb, pa), q)
    } else {
        let q = inlet(pb);
        (-exhaust(pa, pb), q, q)
    }
}

/// Relief (eq. 14) plus anti-cavitation refill from tank: net flow *into* a chamber.
#[inline]
fn relief_flow(h: &Hydraulics, p: f64) -> f64 {
    let g = h.relief_gain_m3_per_s_pa;
    if p > h.relief_pa {
        -g * (p - h.relief_pa)
    } else if p < h.tank_pa {
        g * (h.tank_pa - p)
    } else {
        0.0
    }
}

/// Chamber volumes at actuator position `pos` (x − x_min for the cylinder, θ1 for the motor).
#[inline]
pub fn volumes(act: &Actuator, pos: f64) -> (f64, f64) {
    (
        (act.v0_a_m3 + act.area * pos).max(1e-6),
        (act.v0_b_m3 - act.alpha * act.area * pos).max(1e-6),
    )
}

/// Pressure rates of one actuator's chambers fed by hose flows `qa`, `qb`
/// (000 eq. 11–12, plus leakage and relief; `bleed` is an extra laminar
/// cross-port path).
#[inline]
#[allow(clippy::too_many_arguments)]
fn pressure_rates(
    h: &Hydraulics,
    act: &Actuator,
    pos: f64,
    vel: f64,
    pa: f64,
    pb: f64,
    (qa, qb): (f64, f64),
    bleed: f64,
) -> (f64, f64) {
    let (va, vb) = volumes(act, pos);
    let leak = (act.leakage + bleed) * (pa - pb);
    let dpa = h.bulk(pa) / va * (qa - act.area * vel - leak + relief_flow(h, pa));
    let dpb = h.bulk(pb) / vb * (qb + act.alpha * act.area * vel + leak + relief_flow(h, pb));
    (dpa, dpb)
}

/// The cylinder's end stop's stiffness (N/m). assumed: a steel stop behind
/// a rubber pad.
pub const END_STOP_N_PER_M: f64 = 2.0e7;

/// End-stop force of the cylinder (N): a stiff spring-damper past either end.
#[inline]
fn end_stop(m: &SimModel, x: f64, xd: f64) -> f64 {
    const C: f64 = 2.0e5; // N·s/m
    let lo = m.arm.x_min_m - x;
    let hi = x - m.arm.x_max_m();
    if lo > 0.0 {
        END_STOP_N_PER_M * lo - C * xd.min(0.0)
    } else if hi > 0.0 {
        -END_STOP_N_PER_M * hi - C * xd.max(0.0)
    } else {
        0.0
    }
}

/// Actuator torque / force on the arm (000 eq. 9 minus friction eq. 10).
#[inline]
pub fn actuator_efforts(m: &SimModel, s: &State) -> (f64, f64) {
    let tau1 = m.motor.area * (s[PA1] - s[PB1]) - m.motor.friction.force(s[THD]);
    let tau2 = m.cylinder.area * (s[PA2] - m.cylinder.alpha * s[PB2])
        - m.cylinder.friction.force(s[XD])
        + end_stop(m, s[X], s[XD]);
    (tau1, tau2)
}

/// Time derivative of the state for held inputs `u`; also returns the arm's
/// tip acceleration in the base frame (for the linkage mode and reports).
pub fn derivative(m: &SimModel, s: &State, u: &Inputs) -> (State, [f64; 2]) {
    derivative_near(m, s, u, Trig::at(s[TH]), &ArmConsts::of(m))
}

/// sin and cos of θ1 near a reference angle: one `sin_cos` per RK4 step
/// instead of one per stage (θ1 moves ≤ 0.63 mrad within a 1.25 ms step; the
/// third-order Taylor terms leave under 1e-13 of error).
#[derive(Clone, Copy, Debug)]
pub struct Trig {
    theta: f64,
    sin: f64,
    cos: f64,
}

impl Trig {
    pub fn at(theta: f64) -> Trig {
        let (sin, cos) = theta.sin_cos();
        Trig { theta, sin, cos }
    }

    /// (sin θ, cos θ).
    #[inline]
    fn near(&self, theta: f64) -> (f64, f64) {
        let d = theta - self.theta;
        if d.abs() > 1e-2 {
            return theta.sin_cos();
        }
        let (d2, d3) = (0.5 * d * d, d * d * d / 6.0);
        (
            self.sin * (1.0 - d2) + self.cos * (d - d3),
            self.cos * (1.0 - d2) - self.sin * (d - d3),
        )
    }
}

fn derivative_near(
    m: &SimModel,
    s: &State,
    u: &Inputs,
    trig: Trig,
    a: &ArmConsts,
) -> (State, [f64; 2]) {
    let mut ds = [0.0; N];
    let mm = mass_matrix_of(a, s[X]);
    let (tau1, tau2) = actuator_efforts(m, s);
    let (th, thd, x, xd) = (s[TH], s[THD], s[X], s[XD]);
    let thdd = (tau1 - mm.a11_dx * xd * thd) / mm.a11;
    let xdd =
        (tau2 - 0.5 * mm.a22_dx * xd * xd + 0.5 * mm.a11_dx * thd * thd + a.holding_force_n(x))
            / mm.a22;
    ds[TH] = thd;
    ds[THD] = thdd;
    ds[X] = xd;
    ds[XD] = xdd;
    let h = &m.hydraulics;
    let c = &m.circuit;
    let ps = s[PS];
    // the valves' supply: the accumulator's, or tank behind the dump valve
    let ps_valves = if u.estop { h.tank_pa } else { ps };
    let (va1, vb1, qs1) = valve_flows(h, c, &m.motor, s[Y1], ps_valves, s[LP], s[LP + 1], true);
    let (va2, vb2, qs2) = if u.estop {
        (0.0, 0.0, 0.0)
    } else {
        valve_flows(h, c, &m.cylinder, s[Y2], ps, s[LP + 2], s[LP + 3], false)
    };
    let (qs1, qs2) = if u.estop { (0.0, 0.0) } else { (qs1, qs2) };
    // the hoses: compliance at the valve end, inertance and friction along
    let valve_q = [va1, vb1, va2, vb2];
    let chamber = [s[PA1], s[PB1], s[PA2], s[PB2]];
    let kl = a.kl;
    for j in 0..4 {
        ds[LP + j] = kl * (valve_q[j] - s[LQ + j]);
        ds[LQ + j] = (s[LP + j] - chamber[j] - c.line_resistance * s[LQ + j]) / c.line_inertance;
    }
    let (a1, b1) = pressure_rates(
        h,
        &m.motor,
        th,
        thd,
        s[PA1],
        s[PB1],
        (s[LQ], s[LQ + 1]),
        c.cb_bleed,
    );
    let (a2, b2) = pressure_rates(
        h,
        &m.cylinder,
        x - m.arm.x_min_m,
        xd,
        s[PA2],
        s[PB2],
        (s[LQ + 2], s[LQ + 3]),
        0.0,
    );
    ds[PA1] = a1;
    ds[PB1] = b1;
    ds[PA2] = a2;
    ds[PB2] = b2;
    // the accumulator: pump in, both valves' inlets out
    // (the manifold's oil at its pure-oil modulus: eq. 13 is within 5 % of
    // it at supply pressure)
    let pump = if u.faults.supply_lost {
        0.0
    } else {
        c.pump_flow(ps, h.supply_pa)
    };
    ds[PS] = (pump - qs1 - qs2) / c.supply_capacitance(ps, h.bulk_modulus_pa);
    if u.faults.supply_lost {
        ds[PS] -= (ps - h.tank_pa) / super::fault::SUPPLY_VENT_TAU_S;
    }
    // eq. 17 with K_s folded into the valve gain; the spool stops at ±1
    let spool = |y: f64, cmd: f64, tau: f64| {
        let r = (cmd.clamp(-1.0, 1.0) - y) / tau;
        if (y >= 1.0 && r > 0.0) || (y <= -1.0 && r < 0.0) {
            0.0
        } else {
            r
        }
    };
    ds[Y1] = if u.faults.motor_spool_stuck {
        0.0
    } else {
        spool(s[Y1], u.u_motor, m.motor.valve_tau_s)
    };
    ds[Y2] = spool(s[Y2], u.u_cyl, m.cylinder.valve_tau_s);
    // tip acceleration of W(θ1, R) (a2's contribution, 1 cm, is neglected here)
    let k = a.k;
    let r = m.arm.r_of_x(x);
    let (rd, rdd) = (k * xd, k * xdd);
    let (sn, cs) = trig.near(th);
    let ar = rdd - r * thd * thd;
    let at = r * thdd + 2.0 * rd * thd;
    let acc = [ar * cs - at * sn, ar * sn + at * cs];
    let (g, z2w, ww) = (a.g, a.z2w, a.ww);
    ds[DX] = s[DXD];
    ds[DXD] = -g * acc[0] - z2w * s[DXD] - ww * s[DX];
    ds[DY] = s[DYD];
    ds[DYD] = -g * acc[1] - z2w * s[DYD] - ww * s[DY];
    // each main link's lateral mode, driven by the tangential acceleration
    // of its outer end: link 1 at the pantograph's apex (k·x/2 from the
    // axis, 000 eq. 1), link 2 at the nozzle (R)
    let r_apex = 0.5 * k * x;
    let tangential = [r_apex * thdd + k * xd * thd, at];
    for (i, (p, v)) in [(B1, B1D), (B2, B2D)].into_iter().enumerate() {
        ds[p] = s[v];
        ds[v] = -tangential[i] - a.boom_z2w[i] * s[v] - a.boom_ww[i] * s[p];
    }
    (ds, acc)
}

/// The nozzle's offset in the base frame from the links' bending (m): both
/// modes move it sideways (tangentially), one to one (assumed: link 2
/// carries link 1's apex deflection to the nozzle rigidly).
#[inline]
pub fn boom_offset(s: &State) -> [f64; 2] {
    let d = s[B1] + s[B2];
    let (sn, cs) = s[TH].sin_cos();
    [-sn * d, cs * d]
}

/// One classical RK4 step of length `h`.
pub fn rk4_step(m: &SimModel, s: &mut State, u: &Inputs, h: f64) {
    let trig = Trig::at(s[TH]);
    let a = ArmConsts::of(m);
    let a = &a;
    let (k1, _) = derivative_near(m, s, u, trig, a);
    let mut t = *s;
    for i in 0..N {
        t[i] = s[i] + 0.5 * h * k1[i];
    }
    let (k2, _) = derivative_near(m, &t, u, trig, a);
    for i in 0..N {
        t[i] = s[i] + 0.5 * h * k2[i];
    }
    let (k3, _) = derivative_near(m, &t, u, trig, a);
    for i in 0..N {
        t[i] = s[i] + h * k3[i];
    }
    let (k4, _) = derivative_near(m, &t, u, trig, a);
    for i in 0..N {
        s[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
}

/// The arm at rest at (θ1, R) with chamber pressures that hold it statically
/// against gravity (the cylinder pulls with F(x)); pressures chosen with
/// p_A + p_B = p0 + p_T (valve null of a critically lapped valve).
pub fn rest_state(m: &SimModel, theta: f64, r: f64) -> State {
    let mut s = [0.0; N];
    let x = m.arm.x_of_r(r).clamp(m.arm.x_min_m, m.arm.x_max_m());
    s[TH] = theta;
    s[X] = x;
    let h = &m.hydraulics;
    let sum = h.supply_pa + h.tank_pa;
    s[PA1] = 0.5 * sum;
    s[PB1] = 0.5 * sum;
    // (pA − α·pB)·A = −F(x), pA + pB = sum
    let c = &m.cylinder;
    let f = m.arm.holding_force_n(x);
    let pb = (sum + f / c.area) / (1.0 + c.alpha);
    s[PB2] = pb;
    s[PA2] = sum - pb;
    // the accumulator charged to the compensator setting, the hoses at their
    // chambers' pressures and still
    s[PS] = h.supply_pa;
    s[LP] = s[PA1];
    s[LP + 1] = s[PB1];
    s[LP + 2] = s[PA2];
    s[LP + 3] = s[PB2];
    // the linkage hangs straight at rest
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trig_near_a_reference_matches_sin_cos() {
        for th in [0.79, 1.2, 1.57, 2.35] {
            let t = Trig::at(th);
            for d in [-2e-2, -1e-2, -5e-4, 0.0, 3e-4, 9e-3, 0.5] {
                let (s, c) = t.near(th + d);
                let (s0, c0) = (th + d).sin_cos();
                assert!((s - s0).abs() < 1e-9 && (c - c0).abs() < 1e-9, "{th} {d}");
            }
            // within one 1.25 ms step of the arm's 0.5 rad/s
            let (s, c) = t.near(th + 6.3e-4);
            let (s0, c0) = (th + 6.3e-4).sin_cos();
            assert!((s - s0).abs() < 1e-14 && (c - c0).abs() < 1e-14);
        }
    }

    #[test]
    fn friction_sign_matches_tanh() {
        let f = SimModel::basr().motor.friction;
        for i in -3000..=3000 {
            let v = i as f64 * 1e-5;
            let y = v / f.smooth_speed;
            let exact = f.viscous * v
                + (f.coulomb + f.stiction * (-(v.abs()) / f.stribeck_speed).exp()) * y.tanh();
            assert!((f.force(v) - exact).abs() < 1e-12, "{v}");
        }
    }

    fn max_rate(m: &SimModel, s: &State) -> f64 {
        let (ds, _) = derivative(m, s, &Inputs::default());
        ds[THD].abs().max(ds[XD].abs())
    }

    #[test]
    fn rest_state_is_static_equilibrium_at_f_of_x() {
        let m = SimModel::basr();
        for r in [1.6, 3.0, 4.5, 5.3] {
            let s = rest_state(&m, 1.5, r);
            let (_, tau2) = actuator_efforts(&m, &s);
            let f = m.arm.holding_force_n(s[X]);
            // the cylinder pulls with exactly F(x)
            assert!((tau2 + f).abs() < 1e-6 * f, "r={r}: {tau2} vs {f}");
            assert!(max_rate(&m, &s) < 1e-9, "r={r}");
        }
    }

    #[test]
    fn without_the_holding_force_the_arm_extends() {
        let m = SimModel::basr();
        let mut s = rest_state(&m, 1.5, 3.0);
        s[PB2] = s[PA2]; // drop the pull
        let (ds, _) = derivative(&m, &s, &Inputs::default());
        assert!(ds[XD] > 0.0, "gravity extends the arm");
    }

    #[test]
    fn mass_matrix_derivatives_match_finite_differences() {
        let m = SimModel::basr();
        for x in [0.2, 0.4, 0.6] {
            let h = 1e-6;
            let a = mass_matrix(&m, x);
            let p = mass_matrix(&m, x + h);
            let q = mass_matrix(&m, x - h);
            assert!(((p.a11 - q.a11) / (2.0 * h) - a.a11_dx).abs() < 1e-4 * a.a11_dx.abs());
            assert!(((p.a22 - q.a22) / (2.0 * h) - a.a22_dx).abs() < 1e-4 * a.a22_dx.abs());
        }
    }

    #[test]
    fn energy_is_conserved_without_hydraulics_and_friction() {
        // Lagrange's equations conserve T + V when the actuators do no work:
        // zero friction, a locked-out cylinder replaced by a constant force
        // that exactly balances gravity at the start is not conservative, so
        // instead let the arm fall freely (no pressures) and check T + V.
        let mut m = SimModel::basr();
        m.motor.friction.viscous = 0.0;
        m.motor.friction.coulomb = 0.0;
        m.motor.friction.stiction = 0.0;
        m.cylinder.friction = m.motor.friction.clone();
        m.hydraulics.bulk_modulus_pa = 1.0; // chambers exert ~no force
        m.hydraulics.bulk_law_eq13 = false;
        let mut s = rest_state(&m, 1.5, 2.0);
        for p in [PA1, PB1, PA2, PB2] {
            s[p] = 0.0;
        }
        s[THD] = 0.3;
        let energy = |s: &State| {
            let mm = mass_matrix(&m, s[X]);
            let d = m.arm.d_m;
            let v = m.arm.holding_b_n * (4.0 * d * d - s[X] * s[X]).sqrt();
            0.5 * mm.a11 * s[THD] * s[THD] + 0.5 * mm.a22 * s[XD] * s[XD] + v
        };
        let e0 = energy(&s);
        for _ in 0..300 {
            rk4_step(&m, &mut s, &Inputs::default(), 1e-3);
        }
        assert!(s[X] > m.arm.x_of_r(2.0) + 0.01, "it fell outwards");
        let e1 = energy(&s);
        assert!((e1 - e0).abs() < 1e-6 * e0, "{e0} → {e1}");
    }
}
