//! Tests of the time law: limits hold on the samples, speeds as requested.

use super::path::{max_x, max_x_exhaustive};
use super::*;
use proptest::prelude::*;

fn limits3() -> JointLimits<3> {
    JointLimits {
        vel: [0.5, 0.3, 0.52],
        acc: [1.0, 0.6, 5.0],
        jerk: [10.0, 6.0, 50.0],
    }
}

/// A sample whose finite-difference rate is over its joint's limit.
#[derive(Debug, thiserror::Error)]
enum Over {
    #[error("sample {k} joint {j}: velocity {v} > {limit}")]
    Velocity {
        k: usize,
        j: usize,
        v: f64,
        limit: f64,
    },
    #[error("sample {k} joint {j}: acceleration {a} > {limit}")]
    Acceleration {
        k: usize,
        j: usize,
        a: f64,
        limit: f64,
    },
}

/// Every finite-difference velocity and acceleration of the samples is within the limits.
fn check_limits<const N: usize>(
    s: &Samples<N>,
    lim: &JointLimits<N>,
    period: f64,
) -> Result<(), Over> {
    let tol = 1e-9;
    for k in 1..s.len() {
        for j in 0..N {
            let v = (s.q[k][j] - s.q[k - 1][j]) / period;
            if v.abs() > lim.vel[j] * (1.0 + 1e-6) + tol {
                return Err(Over::Velocity {
                    k,
                    j,
                    v,
                    limit: lim.vel[j],
                });
            }
            if k + 1 < s.len() {
                let a = (s.q[k + 1][j] - 2.0 * s.q[k][j] + s.q[k - 1][j]) / (period * period);
                if a.abs() > lim.acc[j] * (1.0 + 1e-6) + tol {
                    return Err(Over::Acceleration {
                        k,
                        j,
                        a,
                        limit: lim.acc[j],
                    });
                }
            }
        }
    }
    Ok(())
}

fn straight_path(n: usize, speed: Option<f64>) -> Vec<PathPoint<3>> {
    (0..n)
        .map(|k| {
            let s = 0.02 * k as f64;
            PathPoint {
                s_m: s,
                q: [s, 0.5 * s, 0.0],
                cap_only: false,
                dq_ds: None,
                max_speed_mps: speed,
            }
        })
        .collect()
}

#[test]
fn cruise_reaches_the_requested_speed_and_ends_at_rest() {
    let mut pts = straight_path(101, Some(0.15));
    // Run-up and run-out without a speed request.
    for k in [0, 1, 2, 3, 4, 96, 97, 98, 99, 100] {
        pts[k].max_speed_mps = None;
    }
    let tr = time_path(&pts, &limits3(), &PathOptions::default()).unwrap();
    assert!(tr.slowdowns.is_empty(), "{:?}", tr.slowdowns);
    let mid = tr.state_at(tr.time_at(1.0));
    assert!((mid.sd - 0.15).abs() < 1e-6, "{}", mid.sd);
    let end = tr.state_at(tr.duration_s());
    assert_eq!(end.q, pts[100].q);
    assert!(end.sd.abs() < 1e-9);
    // Bang-coast-bang bound: joint 0 moves 1:1 with s, acc ≤ 0.97.
    assert!(tr.duration_s() > (2.0 - 0.16) / 0.15);
}

#[test]
fn velocity_limit_slows_painting_and_names_the_joint() {
    // Joint 1 moves 2:1 with s: its 0.3 rad/s caps ṡ at 0.15·0.97.
    let pts: Vec<PathPoint<3>> = (0..101)
        .map(|k| {
            let s = 0.02 * k as f64;
            PathPoint {
                s_m: s,
                q: [0.0, 2.0 * s, 0.0],
                cap_only: false,
                dq_ds: None,
                max_speed_mps: if (10..90).contains(&k) {
                    Some(0.2)
                } else {
                    None
                },
            }
        })
        .collect();
    let tr = time_path(&pts, &limits3(), &PathOptions::default()).unwrap();
    assert_eq!(tr.slowdowns.len(), 1, "{:?}", tr.slowdowns);
    let sl = tr.slowdowns[0];
    assert_eq!((sl.first_waypoint, sl.last_waypoint), (10, 89));
    assert_eq!(sl.binding, Binding::Velocity { joint: 1 });
    assert!(
        (sl.factor - 0.15 * 0.97 / 0.2).abs() < 1e-3,
        "{}",
        sl.factor
    );
}

