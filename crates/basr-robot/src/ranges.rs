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
            use basr_io::{show_apart, show_num};
            // The bound it misses with enough digits to tell them apart.
            let (value, lo, hi) = if r.value < r.lo {
                let (v, lo) = show_apart(r.value, r.lo);
                (v, lo, show_num(r.hi))
            } else {
                let (v, hi) = show_apart(r.value, r.hi);
                (v, show_num(r.lo), hi)
            };
            (
                r.path,
                format!(
                    "{value} is outside its valid range {lo}..={hi} ({}); use a value in that \
                     range",
                    r.why
                ),
            )
        })
        .collect()
}

const ARM: &str = "a road-marking arm of a few metres";
const SIM_STEP: &str =
    "the simulator samples the controller at its period and integrates in steps of about 1 ms";
const HYD: &str = "industrial hydraulics: supply up to 42 MPa";
const BULK: &str = "mineral oil with or without entrained air: 0.2–2.5 GPa (000 §II eq. 13)";
const SERVO: &str = "a servo the simulator's integration step can follow";
const ENC: &str = "an encoder or transducer of a real arm";
const PAINT: &str = "airless road paint (docs/robot.md)";
const LIM: &str = "a joint of a truck-mounted arm";

/// BASR's numbers outside `[dynamics]` with constant bounds, as data
/// (`[dynamics]`'s sit with its fields in `dynamics.rs`).
static BASR: &[Bound<Robot>] = &[
    Bound {
        field: "arm.a2_m",
        get: |r| r.arm.a2_m,
        lo: -0.5,
        hi: 0.5,
        why: ARM,
    },
    Bound {
        field: "arm.pantograph_ratio",
        get: |r| r.arm.pantograph_ratio,
        lo: 1.0,
        hi: 20.0,
        why: ARM,
    },
    Bound {
        field: "arm.retracted_extension_m",
        get: |r| r.arm.retracted_extension_m,
        lo: 0.2,
        hi: 10.0,
        why: ARM,
    },
    Bound {
        field: "arm.cylinder_stroke_m",
        get: |r| r.arm.cylinder_stroke_m,
        lo: 0.01,
        hi: 2.0,
        why: ARM,
    },
    // assumed: up to 5 cm of cylinder; the check against the stroke
    // itself follows in `problems`.
    Bound {
        field: "arm.cylinder_stroke_margin_m",
        get: |r| r.arm.cylinder_stroke_margin_m,
        lo: 0.0,
        hi: 0.05,
        why: ARM,
    },
    Bound {
        field: "arm.base_motor_ratio",
        get: |r| r.arm.base_motor_ratio,
        lo: 0.01,
        hi: 100.0,
        why: ARM,
    },
    Bound {
        field: "end_effector.mass_kg",
        get: |r| r.end_effector.mass_kg,
        lo: 1.0,
        hi: 500.0,
        why: ARM,
    },
    Bound {
        field: "end_effector.vertical_stroke_m",
        get: |r| r.end_effector.vertical_stroke_m,
        lo: 0.01,
        hi: 2.0,
        why: ARM,
    },
    Bound {
        field: "end_effector.vertical_disturbance_m",
        get: |r| r.end_effector.vertical_disturbance_m,
        lo: 1e-4,
        hi: 0.2,
        why: ARM,
    },
    Bound {
        field: "end_effector.vertical_disturbance_hz",
        get: |r| r.end_effector.vertical_disturbance_hz,
        lo: 0.1,
        hi: 100.0,
        why: SERVO,
    },
    Bound {
        field: "end_effector.tip_height_top_m",
        get: |r| r.end_effector.tip_height_top_m,
        lo: 0.01,
        hi: 3.0,
        why: ARM,
    },
    Bound {
        field: "end_effector.yaw_gear_ratio",
        get: |r| r.end_effector.yaw_gear_ratio,
        lo: 1.0,
        hi: 1000.0,
        why: ENC,
    },
    Bound {
        field: "end_effector.yaw_backlash_rad",
        get: |r| r.end_effector.yaw_backlash_rad,
        lo: 0.0,
        hi: 0.1,
        why: ENC,
    },
    Bound {
        field: "end_effector.tilt_screw_pitch_m",
        get: |r| r.end_effector.tilt_screw_pitch_m,
        lo: 1e-4,
        hi: 0.1,
        why: ENC,
    },
    Bound {
        field: "end_effector.tilt_motor_turns_per_screw_turn",
        get: |r| r.end_effector.tilt_motor_turns_per_screw_turn,
        lo: 0.01,
        hi: 100.0,
        why: ENC,
    },
    Bound {
        field: "end_effector.tilt_nut_max_speed_mps",
        get: |r| r.end_effector.tilt_nut_max_speed_mps,
        lo: 1e-3,
        hi: 10.0,
        why: SERVO,
    },
    Bound {
        field: "end_effector.nozzle_below_joint_f_m",
        get: |r| r.end_effector.nozzle_below_joint_f_m,
        lo: 0.05,
        hi: 5.0,
        why: ARM,
    },
    Bound {
        field: "end_effector.joint_f_test_torque_nm",
        get: |r| r.end_effector.joint_f_test_torque_nm,
        lo: 1.0,
        hi: 1e5,
        why: ARM,
    },
    Bound {
        field: "end_effector.fourbar.ground_m",
        get: |r| r.end_effector.fourbar.ground_m,
        lo: 0.01,
        hi: 2.0,
        why: ARM,
    },
    Bound {
        field: "end_effector.fourbar.coupler_m",
        get: |r| r.end_effector.fourbar.coupler_m,
        lo: 0.01,
        hi: 2.0,
        why: ARM,
    },
    Bound {
        field: "end_effector.fourbar.rocker_m",
        get: |r| r.end_effector.fourbar.rocker_m,
        lo: 0.01,
        hi: 2.0,
        why: ARM,
    },
    Bound {
        field: "end_effector.fourbar.tip_below_coupler_m",
        get: |r| r.end_effector.fourbar.tip_below_coupler_m,
        lo: 0.0,
        hi: 2.0,
        why: ARM,
    },
    Bound {
        field: "paint.flow_m3ps",
        get: |r| r.paint.flow_m3ps,
        lo: 1e-8,
        hi: 1e-3,
        why: PAINT,
    },
    Bound {
        field: "paint.transfer_efficiency",
        get: |r| r.paint.transfer_efficiency,
        lo: 0.01,
        hi: 1.0,
        why: PAINT,
    },
    Bound {
        field: "paint.film_m",
        get: |r| r.paint.film_m,
        lo: 1e-5,
        hi: 0.01,
        why: PAINT,
    },
    Bound {
        field: "paint.tip_life_min_m3",
        get: |r| r.paint.tip_life_min_m3,
        lo: 1e-4,
        hi: 10.0,
        why: PAINT,
    },
    Bound {
        field: "paint.tip_life_max_m3",
        get: |r| r.paint.tip_life_max_m3,
        lo: 1e-4,
        hi: 10.0,
        why: PAINT,
    },
    Bound {
        field: "control.period_s",
        get: |r| r.control.period_s,
        lo: 0.001,
        hi: 0.1,
        why: SIM_STEP,
    },
    Bound {
        field: "control.controller_sample_s",
        get: |r| r.control.controller_sample_s,
        lo: 0.001,
        hi: 0.05,
        why: SIM_STEP,
    },
    Bound {
        field: "control.accuracy_m",
        get: |r| r.control.accuracy_m,
        lo: 1e-4,
        hi: 0.1,
        why: ARM,
    },
    Bound {
        field: "encoders.base_counts_per_rev",
        get: |r| f64::from(r.encoders.base_counts_per_rev),
        lo: 100.0,
        hi: 1e8,
        why: ENC,
    },
    Bound {
        field: "encoders.extension_m_per_count",
        get: |r| r.encoders.extension_m_per_count,
        lo: 1e-7,
        hi: 0.01,
        why: ENC,
    },
    Bound {
        field: "encoders.yaw_counts_per_motor_rev",
        get: |r| f64::from(r.encoders.yaw_counts_per_motor_rev),
        lo: 1.0,
        hi: 1e7,
        why: ENC,
    },
    Bound {
        field: "encoders.tilt_counts_per_motor_rev",
        get: |r| f64::from(r.encoders.tilt_counts_per_motor_rev),
        lo: 1.0,
        hi: 1e7,
        why: ENC,
    },
    Bound {
        field: "encoders.vertical_m_per_count",
        get: |r| r.encoders.vertical_m_per_count,
        lo: 1e-7,
        hi: 0.01,
        why: ENC,
    },
    Bound {
        field: "hydraulics.supply_pa",
        get: |r| r.hydraulics.supply_pa,
        lo: 1e6,
        hi: 4.2e7,
        why: HYD,
    },
    Bound {
        field: "hydraulics.tank_pa",
        get: |r| r.hydraulics.tank_pa,
        lo: 0.0,
        hi: 1e6,
        why: HYD,
    },
    Bound {
        field: "hydraulics.bulk_modulus_pa",
        get: |r| r.hydraulics.bulk_modulus_pa,
        lo: 2e8,
        hi: 2.5e9,
        why: BULK,
    },
    Bound {
        field: "hydraulics.base_motor_displacement_m3prad",
        get: |r| r.hydraulics.base_motor_displacement_m3prad,
        lo: 1e-6,
        hi: 1e-3,
        why: HYD,
    },
    Bound {
        field: "hydraulics.base_chamber_a_m3",
        get: |r| r.hydraulics.base_chamber_a_m3,
        lo: 1e-5,
        hi: 0.01,
        why: HYD,
    },
    Bound {
        field: "hydraulics.base_chamber_b_m3",
        get: |r| r.hydraulics.base_chamber_b_m3,
        lo: 1e-5,
        hi: 0.01,
        why: HYD,
    },
    Bound {
        field: "hydraulics.valve_flow_gain",
        get: |r| r.hydraulics.valve_flow_gain,
        lo: 1e-9,
        hi: 1e-5,
        why: HYD,
    },
    Bound {
        field: "hydraulics.command_limit",
        get: |r| r.hydraulics.command_limit,
        lo: 0.01,
        hi: 1.0,
        why: "a fraction of the spool's full opening",
    },
    Bound {
        field: "hydraulics.gravity_b_n",
        get: |r| r.hydraulics.gravity_b_n,
        lo: 1.0,
        hi: 1e6,
        why: ARM,
    },
    Bound {
        field: "hydraulics.gravity_d_m",
        get: |r| r.hydraulics.gravity_d_m,
        lo: 0.05,
        hi: 5.0,
        why: ARM,
    },
    Bound {
        field: "hydraulics.gravity_x_min_m",
        get: |r| r.hydraulics.gravity_x_min_m,
        lo: 0.01,
        hi: 5.0,
        why: ARM,
    },
    Bound {
        field: "hydraulics.gravity_x_max_m",
        get: |r| r.hydraulics.gravity_x_max_m,
        lo: 0.01,
        hi: 5.0,
        why: ARM,
    },
];

