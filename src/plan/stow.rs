//! The stow pose: where the arm waits while the truck moves, and where
//! every station's motion starts and ends.

use crate::robot::{Joints, Robot};

/// Straight back, retracted, nozzle at the top of its stroke, yaw and tilt
/// centred (within limits).
pub fn stow_joints(robot: &Robot) -> Joints {
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
