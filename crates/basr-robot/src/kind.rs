//! Robot kinds (SPEC §8): what every arm gives — forward kinematics, every
//! inverse-kinematics solution, the shortest-travel choice among them
//! (seed 003, generalised), limits, encoders, the reference point whose
//! workspace seed 002 studies and the checks `basr check` runs — and the
//! description of any kind, read and validated.
//!
//! Every kind has five joints, so a joint set is a `[f64; 5]` ([`Q`]) in the
//! kind's own column order ([`ArmKind::joint_names`]). BASR keeps its own
//! richer types (`Joints`, `Actuators`, the four-bar) and is wrapped here.

use std::f64::consts::TAU;

use serde::{Deserialize, Serialize};

use super::{
    articulated::Articulated,
    describe,
    facts::{RowJoints, SampledFault},
    telescopic::Telescopic,
    Control, JointLimit, Joints, NozzlePose, Paint, Robot, RobotError, Unreachable,
};

/// A joint set of any kind, in its [`ArmKind::joint_names`] order.
pub type Q = [f64; 5];

/// Which arm a description is for (`kind = "…"`; absent = BASR).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Kind {
    /// The pantograph arm of seeds 000/001 (SPEC §4).
    #[default]
    Basr,
    /// Seed 002's 2R+P arm: base rotation, a revolute boom joint, a telescopic stroke.
    Telescopic,
    /// Seed 003's 5-axis arm: waist, shoulder, elbow, pitch, tilt.
    Articulated,
}

impl Kind {
    pub const NAMES: [&'static str; 3] = ["basr", "telescopic", "articulated"];

    pub fn is_basr(&self) -> bool {
        *self == Kind::Basr
    }

    pub fn name(&self) -> &'static str {
        match self {
            Kind::Basr => "basr",
            Kind::Telescopic => "telescopic",
            Kind::Articulated => "articulated",
        }
    }

    pub fn parse(s: &str) -> Option<Kind> {
        match s {
            "basr" => Some(Kind::Basr),
            "telescopic" => Some(Kind::Telescopic),
            "articulated" => Some(Kind::Articulated),
            _ => None,
        }
    }
}

/// One electric servo joint of the telescopic and articulated kinds: range,
/// rate limits, encoder and what the servo simulation needs.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ServoJoint {
    /// Range (rad or m).
    pub min: f64,
    pub max: f64,
    /// Speed and acceleration limits (rad/s, rad/s² or m/s, m/s²).
    pub max_vel: f64,
    pub max_acc: f64,
    /// Encoder counts per radian (or per metre) of the joint; count 0 at joint 0.
    pub counts_per_unit: f64,
    /// Inertia the joint's motor moves, reflected to the joint (kg·m² or kg).
    pub inertia: f64,
    /// Torque (N·m) or force (N) the drive can give at the joint.
    pub max_effort: f64,
}

impl ServoJoint {
    pub fn limit(&self) -> JointLimit {
        JointLimit {
            min: self.min,
            max: self.max,
            max_vel: self.max_vel,
            max_acc: self.max_acc,
        }
    }

    /// (dotted field, problem) of one joint table `joints.NAME` beyond its
    /// numbers' ranges.
    pub(crate) fn problems(&self, path: &str) -> Vec<(String, String)> {
        // Each number's own range is in `ranges::SERVO_RANGES`; these are the
        // checks between them.
        let mut out = Vec::new();
        if self.min >= self.max {
            out.push((
                format!("{path}.min"),
                format!(
                    "reversed range: min {} is not below max {}; swap them",
                    self.min, self.max
                ),
            ));
        }
        // Reaching the speed limit must not need more torque than the drive
        // has: the acceleration limit times the inertia is the effort used.
        if self.inertia > 0.0 && self.max_acc * self.inertia > self.max_effort {
            out.push((
                format!("{path}.max_acc"),
                format!(
                    "needs {:.4} (inertia × max_acc) but the drive gives max_effort {}; lower max_acc or raise max_effort",
                    self.max_acc * self.inertia,
                    self.max_effort
                ),
            ));
        }
        out
    }
}