/// Every out-of-range number of `r` outside `[dynamics]`.
pub(crate) fn problems(r: &Robot) -> Vec<(String, String)> {
    let a = &r.arm;
    let e = &r.end_effector;
    let p = &r.paint;
    let c = &r.control;
    let h = &r.hydraulics;
    let mut v = rows("", r, BASR);
    v.push(Range::new(
        "control.delay_estimate_s",
        c.delay_estimate_s,
        c.controller_sample_s,
        0.1,
        "at least one controller period and at most 0.1 s (000 §II eq. 21)",
    ));
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

/// One row of a range table: a number of `T` (dotted below the table's
/// prefix), its inclusive bounds and why they are there.
pub(crate) struct Bound<T: 'static> {
    pub field: &'static str,
    pub get: fn(&T) -> f64,
    pub lo: f64,
    pub hi: f64,
    pub why: &'static str,
}

/// A table's rows as [`Range`]s for `v`, each field as `prefix.field`.
pub(crate) fn rows<T>(prefix: &str, v: &T, table: &[Bound<T>]) -> Vec<Range> {
    table
        .iter()
        .map(|b| {
            let path = if prefix.is_empty() {
                b.field.to_string()
            } else {
                format!("{prefix}.{}", b.field)
            };
            Range::new(&path, (b.get)(v), b.lo, b.hi, b.why)
        })
        .collect()
}

