//! The constant numbers of the simulated robot: arm masses, hydraulics, valves,
//! end-effector servos, linkage compliance, sensors and controller settings.
//!
//! This is the *model* (Pinocchio/Drake habit): immutable during a run; the
//! changing values live in `plant::State`. Every number says where it comes
//! from; `assumed` marks the ones no source gives.

use serde::{Deserialize, Serialize};

/// Standard gravity (m/s²).
pub const G: f64 = 9.80665;

/// The pantograph arm (000 section II eq. 1–8, appendix A eq. 12).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Arm {
    /// Pantograph amplification k: extension R moves k × the A–C distance x (SPEC §4).
    pub k: f64,
    /// Half-length d of the base link BC; the links rise as √(4d² − x²) (000 App. A eq. 4).
    pub d_m: f64,
    /// A–C distance x at full retraction (000 App. A: 7.5 in).
    pub x_min_m: f64,
    /// Cylinder stroke: x_max = x_min + stroke (000 App. A: 25.5 − 7.5 in).
    pub stroke_m: f64,
    /// Extension R at full retraction (SPEC §4, encoder zero).
    pub r_min_m: f64,
    /// Arm–end-effector offset a2 (SPEC §2).
    pub a2_m: f64,
    /// Holding-force constant B of F(x) = B·x/√(4d² − x²) (000 App. A eq. 12: 709.9 lbf).
    pub holding_b_n: f64,
    /// End-effector mass m3 (SPEC §4, 001 ch. 3).
    pub ee_mass_kg: f64,
    /// End-effector inertia about its own vertical axis (assumed: 35 kg at 0.25 m).
    pub ee_inertia_kgm2: f64,
    /// Inertia of the turntable, motor and cylinder about the base axis (assumed).
    pub base_inertia_kgm2: f64,
    /// Base-rotation safety window (SPEC §4; 000 section III `q1_a` test).
    pub theta_min_rad: f64,
    pub theta_max_rad: f64,
}

impl Arm {
    /// Mass of each of the two main links. The potential energy of the two
    /// links is (m1+m2)·g·k·√(4d²−x²)/4 (000 eq. 1), and appendix A writes it
    /// B·√(4d²−x²); so m1 = m2 = 2B/(g·k): the masses are fixed by the
    /// measured holding force, not guessed.
    pub fn link_mass_kg(&self) -> f64 {
        2.0 * self.holding_b_n / (G * self.k)
    }

    /// Length of each main link, k·d (the links meet at height k·√(4d²−x²)/2).
    pub fn link_length_m(&self) -> f64 {
        self.k * self.d_m
    }

    /// Inertia of a main link about its centre, as a slender rod.
    pub fn link_inertia_kgm2(&self) -> f64 {
        let l = self.link_length_m();
        self.link_mass_kg() * l * l / 12.0
    }

    pub fn x_max_m(&self) -> f64 {
        self.x_min_m + self.stroke_m
    }

    /// Extension R from the A–C distance x.
    pub fn r_of_x(&self, x: f64) -> f64 {
        self.r_min_m + self.k * (x - self.x_min_m)
    }

    /// A–C distance x from the extension R.
    pub fn x_of_r(&self, r: f64) -> f64 {
        self.x_min_m + (r - self.r_min_m) / self.k
    }

    /// Gravity force on the extension coordinate x (N, positive = extends):
    /// F(x) = B·x/√(4d² − x²) (000 App. A eq. 11).
    pub fn holding_force_n(&self, x: f64) -> f64 {
        let s2 = (4.0 * self.d_m * self.d_m - x * x).max(1e-6);
        self.holding_b_n * x / s2.sqrt()
    }
}

/// Friction per 000 eq. 10: viscous + Coulomb + exponentially decaying stiction.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Friction {
    /// Viscous coefficient (N·s/m or N·m·s/rad).
    pub viscous: f64,
    /// Coulomb level (N or N·m).
    pub coulomb: f64,
    /// Stiction excess at zero speed (N or N·m).
    pub stiction: f64,
    /// Speed over which stiction decays (m/s or rad/s).
    pub stribeck_speed: f64,
    /// Speed of the smooth sign (tanh) used instead of sign() so the
    /// fixed-step integrator does not chatter at rest.
    pub smooth_speed: f64,
}