#[test]
fn a_joint_held_at_its_bound_never_overshoots() {
    // Joint 2 climbs to 0.26 and is held there (a tilt clamped at its limit), then comes back.
    let pts: Vec<PathPoint<3>> = (0..40)
        .map(|k| {
            let s = 0.02 * k as f64;
            let held = (0.05 * k as f64).min(0.26).min(0.05 * (39 - k) as f64);
            PathPoint {
                s_m: s,
                q: [s, 0.0, held],
                cap_only: false,
                dq_ds: None,
                max_speed_mps: Some(0.1),
            }
        })
        .collect();
    let tr = time_path(&pts, &limits3(), &PathOptions::default()).unwrap();
    let samples = resample(std::slice::from_ref(&tr), 0.005).unwrap();
    for q in &samples.q {
        assert!(q[2] <= 0.26 + 1e-12 && q[2] >= -1e-12, "{q:?}");
    }
}

#[test]
fn painting_from_rest_is_reported() {
    let pts = straight_path(20, Some(0.15));
    let tr = time_path(&pts, &limits3(), &PathOptions::default()).unwrap();
    assert_eq!(
        tr.slowdowns.first().map(|s| (s.first_waypoint, s.binding)),
        Some((0, Binding::Rest))
    );
}

#[test]
fn bad_input_names_the_waypoint() {
    let mut pts = straight_path(5, None);
    pts[3].s_m = pts[2].s_m;
    assert!(matches!(
        time_path(&pts, &limits3(), &PathOptions::default()),
        Err(TimingError::NotIncreasing { index: 3, .. })
    ));
    let mut pts = straight_path(5, None);
    pts[2].max_speed_mps = Some(0.0);
    assert!(matches!(
        time_path(&pts, &limits3(), &PathOptions::default()),
        Err(TimingError::BadSpeed { index: 2, .. })
    ));
    pts[2].q[1] = f64::NAN;
    assert!(matches!(
        time_path(&pts, &limits3(), &PathOptions::default()),
        Err(TimingError::NotFinite { index: 2 })
    ));
    let mut lim = limits3();
    lim.acc[2] = 0.0;
    assert!(matches!(
        time_path(&straight_path(5, None), &lim, &PathOptions::default()),
        Err(TimingError::BadLimit {
            kind: "acc",
            joint: 2,
            ..
        })
    ));
    assert!(matches!(
        time_path(&straight_path(1, None), &limits3(), &PathOptions::default()),
        Err(TimingError::TooFewPoints(1))
    ));
    assert!(resample::<3>(&[], 0.0).is_err());
}

#[test]
fn air_move_is_synchronised_and_jerk_limited() {
    let lim = limits3();
    let tr = air_move([0.0, 0.0, 0.0], [1.0, -0.2, 0.3], &lim, DEFAULT_MARGIN).unwrap();
    let period = 0.005;
    let s = resample(std::slice::from_ref(&tr), period).unwrap();
    check_limits(&s, &lim, period).unwrap();
    let last = s.q[s.len() - 1];
    assert_eq!(last, [1.0, -0.2, 0.3]);
    // Synchronised: every joint is the same fraction of the way at every sample.
    for q in &s.q {
        let f = q[0];
        assert!((q[1] - -0.2 * f).abs() < 1e-12 && (q[2] - 0.3 * f).abs() < 1e-12);
    }
    // Jerk of the dominant joint (0) by third differences, within its limit.
    for k in 2..s.len() - 1 {
        let j = (s.q[k + 1][0] - 3.0 * s.q[k][0] + 3.0 * s.q[k - 1][0] - s.q[k - 2][0])
            / period.powi(3);
        assert!(j.abs() <= lim.jerk[0] * (1.0 + 1e-6), "{k} {j}");
    }
    // Short moves too (no cruise, no constant-acceleration phase).
    for d in [1e-4, 0.01, 0.05] {
        let tr = air_move([0.0; 3], [d, 0.0, 0.0], &lim, DEFAULT_MARGIN).unwrap();
        let s = resample(std::slice::from_ref(&tr), period).unwrap();
        check_limits(&s, &lim, period).unwrap();
        assert_eq!(s.q[s.len() - 1][0], d);
    }
    let still = air_move([0.3; 3], [0.3; 3], &lim, DEFAULT_MARGIN).unwrap();
    assert_eq!(still.duration_s(), 0.0);
}

