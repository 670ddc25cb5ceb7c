//! Time law speed: a painting path of 10⁵ waypoints (a long message's worth) and air moves, sampled at 5 ms.

use basr::plan::timing::{
    air_move, resample, time_path, JointLimits, PathOptions, PathPoint, DEFAULT_MARGIN,
};
use criterion::{criterion_group, criterion_main, Criterion};

/// A wavy 5-joint path: 20 mm between waypoints, every tenth stroke-length gun off.
fn path(n: usize) -> Vec<PathPoint<5>> {
    (0..n)
        .map(|k| {
            let s = 0.02 * k as f64;
            let q = [
                1.2 + 0.3 * (0.2 * s).sin(),
                3.0 + 0.8 * (0.13 * s).cos(),
                0.5 * (0.9 * s).sin(),
                0.1 * (1.7 * s).sin(),
                0.1 + 0.02 * (0.5 * s).cos(),
            ];
            let width = 0.1 + 0.05 * (0.7 * s).sin().abs();
            let speed = if k % 200 < 180 {
                Some(6.0e-3 / width)
            } else {
                None
            };
            PathPoint {
                s_m: s,
                q,
                cap_only: false,
                dq_ds: None,
                max_speed_mps: speed,
            }
        })
        .collect()
}

fn limits() -> JointLimits<5> {
    JointLimits {
        vel: [0.2, 0.3, 0.52, 0.26, 0.2],
        acc: [0.5, 1.0, 5.2, 2.6, 2.0],
        jerk: [5.0, 10.0, 52.0, 26.0, 20.0],
    }
}

fn bench(c: &mut Criterion) {
    let lim = limits();
    let pts = path(100_000);
    c.bench_function("time_path 1e5 waypoints", |b| {
        b.iter(|| time_path(&pts, &lim, &PathOptions::default()).unwrap())
    });
    let tr = time_path(&pts, &lim, &PathOptions::default()).unwrap();
    c.bench_function("resample 1e5 waypoints at 5 ms", |b| {
        b.iter(|| resample(std::slice::from_ref(&tr), 0.005).unwrap())
    });
    c.bench_function("air_move", |b| {
        b.iter(|| {
            air_move(
                [1.0, 2.0, 0.0, 0.0, 0.1],
                [1.5, 3.5, 1.0, 0.1, 0.0],
                &lim,
                DEFAULT_MARGIN,
            )
            .unwrap()
        })
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = bench
}
criterion_main!(benches);
