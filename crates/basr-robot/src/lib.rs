//! # basr-robot
//!
//! Robot descriptions of every kind behind one `ArmKind` trait, their kinematics, limits, paint law, workspace and design. Imports `basr-io` only; never the job, the planner or the simulator. The workspace's crates are the pipeline (docs/architecture.md).
//!
//! ```
//! use basr_robot::{AnyRobot, NozzlePose};
//!
//! // The embedded BASR: the nozzle 3 m straight back, 0.1 m over the road,
//! // its fan across the arm, untilted.
//! let robot = AnyRobot::load_or_default(None).unwrap();
//! let pose = NozzlePose { x_m: 0.0, y_m: 3.0, z_m: 0.1, yaw_rad: 0.0, tilt_rad: 0.0 };
//! let solutions = robot.ik(&pose).unwrap();
//! assert!(!solutions.is_empty());
//! ```
//!
//! Robot description (TOML, validated, hashed) and its kinematics: nozzle
//! pose ↔ joints ↔ actuators ↔ encoders, the tilt four-bar, limits and the
//! reachable workspace. The default robot is BASR (`robots/basr.toml`).
//!
//! The description is an immutable model (DESIGN: model apart from state);
//! every computation takes it by reference.

pub mod any;
pub mod articulated;
pub mod design;
pub mod dynamics;
pub mod envelope;
pub mod facts;
pub mod fourbar;
pub mod kind;
pub mod kinematics;
pub mod paint_law;
pub mod reach;
pub mod section;
pub mod telescopic;
pub mod workspace;

mod describe;
mod ranges;

pub use describe::{check_source, RobotError};
pub use dynamics::Dynamics;
pub use facts::{AirEnd, RowJoints, SampledFault};
pub use fourbar::FourBar;
pub use kind::{AnyRobot, ArmKind, Kind, ServoJoint, Q};
pub use kinematics::{Actuators, Encoders, Joints, NozzlePose, RateViolation, Unreachable};
pub use workspace::Region;

use serde::{Deserialize, Serialize};

/// The embedded default description (SPEC §4).
pub const BASR_TOML: &str = include_str!("../../../robots/basr.toml");

/// Whether a text that may not parse as TOML looks like a robot description
/// (has an `[arm]` table header), so its syntax errors can be reported.
pub fn looks_like_robot(text: &str) -> bool {
    text.lines().any(|l| l.trim() == "[arm]")
}

/// The immutable description of one robot. One field per TOML section.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Robot {
    pub name: String,
    /// Always BASR here (SPEC §8); other kinds are [`AnyRobot`]'s.
    #[serde(default, skip_serializing_if = "Kind::is_basr")]
    pub kind: Kind,
    pub arm: Arm,
    pub end_effector: EndEffector,
    pub paint: Paint,
    pub control: Control,
    pub encoders: EncoderScales,
    pub hydraulics: Hydraulics,
    pub limits: Limits,
    /// What `basr simulate` needs beyond kinematics (src/robot/dynamics.rs).
    pub dynamics: Dynamics,
    /// How the truck moves between stations (the job's truck phases).
    #[serde(default)]
    pub truck: Truck,
}

/// The truck's move from one station to the next, with the arm stowed.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Truck {
    /// Creeping speed between stations (m/s). assumed: no source gives it;
    /// 0.5 m/s (1.8 km/h), a walking pace for a truck edging along a lane
    /// with a crew beside it.
    pub speed_mps: f64,
    /// Time from the truck stopping to the arm leaving stow (s). assumed: no
    /// source gives it; 3 s for the brakes to set and the chassis to stop
    /// rocking.
    pub settle_s: f64,
}

impl Default for Truck {
    fn default() -> Truck {
        Truck {
            speed_mps: 0.5, // assumed, see the field
            settle_s: 3.0,  // assumed, see the field
        }
    }
}