const SERVO_JOINT: &str = "an electric servo joint of a truck-mounted arm";
const ELECTRIC_ARM: &str = "an arm of a few metres on a truck's rear";

/// The paint of every electric kind: the same bounds as BASR's.
pub(crate) static PAINT_RANGES: &[Bound<super::Paint>] = &[
    Bound {
        field: "fan_angle_rad",
        get: |p| p.fan_angle_rad,
        // A flat fan between 5° and 170°: 0 paints nothing, π is a plane.
        lo: 0.087,
        hi: 2.97,
        why: PAINT,
    },
    Bound {
        field: "flow_m3ps",
        get: |p| p.flow_m3ps,
        lo: 1e-8,
        hi: 1e-3,
        why: PAINT,
    },
    Bound {
        field: "transfer_efficiency",
        get: |p| p.transfer_efficiency,
        lo: 0.01,
        hi: 1.0,
        why: PAINT,
    },
    Bound {
        field: "film_m",
        get: |p| p.film_m,
        lo: 1e-5,
        hi: 0.01,
        why: PAINT,
    },
    Bound {
        field: "tip_life_min_m3",
        get: |p| p.tip_life_min_m3,
        lo: 1e-4,
        hi: 10.0,
        why: PAINT,
    },
    Bound {
        field: "tip_life_max_m3",
        get: |p| p.tip_life_max_m3,
        lo: 1e-4,
        hi: 10.0,
        why: PAINT,
    },
];

