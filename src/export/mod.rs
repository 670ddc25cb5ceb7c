//! Exports for integrators: the job's joint trajectories in the forms other
//! controllers load (a ROS 2 `JointTrajectory` per stop, an industrial
//! arm's program). Each reads the sealed job; none plans anything.

pub mod mcap_trace;
pub mod ros2;
pub mod urscript;

use crate::job::Job;

/// The five joints of row `i`, in the robot's joint order
/// ([`crate::robot::AnyRobot::joint_names`]).
pub fn joints(job: &Job, i: usize) -> [f64; 5] {
    let s = &job.samples;
    match s.kind_joints.get(i) {
        Some(q) => *q,
        None => [
            s.base_rot_rad[i],
            s.extension_m[i],
            s.vertical_m[i],
            s.ee_yaw_rad[i],
            s.tilt_rad[i],
        ],
    }
}

/// The rows of each stop, in order: (stop index, first row, one past the
/// last row). A stop is a run of rows with one `station`.
pub fn stop_rows(job: &Job) -> Vec<(usize, usize, usize)> {
    let st = &job.samples.station;
    let mut out = vec![];
    let mut start = 0;
    for i in 1..=st.len() {
        if i == st.len() || st[i] != st[start] {
            if i > start {
                out.push((st[start] as usize, start, i));
            }
            start = i;
        }
    }
    out
}

/// The gun's switching in rows `range` of the job: (on, off) times from
/// the range's first row, seconds; a gun still on at the end goes off at
/// the last row.
pub fn gun_intervals(job: &Job, range: std::ops::Range<usize>) -> Vec<(f64, f64)> {
    let s = &job.samples;
    let t0 = s.t_s[range.start];
    let mut out = vec![];
    let mut on: Option<f64> = None;
    for i in range.clone() {
        match (s.paint[i] != 0, on) {
            (true, None) => on = Some(s.t_s[i] - t0),
            (false, Some(t)) => {
                out.push((t, s.t_s[i] - t0));
                on = None;
            }
            _ => {}
        }
    }
    if let Some(t) = on {
        out.push((t, s.t_s[range.end - 1] - t0));
    }
    out
}

/// Velocity and acceleration of `q` sampled at times `t` by finite
/// differences: central inside, one-sided at the ends (second order on a
/// uniform grid, exact for a parabola). Written by hand: a three-point
/// stencil is all it takes.
pub fn derivatives(t: &[f64], q: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let n = q.len();
    if n < 2 {
        return (vec![0.0; n], vec![0.0; n]);
    }
    // The neighbours a derivative at `i` is taken between.
    let pair = |i: usize| match i {
        0 => (0, 1),
        i if i == n - 1 => (n - 2, n - 1),
        i => (i - 1, i + 1),
    };
    let rate = |x: &[f64]| -> Vec<f64> {
        (0..n)
            .map(|i| {
                let (a, b) = pair(i);
                let dt = t[b] - t[a];
                if dt > 0.0 {
                    (x[b] - x[a]) / dt
                } else {
                    0.0
                }
            })
            .collect()
    };
    let v = rate(q);
    let acc = rate(&v);
    (v, acc)
}