/// The pantograph arm on its rotating base (SPEC §2, §4).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Arm {
    /// Offset a2 between the arm and the end-effector's yaw axis.
    pub a2_m: f64,
    /// Extension R per metre of cylinder stroke.
    pub pantograph_ratio: f64,
    /// R with the cylinder fully retracted (encoder zero).
    pub retracted_extension_m: f64,
    /// Full cylinder stroke.
    pub cylinder_stroke_m: f64,
    /// Cylinder stroke kept clear of the extended end stop: the planner's
    /// extension limit (`limits.extension_m.max`) must lie inside the
    /// stroke by this much. 0 where a description does not give it.
    #[serde(default)]
    pub cylinder_stroke_margin_m: f64,
    /// Hydraulic-motor radians per radian of base rotation.
    pub base_motor_ratio: f64,
}

/// Yaw, vertical and tilt joints carrying the spray gun.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EndEffector {
    pub mass_kg: f64,
    pub vertical_stroke_m: f64,
    /// Amplitude and frequency of the disturbances the vertical joint follows.
    pub vertical_disturbance_m: f64,
    pub vertical_disturbance_hz: f64,
    /// Tip height over the road at the top of the vertical stroke, zero tilt.
    pub tip_height_top_m: f64,
    pub yaw_gear_ratio: f64,
    pub yaw_backlash_rad: f64,
    pub tilt_screw_pitch_m: f64,
    pub tilt_motor_turns_per_screw_turn: f64,
    pub tilt_nut_max_speed_mps: f64,
    pub nozzle_below_joint_f_m: f64,
    pub joint_f_test_torque_nm: f64,
    /// Extensions at which the joint-F deflection was measured (increasing).
    pub joint_f_deflection_extension_m: Vec<f64>,
    /// Joint-F deflection under the test torque at those extensions.
    pub joint_f_deflection_rad: Vec<f64>,
    pub fourbar: FourBar,
}

/// Spray nozzle and paint (SPEC §3 `paint`, §4).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Paint {
    pub fan_angle_rad: f64,
    pub flow_m3ps: f64,
    pub transfer_efficiency: f64,
    pub film_m: f64,
    pub tip_life_min_m3: f64,
    pub tip_life_max_m3: f64,
    /// Calibrated height law h = c0 + c1·w (both or neither).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height_law_c0_m: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height_law_c1: Option<f64>,
    /// Flux across the fan of the tip these figures describe, as `basr
    /// preview --profile` takes it (`uniform`, `uniform-angle`,
    /// `gauss[:w,mean,sigma;…]`, `beta[:p,q]`); absent: `uniform`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profile: Option<String>,
    /// The listed tip the figures above are (set by compile when it chooses
    /// one of `tip`); absent for a robot without `[[paint.tip]]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mounted: Option<String>,
    /// The tips the crew carries (`[[paint.tip]]`); empty: one tip, this table.
    #[serde(default, rename = "tip", skip_serializing_if = "Vec::is_empty")]
    pub tips: Vec<Tip>,
}

/// One spray tip the crew carries (`[[paint.tip]]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Tip {
    /// The crew's name for it (often the tip code, e.g. `517`).
    pub name: String,
    /// Full fan angle, degrees (the tip codes' unit: first digit × 2 = fan
    /// width in inches at 12 in).
    pub fan_angle_deg: f64,
    /// Paint flow at the working pressure.
    pub flow_m3ps: f64,
    /// Flux across the fan, as [`Paint::profile`]; absent: `uniform`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profile: Option<String>,
}

/// The profile kinds `basr preview --profile` takes (their parameters are
/// checked where the spray model is built).
pub const PROFILE_KINDS: [&str; 4] = ["uniform", "uniform-angle", "gauss", "beta"];

impl Tip {
    /// Fan angle in radians.
    pub fn fan_angle_rad(&self) -> f64 {
        self.fan_angle_deg.to_radians()
    }
}

/// `profile`'s problem, if its kind is none `preview --profile` takes.
fn profile_problem(profile: &str) -> Option<String> {
    let kind = profile.split_once(':').map_or(profile, |(k, _)| k).trim();
    (!PROFILE_KINDS.contains(&kind)).then(|| {
        format!(
            "profile {profile:?} is none of {} (as `basr preview --profile` takes them)",
            PROFILE_KINDS.join(", ")
        )
    })
}

