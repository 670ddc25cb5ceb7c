//! Simulator speed: simulated seconds per wall-clock second on one core.
//!
//! Criterion's throughput is set to the job's duration in milliseconds, so
//! "elem/s" reads as simulated milliseconds per wall-clock second (divide by
//! 1000 for the speed-up factor). Uses STOP when `STOP.job.json` exists in
//! the working folder (compile it first), else the synthetic letter job.

use basr::sim::{self, synthetic, ControllerKind, SimModel};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};

fn job() -> (String, basr::job::Job) {
    match basr::job::Job::read(std::path::Path::new("STOP.job.json")) {
        Ok(j) => ("STOP".into(), j),
        Err(_) => ("synthetic letter".into(), synthetic::letter_job()),
    }
}

fn bench(c: &mut Criterion) {
    let (name, job) = job();
    let model = SimModel::basr();
    let duration_ms =
        (job.samples.len().saturating_sub(1) as f64 * job.control_period_s * 1000.0) as u64;
    let mut g = c.benchmark_group(format!("simulate {name}"));
    g.sample_size(10);
    g.throughput(Throughput::Elements(duration_ms));
    for k in ControllerKind::ALL {
        g.bench_function(k.name(), |b| {
            b.iter(|| {
                let o = sim::simulate(
                    &job,
                    &model,
                    &sim::Options {
                        controller: k,
                        ..Default::default()
                    },
                    &mut |_, _| {},
                );
                criterion::black_box(o.map(|o| o.report.max_error_m).unwrap_or(f64::NAN))
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