impl Friction {
    /// Friction force opposing `v` (000 eq. 10 with a smooth sign).
    #[inline]
    pub fn force(&self, v: f64) -> f64 {
        let y = v / self.smooth_speed;
        // tanh(y) = 1 − 2/(e^{2y} + 1): one exp instead of libm's tanh (its
        // expm1 was 15 % of a simulation's time), within 1e-16 of it; it
        // rounds to ±1 past |y| ≈ 19
        let sgn = if y.abs() > 20.0 {
            y.signum()
        } else {
            1.0 - 2.0 / ((2.0 * y).exp() + 1.0)
        };
        self.viscous * v
            + (self.coulomb + self.stiction * (-(v.abs()) / self.stribeck_speed).exp()) * sgn
    }
}

/// A hydraulic actuator with its servovalve (000 eq. 9, 11–17). For the motor
/// `area` is the displacement (m³/rad), `alpha` = 1 and x is θ1.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Actuator {
    /// Piston area A of chamber A (m²), or motor displacement (m³/rad).
    pub area: f64,
    /// Area ratio α of chamber B to chamber A (000 eq. 9).
    pub alpha: f64,
    /// Volume of chamber A at position 0 incl. pipes (m³): V_A = v0_a + A·pos.
    pub v0_a_m3: f64,
    /// Volume of chamber B at position 0 incl. pipes (m³): V_B = v0_b − α·A·pos.
    pub v0_b_m3: f64,
    /// Servovalve flow gain B_v·K_s per unit command (m³/(s·√Pa)) (eq. 15–17).
    pub valve_gain: f64,
    /// Servovalve time constant τ_s (s) (eq. 17).
    pub valve_tau_s: f64,
    /// Controller's command limit (000 section III: ±0.2 motor, ±1 cylinder).
    pub command_limit: f64,
    /// Command the controller writes when it refuses to drive (000 section III `zero1`, `zero2`).
    pub off_command: f64,
    /// Internal leakage A→B (m³/(s·Pa)).
    pub leakage: f64,
    pub friction: Friction,
}

/// Supply, tank, oil and relief valves.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Hydraulics {
    /// Supply pressure p0 (SPEC §4; 000 section III 2.069e7).
    pub supply_pa: f64,
    /// Tank pressure p_T (SPEC §4; 000 section III 1e5).
    pub tank_pa: f64,
    /// Bulk modulus of pure oil E_oil (SPEC §4; 6.1782 = E·D²).
    pub bulk_modulus_pa: f64,
    /// Use eq. 13's pressure-dependent substitute bulk modulus (air content);
    /// false keeps E constant.
    pub bulk_law_eq13: bool,
    /// Pressure constant p_κ of eq. 13 (assumed: E' reaches E_oil near supply).
    pub bulk_p_kappa_pa: f64,
    /// Relief-valve cracking pressure p_max (eq. 14; assumed just above supply).
    pub relief_pa: f64,
    /// Relief-valve flow gain G (eq. 14; assumed) — also used by the
    /// anti-cavitation check valve that refills a chamber from tank.
    pub relief_gain_m3_per_s_pa: f64,
}

impl Hydraulics {
    /// Substitute bulk modulus at pressure `p` (000 eq. 13, log base 10).
    pub fn bulk(&self, p: f64) -> f64 {
        if !self.bulk_law_eq13 {
            return self.bulk_modulus_pa;
        }
        let arg = 100.0 * (0.9 * p.max(0.0) / self.bulk_p_kappa_pa + 0.03);
        // ln × log10(e), not log10: glibc's log10 is its old slow routine (17 % of a
        // simulation's instructions went to it); the two agree to an ulp or two.
        (0.5 * self.bulk_modulus_pa * arg.ln() * std::f64::consts::LOG10_E)
            .min(self.bulk_modulus_pa)
    }
}