impl Paint {
    /// The profile these figures describe (`uniform` when none is given).
    pub fn profile_text(&self) -> &str {
        self.profile.as_deref().unwrap_or("uniform")
    }

    /// These paint figures with `tip` mounted: its fan angle, flow and
    /// profile, and its name in `mounted`.
    pub fn with_tip(&self, tip: &Tip) -> Paint {
        Paint {
            fan_angle_rad: tip.fan_angle_rad(),
            flow_m3ps: tip.flow_m3ps,
            profile: tip.profile.clone(),
            mounted: Some(tip.name.clone()),
            ..self.clone()
        }
    }

    /// The listed tip named `name`.
    pub fn tip(&self, name: &str) -> Option<&Tip> {
        self.tips.iter().find(|t| t.name == name)
    }

    /// Problems of the profile and the `[[paint.tip]]` list, as
    /// `(field, what)`.
    pub fn tip_problems(&self) -> Vec<(String, String)> {
        let mut out = Vec::new();
        if let Some(why) = self.profile.as_deref().and_then(profile_problem) {
            out.push(("paint.profile".into(), why));
        }
        for (i, t) in self.tips.iter().enumerate() {
            let at = |f: &str| format!("paint.tip[{i}].{f}");
            if t.name.trim().is_empty() {
                out.push((
                    at("name"),
                    "must not be empty: give the crew's name for the tip, e.g. \"517\"".into(),
                ));
            }
            if self.tips[..i].iter().any(|o| o.name == t.name) {
                out.push((
                    at("name"),
                    format!("{:?} is listed twice; each tip needs its own name", t.name),
                ));
            }
            // A flat fan between 5° and 120°: the codes go from 0 (a pencil
            // stream) to 9 (18 in at 12 in, 74°); the spray model needs
            // the fan's edge well above the road.
            if !(t.fan_angle_deg.is_finite() && (5.0..=120.0).contains(&t.fan_angle_deg)) {
                out.push((at("fan_angle_deg"), format!("must be 5 to 120 degrees (got {}); tip codes: first digit × 2 = fan width in inches at 12 in, e.g. 5 → 10 in → 45.2°", basr_io::show_num(t.fan_angle_deg))));
            }
            if !(t.flow_m3ps.is_finite() && (1e-8..=1e-3).contains(&t.flow_m3ps)) {
                out.push((
                    at("flow_m3ps"),
                    format!(
                        "must be 1e-8 to 1e-3 m³/s (got {}); 0.4 L/min is 6.67e-6",
                        basr_io::show_num(t.flow_m3ps)
                    ),
                ));
            }
            if let Some(why) = t.profile.as_deref().and_then(profile_problem) {
                out.push((at("profile"), why));
            }
        }
        if let Some(m) = &self.mounted {
            match self.tip(m) {
                None if !self.tips.is_empty() => out.push((
                    "paint.mounted".into(),
                    format!("names tip {m:?}, which no [[paint.tip]] lists"),
                )),
                // The job plans with [paint]'s figures and names the
                // mounted tip to the crew: they must be that tip's, or the
                // crew mounts one tip for a job planned for another's fan.
                Some(t) => {
                    let near = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(b.abs());
                    let tip = self.with_tip(t);
                    if !near(self.fan_angle_rad, tip.fan_angle_rad)
                        || !near(self.flow_m3ps, tip.flow_m3ps)
                        || self.profile_text() != tip.profile_text()
                    {
                        out.push((
                            "paint.mounted".into(),
                            format!(
                                "names tip {m:?}, but [paint]'s fan ({:.2}°, {} m³/s, profile {}) is \
                                 not that tip's ({:.2}°, {} m³/s, profile {}): give [paint] the \
                                 tip's figures, or remove `mounted` to let compile choose among \
                                 the tips",
                                self.fan_angle_rad.to_degrees(),
                                basr_io::show_num(self.flow_m3ps),
                                self.profile_text(),
                                tip.fan_angle_rad.to_degrees(),
                                basr_io::show_num(tip.flow_m3ps),
                                tip.profile_text()
                            ),
                        ));
                    }
                }
                None => {}
            }
        }
        out
    }

