//! End-effector axes (yaw servo, tilt ball-screw servo, vertical hydraulic
//! joint) as position servo loops with rate and acceleration limits.
//!
//! Each is a critically damped second-order loop of the axis' bandwidth whose
//! acceleration and rate are clipped to the axis' limits; these axes do not
//! load the arm (their masses are in the arm's end-effector mass), so they are
//! stepped beside the arm's ODE at the same sub-step.

use super::model::ServoAxis;

/// State of one servo axis.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Servo {
    pub pos: f64,
    pub vel: f64,
}

impl Servo {
    pub fn at(pos: f64) -> Servo {
        Servo { pos, vel: 0.0 }
    }

    /// Advance by `h` towards `target` moving at `target_vel`; returns true
    /// when a rate or acceleration limit was active.
    pub fn step(&mut self, axis: &ServoAxis, target: f64, target_vel: f64, h: f64) -> bool {
        let w = axis.bandwidth_rad_s;
        let want = w * w * (target - self.pos) + 2.0 * w * (target_vel - self.vel);
        let acc = want.clamp(-axis.accel_limit, axis.accel_limit);
        let v_want = self.vel + acc * h;
        let v = v_want.clamp(-axis.rate_limit, axis.rate_limit);
        self.pos += 0.5 * (self.vel + v) * h;
        self.vel = v;
        acc != want || v != v_want
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::SimModel;

    #[test]
    fn yaw_reaches_its_rate_limit_in_a_tenth_of_a_second() {
        let axis = SimModel::basr().yaw;
        let mut s = Servo::at(0.0);
        let mut t = 0.0;
        while s.vel < 0.999 * axis.rate_limit && t < 1.0 {
            s.step(&axis, 1.0, 0.0, 1e-3);
            t += 1e-3;
        }
        assert!((0.09..0.12).contains(&t), "{t}");
        // and settles on a small step without limits
        let mut s = Servo::at(0.0);
        let mut limited = false;
        for _ in 0..2000 {
            limited |= s.step(&axis, 0.001, 0.0, 1e-3);
        }
        assert!(!limited);
        assert!((s.pos - 0.001).abs() < 1e-6);
    }
}