/// The control timing of every electric kind: BASR's bounds. A 1 ns
/// controller period is a billion simulated ticks a second (issue 31, R2:
/// `compile` ran past a minute).
pub(crate) static CONTROL_RANGES: &[Bound<super::Control>] = &[
    Bound {
        field: "period_s",
        get: |c| c.period_s,
        lo: 0.001,
        hi: 0.1,
        why: SIM_STEP,
    },
    Bound {
        field: "controller_sample_s",
        get: |c| c.controller_sample_s,
        lo: 0.001,
        hi: 0.05,
        why: SIM_STEP,
    },
    Bound {
        field: "delay_estimate_s",
        get: |c| c.delay_estimate_s,
        lo: 0.001,
        hi: 0.1,
        why: "at least one controller period and at most 0.1 s (000 §II eq. 21)",
    },
    Bound {
        field: "accuracy_m",
        get: |c| c.accuracy_m,
        lo: 1e-4,
        hi: 0.1,
        why: ARM,
    },
];

/// Every number of one servo joint table. The position bounds are wide
/// (±13 rad: two turns either way, as BASR's; strokes to 20 m) and the
/// joint's own range is checked against them separately.
pub(crate) static SERVO_RANGES: &[Bound<super::kind::ServoJoint>] = &[
    Bound {
        field: "min",
        get: |j| j.min,
        lo: -13.0,
        hi: 20.0,
        why: SERVO_JOINT,
    },
    Bound {
        field: "max",
        get: |j| j.max,
        lo: -13.0,
        hi: 20.0,
        why: SERVO_JOINT,
    },
    // A joint 10^4 times slower than the shipped ones (0.5 rad/s) would take
    // hours per letter; the planner samples every millisecond of that
    // (issue 31, R3: 1e-12 rad/s asked 84 TB).
    Bound {
        field: "max_vel",
        get: |j| j.max_vel,
        lo: 1e-4,
        hi: 100.0,
        why: SERVO_JOINT,
    },
    Bound {
        field: "max_acc",
        get: |j| j.max_acc,
        lo: 1e-4,
        hi: 1e4,
        why: SERVO_JOINT,
    },
    // From one count a radian (or metre) to 10^10: a 32-bit absolute
    // encoder through a 1000:1 gear is 6.8e8 per radian. Over the widest
    // joint range (20) that is 2e11 counts, far inside the i64 the counts
    // are written as (issue 31, R5: 1e300 saturated every count at i64::MAX).
    Bound {
        field: "counts_per_unit",
        get: |j| j.counts_per_unit,
        lo: 1.0,
        hi: 1e10,
        why: ENC,
    },
    Bound {
        field: "inertia",
        get: |j| j.inertia,
        lo: 1e-6,
        hi: 1e6,
        why: SERVO_JOINT,
    },
    Bound {
        field: "max_effort",
        get: |j| j.max_effort,
        lo: 1e-3,
        hi: 1e7,
        why: SERVO_JOINT,
    },
];