    /// k = flow·efficiency/film: speed × stroke width (001 eq. 2.6; SPEC §3).
    pub fn k_m2ps(&self) -> f64 {
        self.flow_m3ps * self.transfer_efficiency / self.film_m
    }

    /// Tip height painting a stroke `width_m` wide at zero tilt: the
    /// calibrated law when given, else h = (w/2)/tan(α/2) (001 eq. 2.5).
    pub fn height_for_width_m(&self, width_m: f64) -> f64 {
        match (self.height_law_c0_m, self.height_law_c1) {
            (Some(c0), Some(c1)) => c0 + c1 * width_m,
            _ => 0.5 * width_m / (0.5 * self.fan_angle_rad).tan(),
        }
    }
}

/// Control timing and accuracy.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Control {
    /// Setpoint period of the job.
    pub period_s: f64,
    pub controller_sample_s: f64,
    pub delay_estimate_s: f64,
    /// Required end-point accuracy.
    pub accuracy_m: f64,
}

/// Encoder scales (SPEC §4).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EncoderScales {
    pub base_counts_per_rev: u32,
    pub extension_m_per_count: f64,
    pub yaw_counts_per_motor_rev: u32,
    pub tilt_counts_per_motor_rev: u32,
    pub vertical_m_per_count: f64,
}

/// Hydraulic numbers of SPEC §4, listed for the simulator.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Hydraulics {
    pub supply_pa: f64,
    pub tank_pa: f64,
    pub bulk_modulus_pa: f64,
    pub base_motor_displacement_m3prad: f64,
    pub base_chamber_a_m3: f64,
    pub base_chamber_b_m3: f64,
    pub valve_flow_gain: f64,
    pub command_limit: f64,
    pub gravity_b_n: f64,
    pub gravity_d_m: f64,
    pub gravity_x_min_m: f64,
    pub gravity_x_max_m: f64,
}

/// Range, speed and acceleration limits of one joint (SI units of the joint).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointLimit {
    pub min: f64,
    pub max: f64,
    pub max_vel: f64,
    pub max_acc: f64,
}

impl JointLimit {
    /// How far `value` lies outside [min, max] (0 inside).
    pub fn excess(&self, value: f64) -> f64 {
        if value < self.min {
            self.min - value
        } else if value > self.max {
            value - self.max
        } else {
            0.0
        }
    }

    pub fn contains(&self, value: f64) -> bool {
        value >= self.min && value <= self.max
    }
}

/// Per-joint limits, keyed by the joints' CSV column names.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Limits {
    pub base_rot_rad: JointLimit,
    pub extension_m: JointLimit,
    pub vertical_m: JointLimit,
    pub ee_yaw_rad: JointLimit,
    pub tilt_rad: JointLimit,
}

impl Limits {
    /// Joint names in CSV column order.
    pub const NAMES: [&'static str; 5] = [
        "base_rot_rad",
        "extension_m",
        "vertical_m",
        "ee_yaw_rad",
        "tilt_rad",
    ];

    /// (name, limit) in CSV column order.
    pub fn iter(&self) -> impl Iterator<Item = (&'static str, &JointLimit)> {
        Self::NAMES.into_iter().zip([
            &self.base_rot_rad,
            &self.extension_m,
            &self.vertical_m,
            &self.ee_yaw_rad,
            &self.tilt_rad,
        ])
    }

    /// The limit of a joint by its CSV name.
    pub fn get(&self, name: &str) -> Option<&JointLimit> {
        self.iter().find(|(n, _)| *n == name).map(|(_, l)| l)
    }
}

impl Robot {
    /// The embedded default robot (BASR).
    pub fn basr() -> Robot {
        // The embedded text is part of the program and tested to be valid.
        Robot::from_toml_str(BASR_TOML, "robots/basr.toml (embedded)")
            .expect("embedded robots/basr.toml is valid")
    }

    /// Read and validate a description file (`-` reads standard input).
    pub fn load(path: &std::path::Path) -> Result<Robot, RobotError> {
        let origin = path.display().to_string();
        let text = basr_io::read_text(path).map_err(|e| RobotError::Read {
            origin: origin.clone(),
            message: format!("{e:#}"),
        })?;
        Robot::from_toml_str(&text, &origin)
    }