/// One end-effector axis as a servo loop with rate and acceleration limits.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ServoAxis {
    /// Position-loop bandwidth (rad/s) (assumed).
    pub bandwidth_rad_s: f64,
    /// Rate limit (unit/s).
    pub rate_limit: f64,
    /// Acceleration limit (unit/s²).
    pub accel_limit: f64,
    /// Travel [min, max] (unit).
    pub min: f64,
    pub max: f64,
    /// Sensor resolution (unit per count).
    pub resolution: f64,
}

/// The end-effector linkage as one lateral mode (001 table 3.2).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Compliance {
    /// Torsional stiffness at joint F (N·m/rad): 101.7 N·m gives 0.18–0.20°.
    pub stiffness_nm_per_rad: f64,
    /// Nozzle distance below joint F (m).
    pub nozzle_below_f_m: f64,
    /// Mass hanging below F (kg), taken as a uniform rod F→nozzle (assumed).
    pub mass_kg: f64,
    /// Damping ratio of the mode (assumed; welded steel linkage).
    pub damping_ratio: f64,
}

impl Compliance {
    /// Inertia about F of the uniform rod.
    pub fn inertia(&self) -> f64 {
        self.mass_kg * self.nozzle_below_f_m * self.nozzle_below_f_m / 3.0
    }
    /// Natural frequency (rad/s).
    pub fn omega(&self) -> f64 {
        (self.stiffness_nm_per_rad / self.inertia()).sqrt()
    }
    /// Nozzle deflection per unit base acceleration of F, static and
    /// dynamic: δ̈ = −γ·a_F − 2ζωδ̇ − ω²δ with γ = m·(L/2)·L/I.
    pub fn gamma(&self) -> f64 {
        self.mass_kg * 0.5 * self.nozzle_below_f_m * self.nozzle_below_f_m / self.inertia()
    }
}

/// Sensors (000 section III `readValues`; SPEC §4).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Sensors {
    /// Base encoder counts per turn (88 000).
    pub base_counts_per_turn: f64,
    /// Extension encoder: metres of R per count (0.105833 mm).
    pub extension_m_per_count: f64,
    /// Pressure transducer: Pa per volt (5.175e6) and offset volts (1.0).
    pub pressure_pa_per_volt: f64,
    pub pressure_offset_v: f64,
    /// ADC step (V) (assumed: 12 bits over ±10 V).
    pub adc_step_v: f64,
    /// Transducer gain error: the controller reads p × this (1 nominal).
    pub pressure_gain: f64,
    /// Read exact values instead of counts and ADC steps (numerical checks
    /// only: quantisation makes the closed loop sensitive to the last bit).
    pub exact: bool,
}

/// Controller settings (000 section III).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ControlSettings {
    /// Sampling time T (000 section III `const double T = 0.005`).
    pub period_s: f64,
    /// Time-delay estimate λ of the SJCT/SCCT disturbance (SPEC §4: 10 ms).
    pub lambda_s: f64,
}

/// Everything the simulator needs about one robot.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SimModel {
    pub arm: Arm,
    pub hydraulics: Hydraulics,
    pub motor: Actuator,
    pub cylinder: Actuator,
    pub yaw: ServoAxis,
    pub tilt_nut: ServoAxis,
    pub vertical: ServoAxis,
    pub compliance: Compliance,
    /// Accumulator, check and counterbalance valves, hoses (000 §I).
    pub circuit: super::circuit::Circuit,
    /// One lateral bending mode per main link.
    pub boom: super::circuit::Boom,
    pub sensors: Sensors,
    pub control: ControlSettings,
    /// RK4 sub-steps per control period.
    pub substeps: u32,
}

