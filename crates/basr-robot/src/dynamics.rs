//! The `[dynamics]` table of a robot description: the numbers `basr
//! simulate` needs beyond kinematics — inertias, cylinder geometry, valve,
//! friction and relief data, servo bandwidths, pressure transducers. Most
//! have no source in the seeds and are marked *assumed* in robots/basr.toml.

use serde::{Deserialize, Serialize};

/// Dynamic parameters of the arm, its hydraulics and the end-effector servos.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Dynamics {
    /// Inertia of turntable, motor and cylinder about the base axis.
    pub base_inertia_kgm2: f64,
    /// End-effector inertia about its own vertical axis.
    pub ee_inertia_kgm2: f64,
    /// Extension cylinder bore and rod diameters.
    pub cylinder_bore_m: f64,
    pub cylinder_rod_m: f64,
    /// Oil volume of each cylinder chamber at its end of stroke (hoses, ports).
    pub cylinder_dead_volume_m3: f64,
    /// Cylinder servovalve flow gain B_v·K_s per unit command (m³/(s·√Pa)).
    pub cylinder_valve_flow_gain: f64,
    /// Cylinder valve command limit (the motor's is `hydraulics.command_limit`).
    pub cylinder_command_limit: f64,
    /// Servovalve time constant τ_s of both valves (000 eq. 17).
    pub valve_time_constant_s: f64,
    /// Commands written when the controller refuses to drive (000 §III `zero1`, `zero2`).
    pub motor_off_command: f64,
    pub cylinder_off_command: f64,
    /// Internal leakage across piston and motor (m³/(s·Pa)).
    pub leakage_m3_per_s_pa: f64,
    /// Motor friction per 000 eq. 10: viscous (N·m·s/rad), Coulomb and
    /// stiction (N·m), stiction decay speed (rad/s).
    pub motor_viscous_nms_per_rad: f64,
    pub motor_coulomb_nm: f64,
    pub motor_stiction_nm: f64,
    pub motor_stribeck_rad_per_s: f64,
    /// Cylinder friction per 000 eq. 10: viscous (N·s/m), Coulomb and
    /// stiction (N), stiction decay speed (m/s).
    pub cylinder_viscous_ns_per_m: f64,
    pub cylinder_coulomb_n: f64,
    pub cylinder_stiction_n: f64,
    pub cylinder_stribeck_m_per_s: f64,
    /// Use the pressure-dependent bulk modulus of 000 eq. 13 (else constant).
    pub bulk_law_eq13: bool,
    /// Pressure constant p_κ of eq. 13.
    pub bulk_p_kappa_pa: f64,
    /// Relief-valve cracking pressure p_max and flow gain G (000 eq. 14).
    pub relief_pa: f64,
    pub relief_gain_m3_per_s_pa: f64,
    /// Position-loop bandwidths of the end-effector servos (rad/s).
    pub yaw_bandwidth_rad_per_s: f64,
    pub tilt_bandwidth_rad_per_s: f64,
    pub vertical_bandwidth_rad_per_s: f64,
    /// Damping ratio of the end-effector linkage's lateral mode.
    pub linkage_damping_ratio: f64,
    /// Pressure transducers: Pa per volt and offset volts (000 §III), ADC step (V).
    pub pressure_pa_per_volt: f64,
    pub pressure_offset_v: f64,
    pub adc_step_v: f64,
    /// Supply accumulator (000 §I): gas volume at precharge (m³), precharge (Pa).
    pub accumulator_gas_m3: f64,
    pub accumulator_precharge_pa: f64,
    /// Oil in the supply manifold and hose (m³).
    pub supply_volume_m3: f64,
    /// Pressure-compensated pump: full flow (m³/s) and the band below
    /// `hydraulics.supply_pa` over which it falls to zero (Pa).
    pub pump_flow_m3ps: f64,
    pub pump_band_pa: f64,
    /// Supply check valves (000 §I): cracking pressure (Pa).
    pub supply_check_crack_pa: f64,
    /// Counterbalance valves on the motor's exhaust (000 §I): pilot ratio,
    /// cracking pressure and opening band (Pa), fully open orifice
    /// coefficient (m³/(s·√Pa)), damping bleed across the motor (m³/(s·Pa)).
    pub counterbalance_pilot_ratio: f64,
    pub counterbalance_crack_pa: f64,
    pub counterbalance_band_pa: f64,
    pub counterbalance_flow_gain: f64,
    pub counterbalance_bleed_m3_per_s_pa: f64,
    /// Hose between each servovalve port and its actuator: volume (m³),
    /// effective bulk modulus (Pa), inertance (kg/m⁴), laminar resistance (Pa·s/m³).
    pub line_volume_m3: f64,
    pub line_bulk_modulus_pa: f64,
    pub line_inertance_kg_per_m4: f64,
    pub line_resistance_pa_s_per_m3: f64,
    /// Lateral bending mode of each main link (Hz) and their damping ratio.
    pub boom_link1_hz: f64,
    pub boom_link2_hz: f64,
    pub boom_damping_ratio: f64,
}