/// What every robot kind gives (SPEC §8).
pub trait ArmKind {
    fn name(&self) -> &str;
    fn kind(&self) -> Kind;
    /// Setpoint CSV names of the five joints, in [`Q`] order.
    fn joint_names(&self) -> [&'static str; 5];
    fn limits(&self) -> [JointLimit; 5];
    /// Forward kinematics; joints outside the limits still give their pose.
    fn fk(&self, q: &Q) -> NozzlePose;
    /// Every joint set within the limits that gives the pose (each turn of
    /// a joint whose range spans more than one), sorted; Err names the
    /// binding limit of the candidate that came closest.
    fn ik(&self, pose: &NozzlePose) -> Result<Vec<Q>, Unreachable>;
    /// Encoder counts of each joint (nearest count), in [`Q`] order.
    fn encoders(&self, q: &Q) -> [i64; 5];
    /// The joints at encoder counts `counts` (in [`Q`] order): the inverse
    /// of [`ArmKind::encoders`] to within a count. Err where no joint
    /// value gives the count (BASR's tilt nut beyond its linkage).
    fn joints_from_encoders(&self, counts: &[i64; 5]) -> Result<Q, Unreachable>;
    /// Tip heights over the road the kind can paint at with zero tilt.
    fn tip_heights_m(&self) -> [f64; 2];
    /// The point whose workspace seed 002 studies (the wrist, or for BASR
    /// the yaw axis at the tip's height), base frame.
    fn reference_point(&self, q: &Q) -> [f64; 3];
    /// The two joints that shape the workspace's cross-section (θ1 sweeps it
    /// round the base axis).
    fn section_joints(&self) -> [usize; 2];
    /// (dotted field, what is wrong and how to fix it); empty when valid.
    fn problems(&self) -> Vec<(String, String)>;

    /// The middle of every range: where IK is measured from without a
    /// previous state.
    fn rest(&self) -> Q {
        self.limits().map(|l| 0.5 * (l.min + l.max))
    }

    /// The solution with the shortest travel from `prev` (seed 003).
    fn nearest(&self, all: &[Q], prev: &Q) -> Option<Q> {
        shortest_travel(all, prev, &self.limits()).map(|i| all[i])
    }

    /// Speed caps (per joint, in [`Q`] order) that a joint's drive puts on
    /// top of the joint's own `max_vel` and that a slower pace does not
    /// lower; infinite where the joint's limit is all. BASR holds its tilt
    /// to what its ball nut allows ([`Robot::nut_limited_tilt_rate`]); the
    /// electric kinds' servos are their joints' limits.
    fn drive_speed_caps(&self) -> [f64; 5] {
        [f64::INFINITY; 5]
    }

    /// Whether the fan joint is the only one that can jump to another IK
    /// solution between two nearby poses: BASR's solutions differ only in
    /// the fan's branch (ψ or ψ+π) and yaw turn, so its other joints have
    /// one value per pose; an electric arm's other joints can flip (the
    /// articulated elbow, say).
    fn fan_joint_alone_jumps(&self) -> bool {
        false
    }

    /// How far (m) a tilt of ±`tilt_rad` lifts the tip above where the
    /// untilted tip is at the same vertical joint: the lowest tip height
    /// the kind paints at with that tilt is the lowest untilted one plus
    /// this (the larger of +β and −β, as either fan branch may paint the
    /// rung). BASR's tilt four-bar lifts it; 0 for a kind whose tilt does
    /// not. Not positive (or NaN): no lift.
    fn tilt_lift_m(&self, tilt_rad: f64) -> f64 {
        let _ = tilt_rad;
        0.0
    }

    /// Names of the setpoint columns the kind writes after the job's own:
    /// its five joints, then their encoders (`enc_` and the joint name
    /// without its unit); empty for a kind whose joints are the job's own
    /// columns (BASR).
    fn own_sample_columns(&self) -> Vec<String> {
        let names = self.joint_names();
        let mut out: Vec<String> = names.iter().map(|n| n.to_string()).collect();
        out.extend(names.iter().map(|n| super::facts::encoder_name(n)));
        out
    }

    /// What a setpoint row holds of the joints `q`: the kind's own joint
    /// and encoder columns, or (BASR) the job's joint, actuator and
    /// encoder columns.
    fn row_joints(&self, q: &Q) -> RowJoints {
        RowJoints::Own {
            q: *q,
            encoders: self.encoders(q),
        }
    }

    /// The kind's own check of a sampled joint path `qs` (one joint set
    /// every `period_s`): each joint's range, speed and acceleration by
    /// finite differences, up to a relative 1e-9 (rounding); BASR's also
    /// its ball nut's speed. The first fault, with its setpoint.
    fn check_sampled(&self, qs: &[Q], period_s: f64) -> Result<(), SampledFault> {
        super::facts::check_servo_path(&self.joint_names(), &self.limits(), qs, period_s)
    }
}

/// Index of the joint set of `all` with the shortest travel from `prev`:
/// seed 003 runs "the one requiring the shorter travel distance" of its two
/// solutions; generalised to any number, travel is the time the slowest
/// joint needs at its speed limit (joints move together), ties broken by
/// the summed times. `None` when `all` is empty.
pub fn shortest_travel(all: &[Q], prev: &Q, limits: &[JointLimit; 5]) -> Option<usize> {
    let cost = |q: &Q| {
        let mut worst: f64 = 0.0;
        let mut sum = 0.0;
        for k in 0..5 {
            let t = (q[k] - prev[k]).abs() / limits[k].max_vel;
            worst = worst.max(t);
            sum += t;
        }
        (worst, sum)
    };
    let mut best: Option<(usize, (f64, f64))> = None;
    for (i, q) in all.iter().enumerate() {
        let c = cost(q);
        let better = match best {
            None => true,
            Some((_, b)) => c.0 < b.0 - 1e-12 || ((c.0 - b.0).abs() <= 1e-12 && c.1 < b.1),
        };
        if better {
            best = Some((i, c));
        }
    }
    best.map(|(i, _)| i)
}

/// Every turn `a + 2πk` of a revolute joint's angle inside its range
/// (seed 003: a joint that turns 360° can reach −100° instead of 260°), at
/// most 8; empty when none fits.
pub fn turns_within(a: f64, l: &JointLimit) -> Vec<f64> {
    let k_lo = ((l.min - a) / TAU).ceil();
    let k_hi = ((l.max - a) / TAU).floor();
    if !(k_lo.is_finite() && k_hi.is_finite()) || k_lo > k_hi {
        return vec![];
    }
    let n = ((k_hi - k_lo) as i64).min(7);
    (0..=n).map(|i| a + TAU * (k_lo + i as f64)).collect()
}

/// The nearest turn of `a` to the range, as the candidate to report when
/// no turn fits.
pub fn nearest_turn(a: f64, l: &JointLimit) -> f64 {
    let mid = 0.5 * (l.min + l.max);
    a + TAU * ((mid - a) / TAU).round()
}

/// Keep the less severe of two reasons a candidate failed.
pub(crate) fn keep_closest(closest: &mut Option<Unreachable>, u: Unreachable) {
    if closest.as_ref().is_none_or(|c| u.severity() < c.severity()) {
        *closest = Some(u);
    }
}

/// Every joint set of the candidate `q` with each revolute joint (flagged
/// in `revolute`) on every turn inside its range, pushed to `found`; the
/// reason when none fits, kept in `closest`.
pub(crate) fn expand_turns(
    q: Q,
    names: &[&'static str; 5],
    limits: &[JointLimit; 5],
    revolute: &[bool; 5],
    found: &mut Vec<Q>,
    closest: &mut Option<Unreachable>,
) {
    let mut sets: Vec<Q> = vec![q];
    for k in 0..5 {
        let l = &limits[k];
        let options = if revolute[k] {
            turns_within(q[k], l)
        } else if l.contains(q[k]) {
            vec![q[k]]
        } else {
            vec![]
        };
        if options.is_empty() {
            let v = if revolute[k] {
                nearest_turn(q[k], l)
            } else {
                q[k]
            };
            if !v.is_finite() {
                keep_closest(closest, Unreachable::not_finite(names[k], v));
            } else {
                keep_closest(closest, Unreachable::of(names[k], l, v));
            }
            return;
        }
        sets = sets
            .iter()
            .flat_map(|s| {
                options.iter().map(move |&v| {
                    let mut t = *s;
                    t[k] = v;
                    t
                })
            })
            .collect();
    }
    found.extend(sets);
}

/// Sort solutions and drop duplicates (the same joints found twice, e.g.
/// at a singular pose where two branches meet).
pub(crate) fn sort_dedup(found: &mut Vec<Q>) {
    found.sort_by(|a, b| {
        a.iter()
            .zip(b)
            .map(|(x, y)| x.total_cmp(y))
            .find(|o| o.is_ne())
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    found.dedup_by(|a, b| a.iter().zip(b.iter()).all(|(x, y)| (x - y).abs() < 1e-9));
}

/// The checks every electric kind shares: paint, control and every joint
/// number in its range (`ranges::electric`), the painting
/// heights, each joint table, and a span of at least π for the joint that
/// turns the fan (`fan_joint`).
pub(crate) fn electric_problems(
    paint: &Paint,
    control: &Control,
    heights: [f64; 2],
    names: &[&str; 5],
    joints: [&ServoJoint; 5],
    fan_joint: usize,
) -> Vec<(String, String)> {
    let mut out = super::ranges::electric(paint, control, names, joints);
    out.extend(paint.tip_problems());
    if heights[0] >= heights[1] {
        out.push((
            "arm.tip_height_min_m".into(),
            "reversed range: must be below arm.tip_height_max_m".into(),
        ));
    }
    for (name, j) in names.iter().zip(joints) {
        out.extend(j.problems(&format!("joints.{name}")));
    }
    let f = joints[fan_joint];
    if f.max - f.min < std::f64::consts::PI {
        out.push((
            format!("joints.{}.max", names[fan_joint]),
            "the joint that turns the fan must span at least π so it can face every direction"
                .into(),
        ));
    }
    out
}

/// Joints of servo encoder counts (count 0 at joint 0).
pub(crate) fn servo_joints(joints: [&ServoJoint; 5], counts: &[i64; 5]) -> Q {
    std::array::from_fn(|k| counts[k] as f64 / joints[k].counts_per_unit)
}

/// Encoder counts of servo joints (nearest count, count 0 at joint 0).
pub(crate) fn servo_counts(joints: [&ServoJoint; 5], q: &Q) -> [i64; 5] {
    // `as` saturates; joints are finite by contract (IK never returns NaN).
    std::array::from_fn(|k| (q[k] * joints[k].counts_per_unit).round() as i64)
}

/// Pose fields that must be finite before any IK.
pub(crate) fn check_pose_finite(pose: &NozzlePose) -> Result<(), Unreachable> {
    for (name, v) in [
        ("x_m", pose.x_m),
        ("y_m", pose.y_m),
        ("z_m", pose.z_m),
        ("yaw_rad", pose.yaw_rad),
        ("tilt_rad", pose.tilt_rad),
    ] {
        if !v.is_finite() {
            return Err(Unreachable::not_finite(name, v));
        }
    }
    Ok(())
}

fn joints_of(q: &Q) -> Joints {
    Joints::of(q)
}

impl ArmKind for Robot {
    fn name(&self) -> &str {
        &self.name
    }
    fn kind(&self) -> Kind {
        Kind::Basr
    }
    fn joint_names(&self) -> [&'static str; 5] {
        super::Limits::NAMES
    }
    fn limits(&self) -> [JointLimit; 5] {
        let l = &self.limits;
        [
            l.base_rot_rad,
            l.extension_m,
            l.vertical_m,
            l.ee_yaw_rad,
            l.tilt_rad,
        ]
    }
    fn fk(&self, q: &Q) -> NozzlePose {
        Robot::fk(self, &joints_of(q))
    }
    fn ik(&self, pose: &NozzlePose) -> Result<Vec<Q>, Unreachable> {
        Ok(Robot::ik(self, pose)?.iter().map(Joints::values).collect())
    }
    fn encoders(&self, q: &Q) -> [i64; 5] {
        let e = Robot::encoders(self, &joints_of(q));
        [e.base, e.extension, e.vertical, e.yaw, e.tilt]
    }
    fn joints_from_encoders(&self, c: &[i64; 5]) -> Result<Q, Unreachable> {
        let e = crate::kinematics::Encoders {
            base: c[0],
            extension: c[1],
            vertical: c[2],
            yaw: c[3],
            tilt: c[4],
        };
        Ok(Robot::joints_from_encoders(self, &e)?.values())
    }
    fn tip_heights_m(&self) -> [f64; 2] {
        self.region().z_range_m
    }
    fn reference_point(&self, q: &Q) -> [f64; 3] {
        let w = self.yaw_axis(q[0], q[1]);
        [w[0], w[1], self.end_effector.tip_height_top_m - q[2]]
    }
    fn section_joints(&self) -> [usize; 2] {
        [1, 2]
    }
    fn problems(&self) -> Vec<(String, String)> {
        describe::validate(self)
    }
    fn drive_speed_caps(&self) -> [f64; 5] {
        [
            f64::INFINITY,
            f64::INFINITY,
            f64::INFINITY,
            f64::INFINITY,
            self.nut_limited_tilt_rate(),
        ]
    }
    fn fan_joint_alone_jumps(&self) -> bool {
        true
    }
    fn tilt_lift_m(&self, tilt_rad: f64) -> f64 {
        self.tilt_tip_offset(tilt_rad)[1].max(self.tilt_tip_offset(-tilt_rad)[1])
    }
    fn own_sample_columns(&self) -> Vec<String> {
        vec![]
    }
    fn row_joints(&self, q: &Q) -> RowJoints {
        let joints = joints_of(q);
        RowJoints::Spec {
            joints,
            actuators: self.actuators(&joints),
            encoders: Robot::encoders(self, &joints),
        }
    }
    fn check_sampled(&self, qs: &[Q], period_s: f64) -> Result<(), SampledFault> {
        let js: Vec<Joints> = qs.iter().map(joints_of).collect();
        self.check_rates(&js, period_s).map_err(|e| SampledFault {
            setpoint: None,
            what: e.to_string(),
        })?;
        for (k, j) in js.iter().enumerate() {
            self.check_joints(j).map_err(|e| SampledFault {
                setpoint: Some(k),
                what: format!("the joint path between knots leaves a joint's range ({e})"),
            })?;
        }
        Ok(())
    }
}

/// A robot description of any kind.
// Read once per run and passed by reference; boxing BASR's larger
// description would buy nothing.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, PartialEq)]
pub enum AnyRobot {
    Basr(Robot),
    Telescopic(Telescopic),
    Articulated(Articulated),
}

impl AnyRobot {
    /// The kinematics every kind gives.
    pub fn arm(&self) -> &dyn ArmKind {
        match self {
            AnyRobot::Basr(r) => r,
            AnyRobot::Telescopic(r) => r,
            AnyRobot::Articulated(r) => r,
        }
    }

    pub fn kind(&self) -> Kind {
        self.arm().kind()
    }

    /// Read and validate a description of any kind (`-` reads standard input).
    pub fn load(path: &std::path::Path) -> Result<AnyRobot, RobotError> {
        let origin = path.display().to_string();
        let text = basr_io::read_text(path).map_err(|e| RobotError::Read {
            origin: origin.clone(),
            message: format!("{e:#}"),
        })?;
        AnyRobot::from_toml_str(&text, &origin)
    }

    /// The embedded BASR, or the file given with `--robot`.
    pub fn load_or_default(path: Option<&std::path::Path>) -> Result<AnyRobot, RobotError> {
        match path {
            Some(p) => AnyRobot::load(p),
            None => Ok(AnyRobot::Basr(Robot::basr())),
        }
    }

    /// Parse by the `kind` key (absent = BASR) and validate.
    pub fn from_toml_str(text: &str, origin: &str) -> Result<AnyRobot, RobotError> {
        match describe::kind_of(text, origin)? {
            Kind::Basr => describe::parse(text, origin).map(AnyRobot::Basr),
            Kind::Telescopic => describe::parse_as(text, origin, |r: &Telescopic| r.problems())
                .map(AnyRobot::Telescopic),
            Kind::Articulated => describe::parse_as(text, origin, |r: &Articulated| r.problems())
                .map(AnyRobot::Articulated),
        }
    }

    /// The description as JSON (the form a job embeds).
    pub fn to_json(&self) -> serde_json::Value {
        let v = match self {
            AnyRobot::Basr(r) => serde_json::to_value(r),
            AnyRobot::Telescopic(r) => serde_json::to_value(r),
            AnyRobot::Articulated(r) => serde_json::to_value(r),
        };
        v.expect("a robot serialises")
    }

    /// SHA-256 of the canonical JSON form (as [`Robot::sha256`]).
    pub fn sha256(&self) -> String {
        basr_io::sha256_hex(&basr_io::canon::canonical_json(&self.to_json()))
    }

    /// TOML that reads back to this robot: BASR as [`Robot::to_toml_text`],
    /// a shipped description of another kind as shipped (with its sources).
    pub fn to_toml_text(&self) -> String {
        match self {
            AnyRobot::Basr(r) => r.to_toml_text(),
            AnyRobot::Telescopic(r) => shipped_or(r, TELESCOPIC_TOML, "telescopic"),
            AnyRobot::Articulated(r) => shipped_or(r, ARTICULATED_TOML, "articulated"),
        }
    }
}

/// The shipped description of the telescopic kind.
pub const TELESCOPIC_TOML: &str = include_str!("../../../robots/telescopic.toml");
/// The shipped description of the articulated kind.
pub const ARTICULATED_TOML: &str = include_str!("../../../robots/articulated.toml");

fn shipped_or<T: Serialize + PartialEq + for<'de> Deserialize<'de>>(
    r: &T,
    shipped: &str,
    kind: &str,
) -> String {
    if toml::from_str::<T>(shipped).ok().as_ref() == Some(r) {
        return shipped.to_string();
    }
    let body = toml::to_string(r).expect("a robot serialises to TOML");
    format!(
        "# Robot description for basr, kind {kind} (docs/robot-kinds.md). Sources of the shipped values: \
         robots/{kind}.toml in the basr sources.\n{body}"
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn turns_cover_the_range() {
        let l = JointLimit {
            min: -std::f64::consts::PI,
            max: std::f64::consts::PI,
            max_vel: 1.0,
            max_acc: 1.0,
        };
        // 003: 260° is −100° on a joint that turns both ways.
        let t = turns_within(260f64.to_radians(), &l);
        assert_eq!(t.len(), 1);
        assert!((t[0].to_degrees() + 100.0).abs() < 1e-9);
        let wide = JointLimit {
            min: -2.0 * TAU,
            max: 2.0 * TAU,
            ..l
        };
        assert_eq!(turns_within(0.5, &wide).len(), 4);
        let narrow = JointLimit {
            min: 1.0,
            max: 2.0,
            ..l
        };
        assert!(turns_within(0.0, &narrow).is_empty());
    }

    #[test]
    fn shortest_travel_uses_the_slowest_joint() {
        let l = JointLimit {
            min: -10.0,
            max: 10.0,
            max_vel: 1.0,
            max_acc: 1.0,
        };
        let mut limits = [l; 5];
        limits[1].max_vel = 0.1;
        let prev = [0.0; 5];
        // Joint 1 moves 0.2 at 0.1/s (2 s); joint 0 moves 1.5 at 1/s (1.5 s).
        let a = [0.0, 0.2, 0.0, 0.0, 0.0];
        let b = [1.5, 0.0, 0.0, 0.0, 0.0];
        assert_eq!(shortest_travel(&[a, b], &prev, &limits), Some(1));
        assert_eq!(shortest_travel(&[], &prev, &limits), None);
    }

    #[test]
    fn every_shipped_kind_reads_and_prints_as_shipped() {
        for (text, kind) in [
            (super::super::BASR_TOML, Kind::Basr),
            (TELESCOPIC_TOML, Kind::Telescopic),
            (ARTICULATED_TOML, Kind::Articulated),
        ] {
            let r = AnyRobot::from_toml_str(text, "shipped").unwrap();
            assert_eq!(r.kind(), kind);
            assert_eq!(r.to_toml_text(), text);
            assert!(r.arm().problems().is_empty());
        }
    }

    #[test]
    fn unknown_kind_is_named_with_its_line() {
        let text = TELESCOPIC_TOML.replacen("kind = \"telescopic\"", "kind = \"scara\"", 1);
        let line = text.lines().position(|l| l.starts_with("kind")).unwrap() + 1;
        let e = AnyRobot::from_toml_str(&text, "x.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains(&format!("x.toml:{line}: field `kind`")), "{e}");
        assert!(e.contains("telescopic"), "{e}");
    }

    #[test]
    fn basr_with_explicit_kind_hashes_as_without() {
        let text = super::super::BASR_TOML.replacen(
            "name = \"BASR\"",
            "name = \"BASR\"\nkind = \"basr\"",
            1,
        );
        let r = AnyRobot::from_toml_str(&text, "x").unwrap();
        assert_eq!(r.sha256(), Robot::basr().sha256());
    }
}
