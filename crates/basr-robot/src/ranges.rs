//! The validated range of every number of a robot description outside
//! `[dynamics]` (whose ranges sit with its fields in `dynamics.rs`): values
//! past these either describe no road-marking arm or would hang, overflow
//! or destabilise the simulator and the planner (a 1 ns controller period
//! is a billion control ticks a second; a 1e308 Pa bulk modulus overflows
//! the pressure rates). Each bound says why it is where it is; the
//! default robot sits well inside all of them.

use super::Robot;

/// One range: dotted field, value, inclusive bounds, why.
pub(crate) struct Range {
    pub path: String,
    pub value: f64,
    pub lo: f64,
    pub hi: f64,
    pub why: &'static str,
}

impl Range {
    pub(crate) fn new(path: &str, value: f64, lo: f64, hi: f64, why: &'static str) -> Range {
        Range {
            path: path.into(),
            value,
            lo,
            hi,
            why,
        }
    }
}

/// (dotted field, message) for every range in `ranges` its value is outside.
pub(crate) fn outside(ranges: Vec<Range>) -> Vec<(String, String)> {
    ranges
        .into_iter()
        .filter(|r| !(r.value >= r.lo && r.value <= r.hi))
        .map(|r| {
            (
                r.path,
                format!(
                    "{} is outside its valid range {}..={} ({}); use a value in that range",
                    r.value, r.lo, r.hi, r.why
                ),
            )
        })
        .collect()
}

const ARM: &str = "a road-marking arm of a few metres";
const SIM_STEP: &str = "the simulator integrates at 1 ms and samples the controller at its period";
const HYD: &str = "industrial hydraulics: supply up to 42 MPa";
const BULK: &str = "mineral oil with or without entrained air: 0.2–2.5 GPa (000 §II eq. 13)";
const SERVO: &str = "a servo the 1 ms integrator can follow";
const ENC: &str = "an encoder or transducer of a real arm";
const PAINT: &str = "airless road paint (SPEC §4)";
const LIM: &str = "a joint of a truck-mounted arm";

