//! Flown joins: jerk-limited state-to-state moves of every joint from the
//! state a painting path leaves one stroke in (position, speed and
//! acceleration) to the state the next stroke's path starts in, all joints
//! in the same time, the shortest the slowest joint allows under its speed,
//! acceleration and jerk limits and inside its range (Berscheid & Kröger,
//! "Jerk-limited real-time trajectory generation with arbitrary target
//! states", RSS 2021, through the `rsruckig` crate).

use rsruckig::prelude::{
    DataArrayOrVec, InputParameter, Ruckig, RuckigResult, ThrowErrorHandler,
    Trajectory as RuckigTrajectory,
};

use super::{JointLimits, Kind, TimingError, Trajectory};

/// A joint state at one instant: positions, rates and accelerations.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Kinematic<const N: usize> {
    pub q: [f64; N],
    pub qd: [f64; N],
    pub qdd: [f64; N],
}

/// Each joint's range (min, max), which the join never leaves.
pub type Ranges<const N: usize> = [(f64, f64); N];

fn stack<const N: usize>(a: [f64; N]) -> DataArrayOrVec<f64, N> {
    DataArrayOrVec::Stack(a)
}

/// The jerk-limited, time-synchronised move from `from` to `to` within
/// `limits` (less the share `margin` held back) and `range`.
pub fn join_move<const N: usize>(
    from: &Kinematic<N>,
    to: &Kinematic<N>,
    limits: &JointLimits<N>,
    range: &Ranges<N>,
    margin: f64,
) -> Result<Trajectory<N>, TimingError> {
    let traj = solve(from, to, limits, range, margin)?;
    let duration_s = traj.get_duration();
    Ok(Trajectory {
        kind: Kind::Join(Box::new(traj)),
        duration_s,
        slowdowns: Vec::new(),
    })
}

fn solve<const N: usize>(
    from: &Kinematic<N>,
    to: &Kinematic<N>,
    limits: &JointLimits<N>,
    range: &Ranges<N>,
    margin: f64,
) -> Result<RuckigTrajectory<N>, TimingError> {
    limits.validate()?;
    let finite = |k: &Kinematic<N>| k.q.iter().chain(&k.qd).chain(&k.qdd).all(|v| v.is_finite());
    if !(finite(from) && finite(to)) {
        return Err(TimingError::NotFinite { index: 0 });
    }
    let keep = 1.0 - margin;
    let mut input = InputParameter::<N>::new(None);
    input.current_position = stack(from.q);
    input.current_velocity = stack(from.qd);
    input.current_acceleration = stack(from.qdd);
    input.target_position = stack(to.q);
    input.target_velocity = stack(to.qd);
    input.target_acceleration = stack(to.qdd);
    // The speed limits are the joints' own: where an end state would carry
    // a joint past one (its acceleration cannot be brought to zero in time
    // at the jerk limit), no join is found and the caller keeps the seam in
    // the path. An end state may accelerate harder than a slowed join's
    // limit allows (it comes from the path at full pace): that much is
    // allowed.
    let jerk: [f64; N] = std::array::from_fn(|j| limits.jerk[j] * keep);
    input.max_velocity = stack(std::array::from_fn(|j| limits.vel[j] * keep));
    for (j, &jk) in jerk.iter().enumerate() {
        // Ruckig checks the target so; the start it would brake past.
        let (v, a) = (from.qd[j], from.qdd[j]);
        let coast = v.abs() + if v * a > 0.0 { a * a / (2.0 * jk) } else { 0.0 };
        if coast > input.max_velocity[j] * (1.0 + 1e-9) {
            return Err(TimingError::NoJoin(format!(
                "joint {j} leaves at {v} with acceleration {a}: it passes its speed limit before the jerk limit can level it"
            )));
        }
    }
    input.max_acceleration = stack(std::array::from_fn(|j| {
        (limits.acc[j] * keep).max(from.qdd[j].abs().max(to.qdd[j].abs()) * (1.0 + 1e-9))
    }));
    input.max_jerk = stack(jerk);
    input.min_position = Some(stack(std::array::from_fn(|j| {
        range[j].0.min(from.q[j]).min(to.q[j])
    })));
    input.max_position = Some(stack(std::array::from_fn(|j| {
        range[j].1.max(from.q[j]).max(to.q[j])
    })));
    let mut otg = Ruckig::<N, ThrowErrorHandler>::new(None, 0.001);
    let mut traj = RuckigTrajectory::<N>::new(None);
    match otg.calculate(&input, &mut traj) {
        Ok(RuckigResult::Working) | Ok(RuckigResult::Finished) => Ok(traj),
        Ok(r) => Err(TimingError::NoJoin(format!("{r:?}"))),
        Err(e) => Err(TimingError::NoJoin(e.to_string())),
    }
}

/// Position and rate of a join at `t` from its start.
pub(super) fn eval<const N: usize>(traj: &RuckigTrajectory<N>, t: f64) -> ([f64; N], [f64; N]) {
    let mut p = stack([0.0; N]);
    let mut v = stack([0.0; N]);
    let mut section = None;
    traj.at_time(
        t.clamp(0.0, traj.get_duration()),
        &mut Some(&mut p),
        &mut Some(&mut v),
        &mut None,
        &mut None,
        &mut section,
    );
    (std::array::from_fn(|j| p[j]), std::array::from_fn(|j| v[j]))
}
