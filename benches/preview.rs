//! Criterion benchmark of `basr preview` (deposition + metrics) for STOP at
//! 5 mm and 2 mm raster cells. Falls back to a synthetic ring when this
//! build cannot compile STOP yet (and says so).

#[path = "../tests/preview_common/mod.rs"]
mod preview_common;

use basr::paint::preview::{preview_job, Options};
use basr::pipeline::compile::{compile_job, CompileRequest};
use criterion::{criterion_group, criterion_main, Criterion};

fn bench(c: &mut Criterion) {
    let (name, job) = match compile_job(&CompileRequest::message("STOP")) {
        Ok(job) => ("STOP", job),
        Err(e) => {
            eprintln!("compile STOP failed ({e}); benchmarking a synthetic ring instead");
            ("ring", preview_common::ring_job(0.3, 0.5, 0.0, "none"))
        }
    };
    let mut group = c.benchmark_group("preview");
    group.sample_size(10);
    for mm in [5.0, 2.0] {
        let opts = Options {
            resolution_m: mm / 1000.0,
            ..Options::default()
        };
        group.bench_function(format!("{name} {mm} mm"), |b| {
            b.iter(|| preview_job(&job, &opts).expect("preview"))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