/// Largest h·ω of the plant's fastest mode per RK4 step. source: RK4 is
/// stable for h·ω ≤ 2√2 ≈ 2.83 on an undamped mode; 2.4 leaves 15 % for
/// what the bound does not see (a plant of the spread with its bulk modulus
/// 20 % up rings 4 % faster, 50 % up, the most any spread draws, 11 %).
/// The default robot gets 1.25 ms steps
/// (h·ω = 2.26 on its bound): STOP, SCHOOL, STOP at full reach, the bike
/// symbol and markings/turn_lane.toml on 40 plants (seed 1) then give p95
/// within 0.12 mm of 0.25 ms steps, where 1 ms steps came within 0.21 mm
/// (docs/simulate.md); 1.67 ms steps (h·ω = 3.0) went unstable at full
/// reach (p95 10.1 mm).
pub const RK4_H_OMEGA: f64 = 2.4;

impl SimModel {
    /// The default BASR model: [`SimModel::from_robot`] of the embedded
    /// description (robots/basr.toml states every value's source).
    pub fn basr() -> SimModel {
        SimModel::from_robot(&basr_robot::Robot::basr())
            .expect("the embedded robot description simulates")
    }

    /// The simulator's model of `robot`: kinematics, hydraulics, sensors,
    /// limits and control timing from their tables, the rest from its
    /// `[dynamics]` table.
    /// A job's robot of another kind than BASR has no hydraulic model (Err).
    pub fn from_robot(robot: &impl HydraulicRobot) -> Result<SimModel, ModelError> {
        let robot = robot.hydraulic_robot()?;
        let h = &robot.hydraulics;
        let arm = &robot.arm;
        let dy = &robot.dynamics;
        let ee = &robot.end_effector;
        let l = &robot.limits;
        let pi = std::f64::consts::PI;
        let area = pi * dy.cylinder_bore_m * dy.cylinder_bore_m / 4.0;
        let annulus = area - pi * dy.cylinder_rod_m * dy.cylinder_rod_m / 4.0;
        let alpha = annulus / area;
        let friction = |viscous, coulomb, stiction, stribeck: f64| Friction {
            viscous,
            coulomb,
            stiction,
            stribeck_speed: stribeck,
            // numerical: a tenth of the stiction decay speed
            smooth_speed: 0.1 * stribeck,
        };
        let fb = &ee.fourbar;
        let (nut_lo, nut_hi) = match (fb.nut_m(l.tilt_rad.min), fb.nut_m(l.tilt_rad.max)) {
            (Some(a), Some(b)) => (a.min(b), a.max(b)),
            _ => return Err(ModelError::TiltUnreachable),
        };
        // nut speed and acceleration from the tilt's, at the linkage's mean ratio
        let nut_per_rad = (nut_hi - nut_lo) / (l.tilt_rad.max - l.tilt_rad.min).max(1e-9);
        let tilt_counts = robot.encoders.tilt_counts_per_motor_rev as f64
            * ee.tilt_motor_turns_per_screw_turn
            / ee.tilt_screw_pitch_m;
        let yaw_counts = robot.encoders.yaw_counts_per_motor_rev as f64 * ee.yaw_gear_ratio;
        // the softest stiffness of 001 table 3.2 over the reach (it changes by
        // 10 % from retracted to extended; one linear mode)
        let worst_defl = ee
            .joint_f_deflection_rad
            .iter()
            .copied()
            .fold(0.0, f64::max);
        let mut m = SimModel {
            arm: Arm {
                k: arm.pantograph_ratio,
                d_m: h.gravity_d_m,
                x_min_m: h.gravity_x_min_m,
                stroke_m: arm.cylinder_stroke_m,
                r_min_m: arm.retracted_extension_m,
                a2_m: arm.a2_m,
                holding_b_n: h.gravity_b_n,
                ee_mass_kg: ee.mass_kg,
                ee_inertia_kgm2: dy.ee_inertia_kgm2,
                base_inertia_kgm2: dy.base_inertia_kgm2,
                theta_min_rad: l.base_rot_rad.min,
                theta_max_rad: l.base_rot_rad.max,
            },
            hydraulics: Hydraulics {
                supply_pa: h.supply_pa,
                tank_pa: h.tank_pa,
                bulk_modulus_pa: h.bulk_modulus_pa,
                bulk_law_eq13: dy.bulk_law_eq13,
                bulk_p_kappa_pa: dy.bulk_p_kappa_pa,
                relief_pa: dy.relief_pa,
                relief_gain_m3_per_s_pa: dy.relief_gain_m3_per_s_pa,
            },
            motor: Actuator {
                area: h.base_motor_displacement_m3prad / arm.base_motor_ratio,
                alpha: 1.0, // a motor is symmetric
                v0_a_m3: h.base_chamber_a_m3,
                v0_b_m3: h.base_chamber_b_m3,
                valve_gain: h.valve_flow_gain,
                valve_tau_s: dy.valve_time_constant_s,
                command_limit: h.command_limit,
                off_command: dy.motor_off_command,
                leakage: dy.leakage_m3_per_s_pa,
                friction: friction(
                    dy.motor_viscous_nms_per_rad,
                    dy.motor_coulomb_nm,
                    dy.motor_stiction_nm,
                    dy.motor_stribeck_rad_per_s,
                ),
            },
            cylinder: Actuator {
                area,
                alpha,
                v0_a_m3: dy.cylinder_dead_volume_m3,
                v0_b_m3: dy.cylinder_dead_volume_m3 + annulus * arm.cylinder_stroke_m,
                valve_gain: dy.cylinder_valve_flow_gain,
                valve_tau_s: dy.valve_time_constant_s,
                command_limit: dy.cylinder_command_limit,
                off_command: dy.cylinder_off_command,
                leakage: dy.leakage_m3_per_s_pa,
                friction: friction(
                    dy.cylinder_viscous_ns_per_m,
                    dy.cylinder_coulomb_n,
                    dy.cylinder_stiction_n,
                    dy.cylinder_stribeck_m_per_s,
                ),
            },
            yaw: ServoAxis {
                bandwidth_rad_s: dy.yaw_bandwidth_rad_per_s,
                rate_limit: l.ee_yaw_rad.max_vel,
                accel_limit: l.ee_yaw_rad.max_acc,
                min: l.ee_yaw_rad.min,
                max: l.ee_yaw_rad.max,
                resolution: std::f64::consts::TAU / yaw_counts,
            },
            tilt_nut: ServoAxis {
                bandwidth_rad_s: dy.tilt_bandwidth_rad_per_s,
                rate_limit: ee
                    .tilt_nut_max_speed_mps
                    .min(l.tilt_rad.max_vel * nut_per_rad),
                accel_limit: l.tilt_rad.max_acc * nut_per_rad,
                min: nut_lo,
                max: nut_hi,
                resolution: 1.0 / tilt_counts,
            },
            vertical: ServoAxis {
                bandwidth_rad_s: dy.vertical_bandwidth_rad_per_s,
                rate_limit: l.vertical_m.max_vel,
                accel_limit: l.vertical_m.max_acc,
                min: l.vertical_m.min,
                max: l.vertical_m.max,
                resolution: robot.encoders.vertical_m_per_count,
            },
            compliance: Compliance {
                stiffness_nm_per_rad: ee.joint_f_test_torque_nm / worst_defl.max(1e-12),
                nozzle_below_f_m: ee.nozzle_below_joint_f_m,
                mass_kg: ee.mass_kg,
                damping_ratio: dy.linkage_damping_ratio,
            },
            circuit: super::circuit::Circuit {
                acc_gas_m3: dy.accumulator_gas_m3,
                acc_precharge_pa: dy.accumulator_precharge_pa,
                supply_volume_m3: dy.supply_volume_m3,
                pump_flow_m3ps: dy.pump_flow_m3ps,
                pump_band_pa: dy.pump_band_pa,
                check_crack_pa: dy.supply_check_crack_pa,
                cb_pilot_ratio: dy.counterbalance_pilot_ratio,
                cb_crack_pa: dy.counterbalance_crack_pa,
                cb_band_pa: dy.counterbalance_band_pa,
                cb_gain: dy.counterbalance_flow_gain,
                cb_bleed: dy.counterbalance_bleed_m3_per_s_pa,
                line_volume_m3: dy.line_volume_m3,
                line_bulk_pa: dy.line_bulk_modulus_pa,
                line_inertance: dy.line_inertance_kg_per_m4,
                line_resistance: dy.line_resistance_pa_s_per_m3,
                pump_on: true,
            },
            boom: super::circuit::Boom {
                omega: [
                    std::f64::consts::TAU * dy.boom_link1_hz,
                    std::f64::consts::TAU * dy.boom_link2_hz,
                ],
                damping_ratio: dy.boom_damping_ratio,
            },
            sensors: Sensors {
                base_counts_per_turn: robot.encoders.base_counts_per_rev as f64,
                extension_m_per_count: robot.encoders.extension_m_per_count,
                pressure_pa_per_volt: dy.pressure_pa_per_volt,
                pressure_offset_v: dy.pressure_offset_v,
                adc_step_v: dy.adc_step_v,
                pressure_gain: 1.0,
                exact: false,
            },
            control: ControlSettings {
                period_s: robot.control.controller_sample_s,
                lambda_s: robot.control.delay_estimate_s,
            },
            // set from the model's fastest mode below, once every number
            // it is derived from is known to be finite and in range
            substeps: 1,
        };
        m.validate()?;
        m.substeps = m.stable_substeps()?;
        Ok(m)
    }

