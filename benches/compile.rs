//! Criterion benchmark of the whole compile pipeline (layout → knots →
//! stations → order → IK → time law → sealed job) for STOP and for a
//! 26-letter message stacked on six lines.

use basr::plan::compile::{compile_job, CompileRequest};
use criterion::{criterion_group, criterion_main, Criterion};

/// Every letter A–Z once, five letters a line (a 26-letter word is wider
/// than a lane at 8 ft).
const ALPHABET: &str = "ABCDE FGHIJ KLMNO PQRST UVWXY Z";

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("compile");
    g.sample_size(10);
    for (name, msg) in [("STOP", "STOP"), ("alphabet", ALPHABET)] {
        let req = CompileRequest::message(msg);
        g.bench_function(name, |b| {
            b.iter(|| compile_job(std::hint::black_box(&req)).expect("compiles"))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