impl Dynamics {
    /// What is wrong: (dotted field, message). Every number has a range
    /// (see `ranges.rs`): past it the simulator would not describe an arm,
    /// or its 1 ms RK4 step would not follow the dynamics.
    pub fn problems(&self) -> Vec<(String, String)> {
        use super::ranges::Range;
        const ARM: &str = "a truck-mounted arm of a few hundred kilograms";
        const HYD: &str = "industrial hydraulics of this size";
        const FRIC: &str = "friction well below the actuator's stall force";
        const STEP: &str = "dynamics the simulator's 1 ms RK4 step can follow";
        const SENS: &str = "a pressure transducer and ADC of a real controller";
        let d = |name: &str| format!("dynamics.{name}");
        let v = vec![
            Range::new(
                &d("base_inertia_kgm2"),
                self.base_inertia_kgm2,
                0.1,
                1e4,
                ARM,
            ),
            Range::new(
                &d("ee_inertia_kgm2"),
                self.ee_inertia_kgm2,
                0.01,
                100.0,
                ARM,
            ),
            Range::new(&d("cylinder_bore_m"), self.cylinder_bore_m, 0.01, 0.3, HYD),
            Range::new(&d("cylinder_rod_m"), self.cylinder_rod_m, 0.005, 0.3, HYD),
            Range::new(
                &d("cylinder_dead_volume_m3"),
                self.cylinder_dead_volume_m3,
                1e-5,
                0.01,
                HYD,
            ),
            Range::new(
                &d("cylinder_valve_flow_gain"),
                self.cylinder_valve_flow_gain,
                1e-9,
                1e-5,
                HYD,
            ),
            Range::new(
                &d("cylinder_command_limit"),
                self.cylinder_command_limit,
                0.01,
                1.0,
                "a fraction of the spool's full opening",
            ),
            Range::new(
                &d("valve_time_constant_s"),
                self.valve_time_constant_s,
                1e-3,
                0.1,
                "at least the simulator's 1 ms integration step",
            ),
            Range::new(
                &d("motor_off_command"),
                self.motor_off_command,
                -1.0,
                1.0,
                HYD,
            ),
            Range::new(
                &d("cylinder_off_command"),
                self.cylinder_off_command,
                -1.0,
                1.0,
                HYD,
            ),
            Range::new(
                &d("leakage_m3_per_s_pa"),
                self.leakage_m3_per_s_pa,
                0.0,
                1e-10,
                HYD,
            ),
            Range::new(
                &d("motor_viscous_nms_per_rad"),
                self.motor_viscous_nms_per_rad,
                0.0,
                1e4,
                FRIC,
            ),
            Range::new(
                &d("motor_coulomb_nm"),
                self.motor_coulomb_nm,
                0.0,
                1e3,
                FRIC,
            ),
            Range::new(
                &d("motor_stiction_nm"),
                self.motor_stiction_nm,
                0.0,
                1e3,
                FRIC,
            ),
            Range::new(
                &d("motor_stribeck_rad_per_s"),
                self.motor_stribeck_rad_per_s,
                1e-3,
                1.0,
                STEP,
            ),
            Range::new(
                &d("cylinder_viscous_ns_per_m"),
                self.cylinder_viscous_ns_per_m,
                0.0,
                1e5,
                FRIC,
            ),
            Range::new(
                &d("cylinder_coulomb_n"),
                self.cylinder_coulomb_n,
                0.0,
                1e4,
                FRIC,
            ),
            Range::new(
                &d("cylinder_stiction_n"),
                self.cylinder_stiction_n,
                0.0,
                1e4,
                FRIC,
            ),
            Range::new(
                &d("cylinder_stribeck_m_per_s"),
                self.cylinder_stribeck_m_per_s,
                1e-4,
                1.0,
                STEP,
            ),
            Range::new(&d("bulk_p_kappa_pa"), self.bulk_p_kappa_pa, 1e6, 1e8, HYD),
            Range::new(&d("relief_pa"), self.relief_pa, 1e6, 5e7, HYD),
            Range::new(
                &d("relief_gain_m3_per_s_pa"),
                self.relief_gain_m3_per_s_pa,
                1e-13,
                1e-8,
                STEP,
            ),
            Range::new(
                &d("yaw_bandwidth_rad_per_s"),
                self.yaw_bandwidth_rad_per_s,
                0.1,
                300.0,
                STEP,
            ),
            Range::new(
                &d("tilt_bandwidth_rad_per_s"),
                self.tilt_bandwidth_rad_per_s,
                0.1,
                300.0,
                STEP,
            ),
            Range::new(
                &d("vertical_bandwidth_rad_per_s"),
                self.vertical_bandwidth_rad_per_s,
                0.1,
                300.0,
                STEP,
            ),
            Range::new(
                &d("linkage_damping_ratio"),
                self.linkage_damping_ratio,
                1e-3,
                2.0,
                STEP,
            ),
            Range::new(
                &d("pressure_pa_per_volt"),
                self.pressure_pa_per_volt,
                1e5,
                1e8,
                SENS,
            ),
            Range::new(
                &d("pressure_offset_v"),
                self.pressure_offset_v,
                -10.0,
                10.0,
                SENS,
            ),
            Range::new(&d("adc_step_v"), self.adc_step_v, 1e-6, 0.1, SENS),
            Range::new(
                &d("accumulator_gas_m3"),
                self.accumulator_gas_m3,
                1e-4,
                0.1,
                HYD,
            ),
            Range::new(
                &d("accumulator_precharge_pa"),
                self.accumulator_precharge_pa,
                1e6,
                4e7,
                HYD,
            ),
            Range::new(
                &d("supply_volume_m3"),
                self.supply_volume_m3,
                1e-4,
                0.05,
                STEP,
            ),
            Range::new(&d("pump_flow_m3ps"), self.pump_flow_m3ps, 1e-5, 0.01, HYD),
            Range::new(&d("pump_band_pa"), self.pump_band_pa, 1e5, 1e7, HYD),
            Range::new(
                &d("supply_check_crack_pa"),
                self.supply_check_crack_pa,
                0.0,
                1e6,
                HYD,
            ),
            Range::new(
                &d("counterbalance_pilot_ratio"),
                self.counterbalance_pilot_ratio,
                1.0,
                20.0,
                HYD,
            ),
            Range::new(
                &d("counterbalance_crack_pa"),
                self.counterbalance_crack_pa,
                1e6,
                1e8,
                HYD,
            ),
            Range::new(
                &d("counterbalance_band_pa"),
                self.counterbalance_band_pa,
                1e5,
                5e7,
                HYD,
            ),
            Range::new(
                &d("counterbalance_flow_gain"),
                self.counterbalance_flow_gain,
                1e-9,
                1e-5,
                HYD,
            ),
            Range::new(
                &d("counterbalance_bleed_m3_per_s_pa"),
                self.counterbalance_bleed_m3_per_s_pa,
                0.0,
                1e-11,
                HYD,
            ),
            Range::new(&d("line_volume_m3"), self.line_volume_m3, 1e-5, 0.01, STEP),
            Range::new(
                &d("line_bulk_modulus_pa"),
                self.line_bulk_modulus_pa,
                1e8,
                2.5e9,
                HYD,
            ),
            Range::new(
                &d("line_inertance_kg_per_m4"),
                self.line_inertance_kg_per_m4,
                1e5,
                1e9,
                STEP,
            ),
            Range::new(
                &d("line_resistance_pa_s_per_m3"),
                self.line_resistance_pa_s_per_m3,
                0.0,
                1e10,
                HYD,
            ),
            Range::new(&d("boom_link1_hz"), self.boom_link1_hz, 0.5, 60.0, STEP),
            Range::new(&d("boom_link2_hz"), self.boom_link2_hz, 0.5, 60.0, STEP),
            Range::new(
                &d("boom_damping_ratio"),
                self.boom_damping_ratio,
                1e-3,
                1.0,
                STEP,
            ),
        ];
        let mut out = super::ranges::outside(v);
        // The hose's own resonance must stay where the 1 ms RK4 step follows
        // it: ω·h well inside RK4's 2.8 stability bound, with the chamber
        // coupled to it.
        let line_hz = (self.line_bulk_modulus_pa
            / (self.line_volume_m3 * self.line_inertance_kg_per_m4))
            .sqrt()
            / std::f64::consts::TAU;
        if line_hz > 250.0 {
            out.push((
                "dynamics.line_inertance_kg_per_m4".into(),
                format!(
                    "the hose resonates at {line_hz:.0} Hz (bulk modulus over volume × inertance), \
                     above the 250 Hz the simulator's 1 ms step can follow; a longer or wider hose \
                     (more volume or inertance) brings it down"
                ),
            ));
        }
        if self.cylinder_rod_m >= self.cylinder_bore_m {
            out.push((
                "dynamics.cylinder_rod_m".into(),
                format!(
                    "the rod ({} m) must be thinner than the bore ({} m)",
                    self.cylinder_rod_m, self.cylinder_bore_m
                ),
            ));
        }
        out
    }
}