    /// The fastest oscillation of the plant (rad/s), an upper bound: a
    /// hose's inertance between its own compliance and its chamber's at
    /// the chamber's smallest volume over the actuator's travel (the
    /// piston's motion only adds compliance), the linkage mode, each
    /// boom's bending mode, and the cylinder's end stop on the arm's
    /// lightest extension mass. The default robot's hose–chamber bound,
    /// 1809 rad/s (288 Hz, cylinder chamber A at its dead volume), is
    /// within 2 % of the largest eigenvalue of the plant's Jacobian there
    /// (1774 rad/s, computed numerically at rest and moving, over the reach).
    pub fn fastest_mode_rad_s(&self) -> f64 {
        let c = &self.circuit;
        let k_line = c.line_bulk_pa / c.line_volume_m3;
        let k_chamber = |act: &Actuator, lo: f64, hi: f64| {
            let (a_lo, b_lo) = super::plant::volumes(act, lo);
            let (a_hi, b_hi) = super::plant::volumes(act, hi);
            self.hydraulics.bulk_modulus_pa / a_lo.min(b_lo).min(a_hi).min(b_hi)
        };
        let motor = k_chamber(&self.motor, self.arm.theta_min_rad, self.arm.theta_max_rad);
        let cylinder = k_chamber(&self.cylinder, 0.0, self.arm.stroke_m);
        let hose = ((k_line + motor.max(cylinder)) / c.line_inertance).sqrt();
        // the end stop's spring (plant::END_STOP_N_PER_M) on the smallest
        // A22 over the stroke (it grows towards either end)
        let a22 = [0.0, 0.25, 0.5, 0.75, 1.0]
            .map(|f| {
                let x = self.arm.x_min_m + f * (self.arm.x_max_m() - self.arm.x_min_m);
                super::plant::mass_matrix(self, x).a22
            })
            .into_iter()
            .fold(f64::INFINITY, f64::min);
        let end_stop = (super::plant::END_STOP_N_PER_M / a22).sqrt();
        [
            hose,
            self.compliance.omega(),
            self.boom.omega[0],
            self.boom.omega[1],
            end_stop,
        ]
        .into_iter()
        .fold(0.0, f64::max)
    }