#[test]
fn resample_steps_by_exactly_the_period_across_pieces() {
    let lim = limits3();
    let a = air_move([0.0; 3], [0.1, 0.05, 0.0], &lim, DEFAULT_MARGIN).unwrap();
    let mut pts = straight_path(30, Some(0.1));
    for p in &mut pts {
        p.q[0] += 0.1;
        p.q[1] += 0.05;
    }
    let b = time_path(&pts, &lim, &PathOptions::default()).unwrap();
    let pieces = [a, b];
    for period in [0.032, 0.005] {
        let s = resample(&pieces, period).unwrap();
        for (k, &t) in s.t_s.iter().enumerate() {
            assert_eq!(t, k as f64 * period);
        }
        let total = pieces[0].duration_s() + pieces[1].duration_s();
        assert!(s.t_s[s.len() - 1] >= total - 1e-9 && s.t_s[s.len() - 1] < total + period);
        assert_eq!(s.q[s.len() - 1], pts[29].q);
        assert!(s.piece.windows(2).all(|w| w[0] <= w[1]));
        check_limits(&s, &lim, period).unwrap();
    }
}

#[test]
fn gun_times_lead_the_arrival() {
    let mut pts = straight_path(60, Some(0.1));
    for p in pts.iter_mut().take(10) {
        p.max_speed_mps = None;
    }
    let tr = time_path(&pts, &limits3(), &PathOptions::default()).unwrap();
    let (on, off) = tr.gun_times(0.18, 1.0, 0.05, 0.02);
    let t_on = tr.time_at(0.18);
    assert!((tr.state_at(t_on).s - 0.18).abs() < 1e-9);
    assert!((on - (t_on - 0.05)).abs() < 1e-12);
    assert!((off - (tr.time_at(1.0) - 0.02)).abs() < 1e-12);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]
    #[test]
    fn fast_lp_matches_elimination(
        lines in proptest::collection::vec((-5.0f64..5.0, -5.0f64..5.0, 0.0f64..3.0), 1..20),
        cap in 0.0f64..10.0,
    ) {
        let fast = max_x(&lines, cap);
        let slow = max_x_exhaustive(&lines, cap);
        prop_assert!((fast - slow).abs() <= 1e-9 * (1.0 + slow.abs()), "{} vs {}", fast, slow);
    }
}

