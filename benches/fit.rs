//! Criterion benchmark of `basr fit` against `basr compile` for STOP: the
//! issue's figure is that re-planning a stop at the site takes no longer
//! than compiling it (benches/README.md). The fit is what the command
//! runs after reading its files: the least-squares pose and plane from
//! four measured reference points, then the job's marking planned again
//! with the fitted stop and surface (joints, timing, closed-loop
//! verification, film check).

use std::time::Duration;

use basr::job::reference::reference_points;
use basr::pipeline::compile::{compile_job, CompileRequest};
use basr::plan::fit::{fit, Measured};
use basr::plan::site::Site;
use criterion::{criterion_group, criterion_main, Criterion};

#[path = "../tests/common/noise.rs"]
mod noise;

use noise::Noise;

fn bench(c: &mut Criterion) {
    let job = compile_job(&CompileRequest::message("STOP")).expect("STOP compiles");
    // The case: the truck 0.25 m right, 0.30 m back and turned
    // 2.5° from the plan, standing on a road with a 2 % cross slope (its
    // frame leans with the road, so the road is level in the arm's frame,
    // 3 mm under the base), each coordinate read with up to ±2 mm of
    // noise (tests/site_fit.rs `fit_a_word`).
    let planned = &job.stations[0];
    let truth = basr::job::Station {
        x_m: planned.x_m + 0.25,
        y_m: planned.y_m - 0.30,
        heading_rad: planned.heading_rad + 2.5f64.to_radians(),
    };
    let mut noise = Noise(7);
    let points: Vec<Measured> = reference_points(&job, 0)
        .into_iter()
        .map(|r| {
            let b = truth.road_to_base(r.road_m);
            Measured {
                name: r.name,
                road: r.road_m,
                base: [
                    b[0] + 0.002 * noise.next(),
                    b[1] + 0.002 * noise.next(),
                    -0.003 + 0.002 * noise.next(),
                ],
            }
        })
        .collect();
    let mut g = c.benchmark_group("site");
    g.sample_size(10);
    g.measurement_time(Duration::from_secs(10));
    let req = CompileRequest::message("STOP");
    g.bench_function("compile STOP", |b| {
        b.iter(|| compile_job(std::hint::black_box(&req)).expect("compiles"))
    });
    g.bench_function("fit STOP stop 1", |b| {
        b.iter(|| {
            let f = fit(1, std::hint::black_box(&points), 0.01).expect("fits");
            let mut road = job.road.clone();
            road.planes = f.plane.into_iter().collect();
            let mut req = CompileRequest::message("STOP");
            req.site = Some(Site {
                stations: vec![f.station],
                fitted: 0,
                road,
                kept: job.summary.stops.clone(),
                painted: basr::plan::site::painted_passes(&job.samples, job.stations.len()),
            });
            compile_job(&req).expect("re-plans")
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