    /// RK4 steps per control period: as few as keep h·ω of the fastest
    /// mode within [`RK4_H_OMEGA`] and h within the valves' τ_s (RK4's
    /// real-axis bound is 2.79·τ_s). Too many (over 100): the description's
    /// hydraulics are too stiff to simulate at its control period.
    pub fn stable_substeps(&self) -> Result<u32, ModelError> {
        let omega = self.fastest_mode_rad_s();
        let tau = self.motor.valve_tau_s.min(self.cylinder.valve_tau_s);
        let h_max = (RK4_H_OMEGA / omega).min(tau);
        let n = (self.control.period_s / h_max - 1e-9).ceil().max(1.0);
        if !n.is_finite() || n > 100.0 {
            return Err(ModelError::TooStiff {
                hz: omega / std::f64::consts::TAU,
                period_s: self.control.period_s,
            });
        }
        Ok(n as u32)
    }

    /// Check every number is finite and in its physical range.
    pub fn validate(&self) -> Result<(), ModelError> {
        let checks: &[(&str, f64, bool)] = &[
            ("arm.k", self.arm.k, self.arm.k > 0.0),
            ("arm.d_m", self.arm.d_m, self.arm.d_m > 0.0),
            (
                "arm.stroke_m",
                self.arm.stroke_m,
                self.arm.stroke_m > 0.0 && self.arm.x_max_m() < 2.0 * self.arm.d_m,
            ),
            (
                "arm.holding_b_n",
                self.arm.holding_b_n,
                self.arm.holding_b_n > 0.0,
            ),
            (
                "arm.ee_mass_kg",
                self.arm.ee_mass_kg,
                self.arm.ee_mass_kg >= 0.0,
            ),
            (
                "hydraulics.supply_pa",
                self.hydraulics.supply_pa,
                self.hydraulics.supply_pa > self.hydraulics.tank_pa,
            ),
            (
                "hydraulics.bulk_modulus_pa",
                self.hydraulics.bulk_modulus_pa,
                self.hydraulics.bulk_modulus_pa > 0.0,
            ),
            ("motor.area", self.motor.area, self.motor.area > 0.0),
            (
                "cylinder.area",
                self.cylinder.area,
                self.cylinder.area > 0.0,
            ),
            (
                "cylinder.alpha",
                self.cylinder.alpha,
                self.cylinder.alpha > 0.0 && self.cylinder.alpha <= 1.0,
            ),
            (
                "motor.valve_tau_s",
                self.motor.valve_tau_s,
                self.motor.valve_tau_s > 0.0,
            ),
            (
                "cylinder.valve_tau_s",
                self.cylinder.valve_tau_s,
                self.cylinder.valve_tau_s > 0.0,
            ),
            (
                "compliance.stiffness_nm_per_rad",
                self.compliance.stiffness_nm_per_rad,
                self.compliance.stiffness_nm_per_rad > 0.0,
            ),
            (
                "control.period_s",
                self.control.period_s,
                self.control.period_s > 0.0,
            ),
            (
                "control.lambda_s",
                self.control.lambda_s,
                self.control.lambda_s >= self.control.period_s,
            ),
        ];
        for (name, v, ok) in checks {
            if !v.is_finite() || !ok {
                return Err(ModelError::OutOfRange { name, value: *v });
            }
        }
        if self.substeps == 0 || self.substeps > 100 {
            return Err(ModelError::Substeps(self.substeps));
        }
        Ok(())
    }
}

