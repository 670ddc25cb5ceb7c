//! What the planner, the job and the simulator see of a robot of any kind
//! (SPEC §8): one joint set `Q` in the kind's column order, its limits,
//! forward kinematics, every IK solution and the shortest-travel choice,
//! the stow pose, the joint that turns the fan, the tilt the fan can lean
//! by, the nozzle and control settings and the reach on the road. BASR
//! answers with its own code (`Robot::ik_nearest`, the pantograph region),
//! so a BASR job is planned exactly as before; BASR-only parts (actuators,
//! the tilt four-bar, the hydraulic plant) stay behind [`AnyRobot::basr`].
//!
//! A job embeds the description as its own JSON; BASR's has no `kind`
//! member (its hash is the same with or without `kind = "basr"`), another
//! kind's says which it is, and reading dispatches on it.

use std::f64::consts::FRAC_PI_2;

use serde::{Deserialize, Serialize};

use super::kind::{AnyRobot, Kind, Q};
use super::reach::Reach;
use super::{Control, JointLimit, Joints, NozzlePose, Paint, Robot, Truck, Unreachable};

impl AnyRobot {
    /// BASR's own description, for what only BASR has (actuators, the tilt
    /// four-bar, the hydraulic plant); `None` for the electric kinds.
    pub fn basr(&self) -> Option<&Robot> {
        match self {
            AnyRobot::Basr(r) => Some(r),
            _ => None,
        }
    }

    /// [`AnyRobot::basr`], to edit (tests of damaged jobs).
    pub fn basr_mut(&mut self) -> Option<&mut Robot> {
        match self {
            AnyRobot::Basr(r) => Some(r),
            _ => None,
        }
    }

    pub fn name(&self) -> &str {
        self.arm().name()
    }

    pub fn paint(&self) -> &Paint {
        match self {
            AnyRobot::Basr(r) => &r.paint,
            AnyRobot::Telescopic(r) => &r.paint,
            AnyRobot::Articulated(r) => &r.paint,
        }
    }

    /// The paint figures, to mount a tip on them (compile's tip choice).
    pub fn paint_mut(&mut self) -> &mut Paint {
        match self {
            AnyRobot::Basr(r) => &mut r.paint,
            AnyRobot::Telescopic(r) => &mut r.paint,
            AnyRobot::Articulated(r) => &mut r.paint,
        }
    }

    /// This description with the listed tip `name` mounted, as compile
    /// records it in a job planned for that tip (`paint.tip`): what a job's
    /// `robot_sha256` is compared with. Unchanged when `name` is `None` or
    /// not listed.
    pub fn with_mounted(mut self, name: Option<&str>) -> AnyRobot {
        if let Some(tip) = name.and_then(|n| self.paint().tip(n)).cloned() {
            let p = self.paint_mut();
            *p = p.with_tip(&tip);
        }
        self
    }

    pub fn control(&self) -> &Control {
        match self {
            AnyRobot::Basr(r) => &r.control,
            AnyRobot::Telescopic(r) => &r.control,
            AnyRobot::Articulated(r) => &r.control,
        }
    }

    /// The truck's moves between stations: BASR's `[truck]`; the electric
    /// kinds ride the same truck (its defaults).
    pub fn truck(&self) -> Truck {
        match self {
            AnyRobot::Basr(r) => r.truck.clone(),
            _ => Truck::default(),
        }
    }

    /// (dotted field, problem) of the description; empty when valid.
    pub fn problems(&self) -> Vec<(String, String)> {
        self.arm().problems()
    }

    /// Setpoint column names of the five joints, in [`Q`] order.
    pub fn joint_names(&self) -> [&'static str; 5] {
        self.arm().joint_names()
    }

    pub fn limits(&self) -> [JointLimit; 5] {
        self.arm().limits()
    }

    pub fn fk(&self, q: &Q) -> NozzlePose {
        self.arm().fk(q)
    }

    pub fn ik(&self, pose: &NozzlePose) -> Result<Vec<Q>, Unreachable> {
        self.arm().ik(pose)
    }

    /// The IK solution with the shortest travel from `prev` (seed 003).
    pub fn ik_nearest(&self, pose: &NozzlePose, prev: &Q) -> Result<Q, Unreachable> {
        match self {
            AnyRobot::Basr(r) => Ok(r.ik_nearest(pose, &Joints::of(prev))?.values()),
            _ => {
                let all = self.ik(pose)?;
                // `ik` returns Ok only with at least one solution.
                Ok(self.arm().nearest(&all, prev).unwrap_or(all[0]))
            }
        }
    }