/// Every out-of-range number of `r` outside `[dynamics]`.
pub(crate) fn problems(r: &Robot) -> Vec<(String, String)> {
    let a = &r.arm;
    let e = &r.end_effector;
    let f = &e.fourbar;
    let p = &r.paint;
    let c = &r.control;
    let n = &r.encoders;
    let h = &r.hydraulics;
    let mut v = vec![
        Range::new("arm.a2_m", a.a2_m, -0.5, 0.5, ARM),
        Range::new("arm.pantograph_ratio", a.pantograph_ratio, 1.0, 20.0, ARM),
        Range::new(
            "arm.retracted_extension_m",
            a.retracted_extension_m,
            0.2,
            10.0,
            ARM,
        ),
        Range::new("arm.cylinder_stroke_m", a.cylinder_stroke_m, 0.01, 2.0, ARM),
        // assumed: up to 5 cm of cylinder; the check against the stroke
        // itself follows below.
        Range::new(
            "arm.cylinder_stroke_margin_m",
            a.cylinder_stroke_margin_m,
            0.0,
            0.05,
            ARM,
        ),
        Range::new("arm.base_motor_ratio", a.base_motor_ratio, 0.01, 100.0, ARM),
        Range::new("end_effector.mass_kg", e.mass_kg, 1.0, 500.0, ARM),
        Range::new(
            "end_effector.vertical_stroke_m",
            e.vertical_stroke_m,
            0.01,
            2.0,
            ARM,
        ),
        Range::new(
            "end_effector.vertical_disturbance_m",
            e.vertical_disturbance_m,
            1e-4,
            0.2,
            ARM,
        ),
        Range::new(
            "end_effector.vertical_disturbance_hz",
            e.vertical_disturbance_hz,
            0.1,
            100.0,
            SERVO,
        ),
        Range::new(
            "end_effector.tip_height_top_m",
            e.tip_height_top_m,
            0.01,
            3.0,
            ARM,
        ),
        Range::new(
            "end_effector.yaw_gear_ratio",
            e.yaw_gear_ratio,
            1.0,
            1000.0,
            ENC,
        ),
        Range::new(
            "end_effector.yaw_backlash_rad",
            e.yaw_backlash_rad,
            0.0,
            0.1,
            ENC,
        ),
        Range::new(
            "end_effector.tilt_screw_pitch_m",
            e.tilt_screw_pitch_m,
            1e-4,
            0.1,
            ENC,
        ),
        Range::new(
            "end_effector.tilt_motor_turns_per_screw_turn",
            e.tilt_motor_turns_per_screw_turn,
            0.01,
            100.0,
            ENC,
        ),
        Range::new(
            "end_effector.tilt_nut_max_speed_mps",
            e.tilt_nut_max_speed_mps,
            1e-3,
            10.0,
            SERVO,
        ),
        Range::new(
            "end_effector.nozzle_below_joint_f_m",
            e.nozzle_below_joint_f_m,
            0.05,
            5.0,
            ARM,
        ),
        Range::new(
            "end_effector.joint_f_test_torque_nm",
            e.joint_f_test_torque_nm,
            1.0,
            1e5,
            ARM,
        ),
        Range::new("end_effector.fourbar.ground_m", f.ground_m, 0.01, 2.0, ARM),
        Range::new(
            "end_effector.fourbar.coupler_m",
            f.coupler_m,
            0.01,
            2.0,
            ARM,
        ),
        Range::new("end_effector.fourbar.rocker_m", f.rocker_m, 0.01, 2.0, ARM),
        Range::new(
            "end_effector.fourbar.tip_below_coupler_m",
            f.tip_below_coupler_m,
            0.0,
            2.0,
            ARM,
        ),
        Range::new("paint.flow_m3ps", p.flow_m3ps, 1e-8, 1e-3, PAINT),
        Range::new(
            "paint.transfer_efficiency",
            p.transfer_efficiency,
            0.01,
            1.0,
            PAINT,
        ),
        Range::new("paint.film_m", p.film_m, 1e-5, 0.01, PAINT),
        Range::new(
            "paint.tip_life_min_m3",
            p.tip_life_min_m3,
            1e-4,
            10.0,
            PAINT,
        ),
        Range::new(
            "paint.tip_life_max_m3",
            p.tip_life_max_m3,
            1e-4,
            10.0,
            PAINT,
        ),
        Range::new("control.period_s", c.period_s, 0.001, 0.1, SIM_STEP),
        Range::new(
            "control.controller_sample_s",
            c.controller_sample_s,
            0.001,
            0.05,
            SIM_STEP,
        ),
        Range::new(
            "control.delay_estimate_s",
            c.delay_estimate_s,
            c.controller_sample_s,
            0.1,
            "at least one controller period and at most 0.1 s (000 §II eq. 21)",
        ),
        Range::new("control.accuracy_m", c.accuracy_m, 1e-4, 0.1, ARM),
        Range::new(
            "encoders.base_counts_per_rev",
            n.base_counts_per_rev.into(),
            100.0,
            1e8,
            ENC,
        ),
        Range::new(
            "encoders.extension_m_per_count",
            n.extension_m_per_count,
            1e-7,
            0.01,
            ENC,
        ),
        Range::new(
            "encoders.yaw_counts_per_motor_rev",
            n.yaw_counts_per_motor_rev.into(),
            1.0,
            1e7,
            ENC,
        ),
        Range::new(
            "encoders.tilt_counts_per_motor_rev",
            n.tilt_counts_per_motor_rev.into(),
            1.0,
            1e7,
            ENC,
        ),
        Range::new(
            "encoders.vertical_m_per_count",
            n.vertical_m_per_count,
            1e-7,
            0.01,
            ENC,
        ),
        Range::new("hydraulics.supply_pa", h.supply_pa, 1e6, 4.2e7, HYD),
        Range::new("hydraulics.tank_pa", h.tank_pa, 0.0, 1e6, HYD),
        Range::new(
            "hydraulics.bulk_modulus_pa",
            h.bulk_modulus_pa,
            2e8,
            2.5e9,
            BULK,
        ),
        Range::new(
            "hydraulics.base_motor_displacement_m3prad",
            h.base_motor_displacement_m3prad,
            1e-6,
            1e-3,
            HYD,
        ),
        Range::new(
            "hydraulics.base_chamber_a_m3",
            h.base_chamber_a_m3,
            1e-5,
            0.01,
            HYD,
        ),
        Range::new(
            "hydraulics.base_chamber_b_m3",
            h.base_chamber_b_m3,
            1e-5,
            0.01,
            HYD,
        ),
        Range::new(
            "hydraulics.valve_flow_gain",
            h.valve_flow_gain,
            1e-9,
            1e-5,
            HYD,
        ),
        Range::new(
            "hydraulics.command_limit",
            h.command_limit,
            0.01,
            1.0,
            "a fraction of the spool's full opening",
        ),
        Range::new("hydraulics.gravity_b_n", h.gravity_b_n, 1.0, 1e6, ARM),
        Range::new("hydraulics.gravity_d_m", h.gravity_d_m, 0.05, 5.0, ARM),
        Range::new(
            "hydraulics.gravity_x_min_m",
            h.gravity_x_min_m,
            0.01,
            5.0,
            ARM,
        ),
        Range::new(
            "hydraulics.gravity_x_max_m",
            h.gravity_x_max_m,
            0.01,
            5.0,
            ARM,
        ),
    ];
    for (i, d) in e.joint_f_deflection_rad.iter().enumerate() {
        v.push(Range::new(
            &format!("end_effector.joint_f_deflection_rad[{i}]"),
            *d,
            0.0,
            0.1,
            ARM,
        ));
    }
    for (i, x) in e.joint_f_deflection_extension_m.iter().enumerate() {
        v.push(Range::new(
            &format!("end_effector.joint_f_deflection_extension_m[{i}]"),
            *x,
            0.0,
            20.0,
            ARM,
        ));
    }
    if let Some(c0) = p.height_law_c0_m {
        v.push(Range::new("paint.height_law_c0_m", c0, -1.0, 1.0, PAINT));
    }
    if let Some(c1) = p.height_law_c1 {
        v.push(Range::new("paint.height_law_c1", c1, 1e-3, 100.0, PAINT));
    }
    let pos = |name: &str| -> (f64, f64) {
        match name {
            "base_rot_rad" | "ee_yaw_rad" => (-13.0, 13.0),
            "tilt_rad" => (-1.5, 1.5),
            _ => (0.0, 20.0),
        }
    };
    for (name, l) in r.limits.iter() {
        let (lo, hi) = pos(name);
        v.push(Range::new(
            &format!("limits.{name}.min"),
            l.min,
            lo,
            hi,
            LIM,
        ));
        v.push(Range::new(
            &format!("limits.{name}.max"),
            l.max,
            lo,
            hi,
            LIM,
        ));
        v.push(Range::new(
            &format!("limits.{name}.max_vel"),
            l.max_vel,
            1e-4,
            100.0,
            LIM,
        ));
        v.push(Range::new(
            &format!("limits.{name}.max_acc"),
            l.max_acc,
            1e-4,
            1e4,
            LIM,
        ));
    }
    let mut out = outside(v);
    if a.cylinder_stroke_margin_m * 4.0 >= a.cylinder_stroke_m {
        out.push((
            "arm.cylinder_stroke_margin_m".into(),
            format!(
                "{} m leaves too little of the {} m cylinder stroke to plan in; keep it under a \
                 quarter of the stroke",
                a.cylinder_stroke_margin_m, a.cylinder_stroke_m
            ),
        ));
    }
    // The pantograph must stay open over the cylinder's stroke: the links
    // rise as √(4d² − x²) (000 app. A eq. 4), so x_min + stroke < 2d.
    let x_end = h.gravity_x_min_m + a.cylinder_stroke_m;
    if x_end >= 2.0 * h.gravity_d_m {
        out.push((
            "arm.cylinder_stroke_m".into(),
            format!(
                "{} m of stroke from hydraulics.gravity_x_min_m {} m reaches x = {x_end} m, at or \
                 past 2·gravity_d_m = {} m where the pantograph folds flat; shorten the stroke",
                a.cylinder_stroke_m,
                h.gravity_x_min_m,
                2.0 * h.gravity_d_m
            ),
        ));
    }
    out
}
