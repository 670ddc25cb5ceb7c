//! Leads: gun-off run-ups and run-outs along a stroke's end tangents, so the
//! nozzle reaches the painting speed before the first rung and keeps it past
//! the last.

use basr_robot::kinematics::wrap_pi;

use super::knots::{self, Knot};

/// A knot with the same spray moved `d` metres along `dir` (road frame),
/// its fan turned by `dyaw`.
fn shifted(k: &Knot, dir: kurbo::Vec2, d: f64, dyaw: f64) -> Knot {
    Knot {
        mid: k.mid + dir * d,
        tip: k.tip + dir * d,
        yaw_rad: k.yaw_rad + dyaw,
        ..*k
    }
}

/// Fan turn per metre of tip travel from knot `a` to knot `b` (rad/m).
fn yaw_per_m(a: &Knot, b: &Knot) -> f64 {
    let ds = (b.tip - a.tip).hypot();
    let dyaw = wrap_pi(b.yaw_rad - a.yaw_rad);
    if ds > knots::MIN_TIP_STEP_M && dyaw.is_finite() {
        dyaw / ds
    } else {
        0.0
    }
}

/// The run's knots with a lead-in and lead-out of `lead` metres along the
/// stroke's end directions, `per_lead` pseudo-knots each (at least one);
/// returns (knots, index of the first and last painting knot).
pub fn with_leads(ks: &[Knot], lead: f64, per_lead: usize) -> (Vec<Knot>, usize, usize) {
    let n = ks.len();
    let per = per_lead.max(1);
    if lead <= 0.0 || n < 2 {
        return (ks.to_vec(), 0, n.saturating_sub(1));
    }
    let dir_in = (ks[0].tip - ks[1].tip).normalize();
    let dir_out = (ks[n - 1].tip - ks[n - 2].tip).normalize();
    if !(dir_in.is_finite() && dir_out.is_finite()) {
        return (ks.to_vec(), 0, n - 1);
    }
    // The fan already turns at the stroke's own rate when the gun opens: the
    // lead winds the turn up from rest (dyaw/ds falls linearly from the
    // stroke's rate at its end to 0 at the lead's far end), so a curved
    // stroke does not start with a step in yaw rate that the servo's
    // acceleration limit would answer by slowing the nozzle over paint.
    let (turn_in, turn_out) = (yaw_per_m(&ks[1], &ks[0]), yaw_per_m(&ks[n - 2], &ks[n - 1]));
    let wound = |d: f64| d - d * d / (2.0 * lead);
    let mut out = Vec::with_capacity(n + 2 * per);
    for i in (1..=per).rev() {
        let d = lead * i as f64 / per as f64;
        out.push(shifted(&ks[0], dir_in, d, turn_in * wound(d)));
    }
    out.extend_from_slice(ks);
    for i in 1..=per {
        let d = lead * i as f64 / per as f64;
        out.push(shifted(&ks[n - 1], dir_out, d, turn_out * wound(d)));
    }
    (out, per, per + n - 1)
}