    /// Encoder counts of the joints, in [`Q`] order.
    pub fn encoders(&self, q: &Q) -> [i64; 5] {
        self.arm().encoders(q)
    }

    /// The setpoint CSV's names of the encoder counts, in [`Q`] order (as
    /// [`AnyRobot::encoders`] gives them): BASR's own columns (SPEC §3's
    /// `enc_base` … in its joint order), another kind's kind columns.
    pub fn count_columns(&self) -> [String; 5] {
        match self {
            AnyRobot::Basr(_) => [
                "enc_base",
                "enc_extension",
                "enc_vertical",
                "enc_yaw",
                "enc_tilt",
            ]
            .map(String::from),
            _ => self.encoder_names(),
        }
    }

    /// The joints at encoder counts `counts` ([`Q`] order, as
    /// [`AnyRobot::count_columns`] names them).
    pub fn joints_from_encoders(&self, counts: &[i64; 5]) -> Result<Q, Unreachable> {
        self.arm().joints_from_encoders(counts)
    }

    /// Index in [`Q`] of the joint that turns the fan about the vertical
    /// (BASR's and the telescopic head's yaw, the articulated gun's tilt).
    pub fn fan_joint(&self) -> usize {
        match self {
            AnyRobot::Articulated(_) => 4,
            _ => 3,
        }
    }

    /// The range the fan can lean by towards its direction (SPEC §2's β);
    /// `None` for the articulated arm, whose gun leans only in the arm's
    /// plane (seed 003's pitch), so it paints with the fan untilted.
    pub fn tilt_limit(&self) -> Option<JointLimit> {
        match self {
            AnyRobot::Basr(r) => Some(r.limits.tilt_rad),
            AnyRobot::Telescopic(r) => Some(r.joints.tilt_rad.limit()),
            AnyRobot::Articulated(_) => None,
        }
    }

    /// This robot as the planner sees it on an uneven road: the painting
    /// heights the nozzle keeps over the surface wherever the marking lies,
    /// when the surface there lies up to `below_m` under the level of the
    /// base's origin and up to `above_m` over it (docs/site.md). For the
    /// paint law only: the joints are solved with the real ranges, which
    /// reach that much further down and up.
    pub fn on_uneven_road(&self, below_m: f64, above_m: f64) -> AnyRobot {
        let mut r = self.clone();
        match &mut r {
            AnyRobot::Basr(b) => {
                // IK: vertical = top + rise(β) − z; a lower tip is a longer stroke.
                b.limits.vertical_m.max -= below_m;
                b.limits.vertical_m.min += above_m;
            }
            AnyRobot::Telescopic(t) => {
                t.arm.tip_height_min_m += below_m;
                t.arm.tip_height_max_m -= above_m;
            }
            AnyRobot::Articulated(a) => {
                a.arm.tip_height_min_m += below_m;
                a.arm.tip_height_max_m -= above_m;
            }
        }
        r
    }

    /// Tip heights over the road the nozzle paints at with zero tilt.
    pub fn tip_heights_m(&self) -> [f64; 2] {
        self.arm().tip_heights_m()
    }

    /// The stow pose: where the arm waits while the truck moves and where
    /// each station's motion starts and ends.
    pub fn stow(&self) -> Q {
        match self {
            AnyRobot::Basr(r) => stow_basr(r).values(),
            _ => self.stow_electric(),
        }
    }

    /// The electric kinds' stow: the base in the middle of its window and
    /// the tip over the middle of the road region at the top painting
    /// height, fan across the arm, untilted (the IK solution nearest the
    /// middle of every range). assumed: no seed gives a stow pose; this one
    /// keeps the first and last air moves of a station short. Falls back
    /// to the middle of every range when that point is out of reach.
    fn stow_electric(&self) -> Q {
        let arm = self.arm();
        let rest = arm.rest();
        let reach = self.reach();
        let [x, y] = reach.centre();
        let pose = NozzlePose {
            x_m: x,
            y_m: y,
            z_m: self.tip_heights_m()[1],
            yaw_rad: 0.0,
            tilt_rad: 0.0,
        };
        arm.ik(&pose)
            .ok()
            .and_then(|all| arm.nearest(&all, &rest))
            .unwrap_or(rest)
    }

    /// Where the tip reaches on the road, for the station planner.
    pub fn reach(&self) -> Reach {
        match self {
            AnyRobot::Basr(r) => Reach::Region(r.region()),
            _ => Reach::sector_of(self.arm(), self.tilt_limit()),
        }
    }

    /// Encoder column names of the kind's joints: `enc_` and the joint name
    /// without its unit (`boom_rad` → `enc_boom`).
    pub fn encoder_names(&self) -> [String; 5] {
        self.joint_names().map(super::facts::encoder_name)
    }
}