    /// The embedded robot, or the file given with `--robot`.
    pub fn load_or_default(path: Option<&std::path::Path>) -> Result<Robot, RobotError> {
        match path {
            Some(p) => Robot::load(p),
            None => Ok(Robot::basr()),
        }
    }

    /// Parse and validate a description; `origin` names it in messages.
    pub fn from_toml_str(text: &str, origin: &str) -> Result<Robot, RobotError> {
        match describe::kind_of(text, origin)? {
            Kind::Basr => describe::parse(text, origin),
            kind => {
                // Report the description's own problems first.
                AnyRobot::from_toml_str(text, origin)?;
                Err(RobotError::Kind {
                    origin: origin.to_string(),
                    kind: kind.name(),
                })
            }
        }
    }

    /// The description as TOML that reads back to an identical robot.
    pub fn to_toml_string(&self) -> String {
        let body = toml::to_string(self).expect("a robot serialises to TOML");
        format!(
            "# Robot description for basr (docs/robot.md). Sources of the default values: \
             robots/basr.toml in the basr sources.\n{body}"
        )
    }

    /// The description as TOML for `basr robot --toml`: the embedded file as
    /// shipped, with every value's source, when this is the default robot
    /// (same canonical hash, however the file it came from was spelled);
    /// else [`Robot::to_toml_string`]. Either way the text reads back to this
    /// robot and prints again byte for byte.
    pub fn to_toml_text(&self) -> String {
        if self.sha256() == Robot::basr().sha256() {
            BASR_TOML.to_string()
        } else {
            self.to_toml_string()
        }
    }

    /// SHA-256 of the description's canonical form (see `basr_io::canon::canonical_json`).
    pub fn sha256(&self) -> String {
        let v = serde_json::to_value(self).expect("robot serialises");
        basr_io::sha256_hex(&basr_io::canon::canonical_json(&v))
    }

    /// What is wrong with a description already read (a job's embedded
    /// robot): (dotted field, what and how to fix it); empty when valid.
    /// The same semantic checks a robot file gets on load.
    pub fn problems(&self) -> Vec<(String, String)> {
        describe::validate(self)
    }

    /// Angular compliance of joint F (rad per N·m) at extension `r`:
    /// the measured deflection under the test torque (001 table 3.2),
    /// interpolated linearly and held constant beyond the measured range.
    pub fn joint_f_compliance_rad_per_nm(&self, extension_m: f64) -> f64 {
        let e = &self.end_effector;
        let xs = &e.joint_f_deflection_extension_m;
        let ys = &e.joint_f_deflection_rad;
        let defl = match xs.iter().position(|&x| x >= extension_m) {
            _ if xs.is_empty() || ys.len() != xs.len() => 0.0,
            Some(0) => ys[0],
            None => ys[ys.len() - 1],
            Some(i) => {
                let t = (extension_m - xs[i - 1]) / (xs[i] - xs[i - 1]);
                ys[i - 1] + t * (ys[i] - ys[i - 1])
            }
        };
        defl / e.joint_f_test_torque_nm
    }

    /// Highest extension the cylinder can give.
    pub fn max_extension_by_cylinder_m(&self) -> f64 {
        self.arm.retracted_extension_m + self.arm.pantograph_ratio * self.arm.cylinder_stroke_m
    }

    /// Highest extension a plan may use: the cylinder's, less the stroke
    /// margin (`arm.cylinder_stroke_margin_m`) before the end stop.
    pub fn max_planned_extension_m(&self) -> f64 {
        self.arm.retracted_extension_m
            + self.arm.pantograph_ratio
                * (self.arm.cylinder_stroke_m - self.arm.cylinder_stroke_margin_m)
    }
}

#[cfg(test)]
#[allow(clippy::approx_constant)] // 0.7854 is the seed's base window, not π/4
mod tests {
    use super::*;

