//! Simulator speed: the closed-loop simulation of STOP (compiled here, in
//! process, with `basr compile STOP`'s defaults) under each controller.
//!
//! Criterion's throughput is the job's duration in whole simulated seconds,
//! so "elem/s" reads as simulated seconds per wall-clock second: how many
//! times faster than real time the simulator runs. A compile or simulate
//! error stops the bench with its message: a benchmark of a failed run
//! would time nothing.

use basr::pipeline::compile::{compile_job, CompileRequest};
use basr::sim::{self, ControllerKind, SimModel};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};

fn bench(c: &mut Criterion) {
    let job = compile_job(&CompileRequest::message("STOP"))
        .unwrap_or_else(|e| panic!("compile STOP failed, nothing to simulate: {e}"));
    let model = SimModel::from_robot(job.robot.basr().expect("a BASR job"))
        .unwrap_or_else(|e| panic!("STOP's robot cannot be simulated: {e}"));
    let duration_s = job.samples.len().saturating_sub(1) as f64 * job.control_period_s;
    let mut g = c.benchmark_group(format!("simulate STOP ({duration_s:.1} s)"));
    g.sample_size(10);
    // Whole seconds: criterion counts integer elements (188.8 s → 189, 0.1 %).
    g.throughput(Throughput::Elements(duration_s.round() as u64));
    for k in ControllerKind::ALL {
        let opts = sim::Options {
            controller: k,
            ..Default::default()
        };
        g.bench_function(k.name(), |b| {
            b.iter(|| {
                let o = sim::simulate(&job, &model, &opts, &mut |_, _| {})
                    .unwrap_or_else(|e| panic!("simulate STOP with {}: {e}", k.name()));
                criterion::black_box(o.report.max_error_m)
            })
        });
    }
    g.finish();
    // 100 plants of STOP within ±10 % (issue 12: ≤ 30 s on 2 cores), rayon
    // over the machine's cores
    let mut g = c.benchmark_group("simulate STOP --plants 100 --spread 0.1");
    g.sample_size(10);
    let plants = sim::plants::PlantsOptions {
        n: 100,
        spread: 0.1,
        seed: 7,
    };
    g.bench_function("sjct", |b| {
        b.iter(|| {
            let s = sim::plants::run(&job, &model, &sim::Options::default(), &plants)
                .unwrap_or_else(|e| panic!("100 plants of STOP: {e}"));
            criterion::black_box(s.p95_max_error_m)
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