/// The telescopic arm's dimensions (seed 002's DH parameters and the head).
pub(crate) static TELESCOPIC_ARM: &[Bound<super::telescopic::TelescopicArm>] = &[
    Bound {
        field: "base_height_m",
        get: |a| a.base_height_m,
        lo: 0.1,
        hi: 10.0,
        why: ELECTRIC_ARM,
    },
    Bound {
        field: "a1_m",
        get: |a| a.a1_m,
        lo: 1e-3,
        hi: 5.0,
        why: "002's eq. 1 needs an offset between the first two axes (0.05 m will do)",
    },
    Bound {
        field: "alpha1_rad",
        get: |a| a.alpha1_rad,
        lo: -std::f64::consts::PI,
        hi: std::f64::consts::PI,
        why: "an angle of one turn",
    },
    Bound {
        field: "h2_m",
        get: |a| a.h2_m,
        lo: -5.0,
        hi: 5.0,
        why: ELECTRIC_ARM,
    },
    Bound {
        field: "a2_m",
        get: |a| a.a2_m,
        lo: 0.0,
        hi: 5.0,
        why: ELECTRIC_ARM,
    },
    Bound {
        field: "alpha2_rad",
        get: |a| a.alpha2_rad,
        lo: -std::f64::consts::PI,
        hi: std::f64::consts::PI,
        why: "an angle of one turn",
    },
    Bound {
        field: "nozzle_m",
        get: |a| a.nozzle_m,
        lo: 0.01,
        hi: 5.0,
        why: ELECTRIC_ARM,
    },
    Bound {
        field: "tip_height_min_m",
        get: |a| a.tip_height_min_m,
        lo: 1e-3,
        hi: 3.0,
        why: ELECTRIC_ARM,
    },
    Bound {
        field: "tip_height_max_m",
        get: |a| a.tip_height_max_m,
        lo: 1e-3,
        hi: 3.0,
        why: ELECTRIC_ARM,
    },
];

/// The articulated arm's dimensions (seed 003's links).
pub(crate) static ARTICULATED_ARM: &[Bound<super::articulated::ArticulatedArm>] = &[
    Bound {
        field: "shoulder_height_m",
        get: |a| a.shoulder_height_m,
        lo: 0.1,
        hi: 10.0,
        why: ELECTRIC_ARM,
    },
    Bound {
        field: "shoulder_offset_m",
        get: |a| a.shoulder_offset_m,
        lo: -5.0,
        hi: 5.0,
        why: ELECTRIC_ARM,
    },
    Bound {
        field: "upper_arm_m",
        get: |a| a.upper_arm_m,
        lo: 0.05,
        hi: 20.0,
        why: ELECTRIC_ARM,
    },
    Bound {
        field: "forearm_m",
        get: |a| a.forearm_m,
        lo: 0.05,
        hi: 20.0,
        why: ELECTRIC_ARM,
    },
    Bound {
        field: "gun_m",
        get: |a| a.gun_m,
        lo: 0.01,
        hi: 5.0,
        why: ELECTRIC_ARM,
    },
    Bound {
        field: "tip_height_min_m",
        get: |a| a.tip_height_min_m,
        lo: 1e-3,
        hi: 3.0,
        why: ELECTRIC_ARM,
    },
    Bound {
        field: "tip_height_max_m",
        get: |a| a.tip_height_max_m,
        lo: 1e-3,
        hi: 3.0,
        why: ELECTRIC_ARM,
    },
];

/// Every out-of-range number of an electric kind's shared tables: paint,
/// control and each joint (`names`: the joints' table names), and the
/// cross-check a row cannot say: the delay estimate is at least one
/// controller period.
pub(crate) fn electric(
    paint: &super::Paint,
    control: &super::Control,
    names: &[&str; 5],
    joints: [&super::kind::ServoJoint; 5],
) -> Vec<(String, String)> {
    let mut v = rows("paint", paint, PAINT_RANGES);
    v.extend(rows("control", control, CONTROL_RANGES));
    for (name, j) in names.iter().zip(joints) {
        v.extend(rows(&format!("joints.{name}"), j, SERVO_RANGES));
    }
    let mut out = outside(v);
    if control.delay_estimate_s < control.controller_sample_s {
        out.push((
            "control.delay_estimate_s".into(),
            format!(
                "{} s is shorter than one controller period (control.controller_sample_s = {} \
                 s); give at least that (000 §II eq. 21)",
                basr_io::show_num(control.delay_estimate_s),
                basr_io::show_num(control.controller_sample_s)
            ),
        ));
    }
    out
}
