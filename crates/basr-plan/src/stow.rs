//! The stow pose: where the arm waits while the truck moves, and where
//! every station's motion starts and ends.

use basr_job::Station;
use basr_robot::{AnyRobot, Q};

/// The kind's stow pose (`AnyRobot::stow`): for BASR straight back,
/// retracted, nozzle at the top of its stroke, yaw and tilt centred.
pub fn stow_joints(robot: &AnyRobot) -> Q {
    robot.stow()
}

/// Setpoint rows the arm holds the stow pose while the truck drives from
/// station `from` to `to` and settles (the robot's `truck` speed and settle
/// time), at least one.
pub fn truck_rows(robot: &AnyRobot, from: &Station, to: &Station, period_s: f64) -> usize {
    let t = robot.truck();
    let d = (to.x_m - from.x_m).hypot(to.y_m - from.y_m);
    let secs = d / t.speed_mps + t.settle_s;
    if secs.is_finite() && secs > 0.0 {
        ((secs / period_s).ceil() as usize).max(1)
    } else {
        1
    }
}