    #[test]
    fn embedded_robot_is_valid_and_has_spec_values() {
        let r = Robot::basr();
        assert_eq!(r.limits.base_rot_rad.min, 0.7854);
        assert_eq!(r.limits.base_rot_rad.max, 2.3562);
        assert_eq!(r.arm.a2_m, 0.01);
        // Full stroke 5.358 m; the plan stops the ¼ in margin short of it.
        assert!((r.max_extension_by_cylinder_m() - 5.358333333333333).abs() < 1e-12);
        assert_eq!(r.arm.cylinder_stroke_margin_m, 0.00635);
        assert!((r.limits.extension_m.max - 5.305416666666667).abs() < 1e-12);
        assert!((r.max_planned_extension_m() - r.limits.extension_m.max).abs() < 1e-12);
        assert_eq!(r.encoders.base_counts_per_rev, 88000);
        assert!((r.paint.fan_angle_rad.to_degrees() - 63.5).abs() < 1e-12);
        // 0.4 L/min · 0.9 / 0.38 mm.
        assert!((r.paint.k_m2ps() - 0.4e-3 / 60.0 * 0.9 / 0.38e-3).abs() < 1e-15);
    }

    #[test]
    fn toml_round_trip_is_identical() {
        let r = Robot::basr();
        let text = r.to_toml_string();
        let back = Robot::from_toml_str(&text, "round-trip").unwrap();
        assert_eq!(back, r);
        assert_eq!(back.sha256(), r.sha256());
        assert_eq!(back.to_toml_string(), text);
    }

    #[test]
    fn toml_text_is_a_fixed_point() {
        // The default, however its file was spelled, prints as shipped.
        let r = Robot::basr();
        assert_eq!(r.to_toml_text(), BASR_TOML);
        let respelled = Robot::from_toml_str(&r.to_toml_string(), "x").unwrap();
        assert_eq!(respelled.to_toml_text(), BASR_TOML);
        // Any other description: print(read(print(x))) == print(x), for
        // values toml spells in unusual ways (exponents, -0.0, optional keys).
        let mut c = Robot::basr();
        c.name = "custom \"arm\"".into();
        c.end_effector.mass_kg = 35.0 + 0.1 + 0.2;
        c.dynamics.leakage_m3_per_s_pa = 1.234e-17;
        c.hydraulics.supply_pa = 2.5e7 + 1.0 / 3.0; // within its range (ranges.rs)
        c.arm.a2_m = -0.0;
        c.paint.height_law_c0_m = Some(0.02);
        c.paint.height_law_c1 = Some(0.7);
        let once = c.to_toml_text();
        let back = Robot::from_toml_str(&once, "custom").unwrap();
        assert_eq!(back.sha256(), c.sha256());
        assert_eq!(back.to_toml_text(), once);
    }

    #[test]
    fn height_law_geometric_and_calibrated() {
        let mut p = Robot::basr().paint;
        // 001 eq. 2.5 at 63.5°: w = 0.41 m needs 0.331 m.
        assert!((p.height_for_width_m(0.41) - 0.3314).abs() < 1e-3);
        p.height_law_c0_m = Some(0.02);
        p.height_law_c1 = Some(0.7);
        assert!((p.height_for_width_m(0.2) - 0.16).abs() < 1e-15);
    }

    #[test]
    fn joint_f_compliance_from_table_3_2() {
        let r = Robot::basr();
        let per = |deg: f64| deg.to_radians() / 101.7;
        assert!((r.joint_f_compliance_rad_per_nm(1.0) - per(0.18)).abs() < 1e-15);
        assert!((r.joint_f_compliance_rad_per_nm(2.0) - per(0.18)).abs() < 1e-15);
        assert!((r.joint_f_compliance_rad_per_nm(5.3) - per(0.20)).abs() < 1e-15);
        // Halfway between 4.788 m (0.19°) and 5.093 m (0.20°).
        let mid = 0.5 * (4.788 + 5.093);
        assert!((r.joint_f_compliance_rad_per_nm(mid) - per(0.195)).abs() < 1e-12);
    }

    #[test]
    fn limits_iterate_in_csv_order() {
        let r = Robot::basr();
        let names: Vec<_> = r.limits.iter().map(|(n, _)| n).collect();
        assert_eq!(names, Limits::NAMES);
        assert_eq!(r.limits.get("tilt_rad"), Some(&r.limits.tilt_rad));
    }
}