/// BASR's stow: straight back, retracted, nozzle at the top of its stroke,
/// yaw and tilt centred (within limits).
pub fn stow_basr(robot: &Robot) -> Joints {
    let l = &robot.limits;
    let mid = |a: f64, b: f64| 0.5 * (a + b);
    Joints {
        base_rot_rad: mid(l.base_rot_rad.min, l.base_rot_rad.max),
        extension_m: l.extension_m.min,
        vertical_m: l.vertical_m.min,
        ee_yaw_rad: 0.0_f64.clamp(l.ee_yaw_rad.min, l.ee_yaw_rad.max),
        tilt_rad: 0.0_f64.clamp(l.tilt_rad.min, l.tilt_rad.max),
    }
}

impl From<Robot> for AnyRobot {
    fn from(r: Robot) -> AnyRobot {
        AnyRobot::Basr(r)
    }
}

impl Serialize for AnyRobot {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            AnyRobot::Basr(r) => r.serialize(s),
            AnyRobot::Telescopic(r) => r.serialize(s),
            AnyRobot::Articulated(r) => r.serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for AnyRobot {
    /// By the description's `kind` member (absent = BASR).
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<AnyRobot, D::Error> {
        use serde::de::Error;
        let v = serde_json::Value::deserialize(d)?;
        let kind = match v.get("kind") {
            None => Kind::Basr,
            Some(k) => Kind::deserialize(k).map_err(D::Error::custom)?,
        };
        let r = match kind {
            Kind::Basr => serde_json::from_value(v).map(AnyRobot::Basr),
            Kind::Telescopic => serde_json::from_value(v).map(AnyRobot::Telescopic),
            Kind::Articulated => serde_json::from_value(v).map(AnyRobot::Articulated),
        };
        r.map_err(|e| D::Error::custom(format!("robot ({} kind): {e}", kind.name())))
    }
}

/// Fan direction in the road frame of a base-frame one (station heading
/// `heading_rad`, SPEC §2).
pub fn road_yaw(base_yaw: f64, heading_rad: f64) -> f64 {
    super::kinematics::wrap_pi(base_yaw + heading_rad - FRAC_PI_2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kind::{ARTICULATED_TOML, TELESCOPIC_TOML};

    fn all() -> Vec<AnyRobot> {
        [super::super::BASR_TOML, TELESCOPIC_TOML, ARTICULATED_TOML]
            .iter()
            .map(|t| AnyRobot::from_toml_str(t, "shipped").unwrap())
            .collect()
    }

    /// Counts read off an arm give back its joints: the counts of those
    /// joints are the counts read, for every kind.
    #[test]
    fn encoder_counts_round_trip_every_kind() {
        for r in all() {
            let q = r.arm().rest();
            let counts = r.encoders(&q);
            let back = r.joints_from_encoders(&counts).unwrap();
            assert_eq!(r.encoders(&back), counts, "{}", r.name());
            for (a, b) in q.iter().zip(&back) {
                // Within a count: the finest is well under a millimetre.
                assert!((a - b).abs() < 1e-3, "{}: {a} vs {b}", r.name());
            }
        }
    }

    #[test]
    fn json_round_trips_every_kind_and_basr_as_before() {
        for r in all() {
            let v = serde_json::to_value(&r).unwrap();
            let back: AnyRobot = serde_json::from_value(v.clone()).unwrap();
            assert_eq!(back, r);
            assert_eq!(v.get("kind").is_none(), r.kind() == Kind::Basr);
        }
        let basr = Robot::basr();
        assert_eq!(
            serde_json::to_value(AnyRobot::Basr(basr.clone())).unwrap(),
            serde_json::to_value(&basr).unwrap()
        );
    }

    #[test]
    fn stow_is_inside_every_limit_and_reachable() {
        for r in all() {
            let q = r.stow();
            for (l, v) in r.limits().iter().zip(q) {
                assert!(l.contains(v), "{}: {q:?}", r.name());
            }
            let p = r.fk(&q);
            assert!(p.z_m > 0.0, "{}: {p:?}", r.name());
        }
        let b = Robot::basr();
        assert_eq!(AnyRobot::Basr(b.clone()).stow(), stow_basr(&b).values());
    }

    #[test]
    fn encoder_names_drop_the_unit() {
        let r = AnyRobot::from_toml_str(ARTICULATED_TOML, "a").unwrap();
        assert_eq!(r.encoder_names()[4], "enc_gun_tilt");
        let t = AnyRobot::from_toml_str(TELESCOPIC_TOML, "t").unwrap();
        assert_eq!(t.encoder_names()[2], "enc_stroke");
    }
}