/// Random wiggly paths through 3 joints.
fn random_path() -> impl Strategy<Value = Vec<PathPoint<3>>> {
    proptest::collection::vec(
        (
            0.005f64..0.05,
            -0.02f64..0.02,
            -0.02f64..0.02,
            -0.05f64..0.05,
            proptest::option::of(0.02f64..0.5),
        ),
        2..60,
    )
    .prop_map(|steps| {
        let mut s = 0.0;
        let mut q = [0.0; 3];
        steps
            .into_iter()
            .enumerate()
            .map(|(k, (ds, d0, d1, d2, v))| {
                if k > 0 {
                    s += ds;
                    q = [q[0] + ds + d0, q[1] + d1, q[2] + d2];
                }
                PathPoint {
                    s_m: s,
                    q,
                    cap_only: false,
                    dq_ds: None,
                    max_speed_mps: v,
                }
            })
            .collect()
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]
    #[test]
    fn sampled_paths_never_exceed_a_limit(pts in random_path(), fine in any::<bool>(),
                                           scale in 0.2f64..3.0) {
        let base = limits3();
        let lim = JointLimits {
            vel: base.vel.map(|v| v * scale),
            acc: base.acc.map(|a| a * scale),
            jerk: base.jerk,
        };
        let period = if fine { 0.005 } else { 0.032 };
        let tr = time_path(&pts, &lim, &PathOptions::default()).unwrap();
        // No stalls: these paths are at most 3 m long at ≥ 0.02 m/s.
        prop_assert!(tr.duration_s() < 1000.0, "duration {}", tr.duration_s());
        let s = resample(std::slice::from_ref(&tr), period).unwrap();
        check_limits(&s, &lim, period).map_err(|e| TestCaseError::fail(e.to_string()))?;
        prop_assert_eq!(s.q[s.len() - 1], pts[pts.len() - 1].q);
        // Never faster than requested at a waypoint.
        for p in &pts {
            if let Some(v) = p.max_speed_mps {
                let st = tr.state_at(tr.time_at(p.s_m));
                prop_assert!(st.sd <= v * (1.0 + 1e-6), "{} > {}", st.sd, v);
            }
        }
    }

    #[test]
    fn air_moves_never_exceed_a_limit(a in proptest::array::uniform3(-2.0f64..2.0),
                                      b in proptest::array::uniform3(-2.0f64..2.0),
                                      fine in any::<bool>()) {
        let lim = limits3();
        let period = if fine { 0.005 } else { 0.032 };
        let tr = air_move(a, b, &lim, DEFAULT_MARGIN).unwrap();
        let s = resample(std::slice::from_ref(&tr), period).unwrap();
        check_limits(&s, &lim, period).map_err(|e| TestCaseError::fail(e.to_string()))?;
        prop_assert_eq!(s.q[0], a);
        prop_assert_eq!(s.q[s.len() - 1], b);
    }
}

proptest! {
    /// A join from any state within the limits (moving, accelerating) to
    /// any other ends where asked, stays in range, and its samples' first,
    /// second and third differences stay within the speed, acceleration and
    /// jerk limits.
    #[test]
    fn joins_end_where_asked_within_every_limit(
        q0 in proptest::array::uniform3(-1.0f64..1.0), q1 in proptest::array::uniform3(-1.0f64..1.0),
        f0 in proptest::array::uniform3(-0.8f64..0.8), f1 in proptest::array::uniform3(-0.8f64..0.8),
        g0 in proptest::array::uniform3(-0.5f64..0.5), g1 in proptest::array::uniform3(-0.5f64..0.5),
    ) {
        let lim = limits3();
        let state = |q: [f64; 3], f: [f64; 3], g: [f64; 3]| Kinematic {
            q,
            qd: std::array::from_fn(|j| f[j] * lim.vel[j]),
            qdd: std::array::from_fn(|j| g[j] * lim.acc[j]),
        };
        let (from, to) = (state(q0, f0, g0), state(q1, f1, g1));
        let range = [(-2.0, 2.0); 3];
        let tr = join_move(&from, &to, &lim, &range, DEFAULT_MARGIN).unwrap();
        let end = tr.state_at(tr.duration_s());
        for (j, &target) in q1.iter().enumerate() {
            prop_assert!((end.q[j] - target).abs() < 1e-8, "joint {j}: {} vs {target}", end.q[j]);
            prop_assert!((end.qd[j] - to.qd[j]).abs() < 1e-8);
        }
        let period = 0.005;
        let n = (tr.duration_s() / period).floor() as usize;
        let q: Vec<[f64; 3]> = (0..=n).map(|k| tr.state_at(k as f64 * period).q).collect();
        for k in 0..q.len() {
            #[allow(clippy::needless_range_loop)] // differences across samples
            for j in 0..3 {
                prop_assert!(q[k][j] >= -2.0 - 1e-9 && q[k][j] <= 2.0 + 1e-9);
                if k >= 3 {
                    let d3 = (q[k][j] - 3.0 * q[k - 1][j] + 3.0 * q[k - 2][j] - q[k - 3][j]) / period.powi(3);
                    prop_assert!(d3.abs() <= lim.jerk[j] * (1.0 + 1e-6), "joint {j} sample {k}: jerk {d3}");
                }
                if k >= 2 {
                    let d2 = (q[k][j] - 2.0 * q[k - 1][j] + q[k - 2][j]) / period.powi(2);
                    prop_assert!(d2.abs() <= lim.acc[j] * (1.0 + 1e-6), "joint {j} sample {k}: acceleration {d2}");
                }
                if k >= 1 {
                    let d1 = (q[k][j] - q[k - 1][j]) / period;
                    prop_assert!(d1.abs() <= lim.vel[j] * (1.0 + 1e-6), "joint {j} sample {k}: speed {d1}");
                }
            }
        }
    }
}