/// A robot the hydraulic model cannot be built from, or a model with a
/// number outside its physical range.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ModelError {
    #[error("the robot is of the {kind} kind, which has no hydraulic plant: `basr simulate` runs its servo plant")]
    NoHydraulicPlant { kind: String },
    #[error("the tilt four-bar cannot reach the tilt limits")]
    TiltUnreachable,
    #[error("{name} = {value} is outside its physical range")]
    OutOfRange { name: &'static str, value: f64 },
    #[error("substeps = {0} must be 1–100")]
    Substeps(u32),
    #[error(
        "the hydraulics ring at {hz:.0} Hz (a hose on its chamber, the linkage, a boom or the end \
         stop): simulating them needs over 100 RK4 steps per {period_s} s control period; check \
         the [dynamics] line and chamber volumes, or shorten controller_sample_s"
    )]
    TooStiff { hz: f64, period_s: f64 },
}

/// What a hydraulic model is built from: BASR's description, or a job's
/// robot of any kind (`AnyRobot`), which is refused unless it is BASR's:
/// the electric kinds have their servo plant (`sim::servo_job`).
pub trait HydraulicRobot {
    fn hydraulic_robot(&self) -> Result<&basr_robot::Robot, ModelError>;
}

impl HydraulicRobot for basr_robot::Robot {
    fn hydraulic_robot(&self) -> Result<&basr_robot::Robot, ModelError> {
        Ok(self)
    }
}

impl HydraulicRobot for basr_robot::AnyRobot {
    fn hydraulic_robot(&self) -> Result<&basr_robot::Robot, ModelError> {
        self.basr().ok_or_else(|| ModelError::NoHydraulicPlant {
            kind: self.kind().name().to_string(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const IN: f64 = 0.0254;

    /// The default robot's fastest mode is a hose on the cylinder's chamber
    /// A at its dead volume (1809 rad/s), and its 5 ms period takes four
    /// RK4 steps of 1.25 ms; hoses ten times stiffer need more, and a
    /// description too stiff for 100 steps is refused by name.
    #[test]
    fn the_integration_step_follows_the_fastest_mode() {
        let m = SimModel::basr();
        let w = m.fastest_mode_rad_s();
        assert!((w - 1809.0).abs() < 5.0, "{w}");
        assert_eq!(m.substeps, 4);
        assert!(m.control.period_s / m.substeps as f64 * w <= RK4_H_OMEGA);
        let mut stiff = m.clone();
        stiff.circuit.line_inertance /= 10.0;
        let n = stiff.stable_substeps().unwrap();
        assert!(
            n > 4 && stiff.control.period_s / n as f64 * stiff.fastest_mode_rad_s() <= RK4_H_OMEGA
        );
        stiff.circuit.line_inertance /= 1.0e4;
        let e = stiff.stable_substeps().unwrap_err().to_string();
        assert!(e.contains("Hz") && e.contains("controller_sample_s"), "{e}");
    }

    #[test]
    fn link_masses_reproduce_the_holding_force() {
        let m = SimModel::basr();
        // 000 App. A eq. 12 in its own units: F = 709.9·x/√(676 − x²) lbf, x in inches.
        for x_in in [7.5, 12.0, 18.0, 25.5] {
            let f_lbf = 709.9 * x_in / (676.0f64 - x_in * x_in).sqrt();
            let f = m.arm.holding_force_n(x_in * IN);
            assert!((f / 4.4482 - f_lbf).abs() < 1e-3 * f_lbf, "{x_in}: {f}");
        }
        // 2·m·g·k/4 = B
        let b = 2.0 * m.arm.link_mass_kg() * G * m.arm.k / 4.0;
        assert!((b - m.arm.holding_b_n).abs() < 1e-9);
        // R spans 1.55 .. ≈5.36 m (SPEC §4)
        assert!((m.arm.r_of_x(m.arm.x_max_m()) - 5.36).abs() < 0.01);
    }

    #[test]
    fn compliance_matches_table_3_2() {
        let c = SimModel::basr().compliance;
        let deg = (101.7 / c.stiffness_nm_per_rad).to_degrees();
        assert!((0.18..=0.2001).contains(&deg), "{deg}");
        // the mode sits near 9 Hz
        let f = c.omega() / std::f64::consts::TAU;
        assert!((5.0..15.0).contains(&f), "{f}");
    }

    #[test]
    fn bulk_law_is_near_e_at_supply_and_softer_at_low_pressure() {
        let h = SimModel::basr().hydraulics;
        assert!(h.bulk(20.0e6) > 0.95 * h.bulk_modulus_pa);
        assert!(h.bulk(1.0e6) < 0.7 * h.bulk_modulus_pa);
        assert!(h.bulk(0.0) > 0.2 * h.bulk_modulus_pa);
    }
}
