//! Criterion benchmark of the whole compile pipeline (layout → knots →
//! stations → order → IK → time law → sealed job) for 4, 26 and 100
//! letters; the throughput is in letters, so "elem/s" reads as letters per
//! second and the per-letter times can be compared (benches/README.md).
//! Each compile includes the closed-loop verification and its re-timing
//! and the film check (`CompileRequest::message` leaves `verify` and
//! `film` on), as `basr compile` does.

use std::time::Duration;

use basr::pipeline::compile::{compile_job, CompileRequest};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};

/// Every letter A–Z once, five letters a line (a 26-letter word is wider
/// than a lane at 8 ft).
const ALPHABET: &str = "ABCDE FGHIJ KLMNO PQRST UVWXY Z";

/// 100 letters on 23 lines: the standard pavement words a crew paints along
/// a corridor, one word a line (the longest, SCHOOL and SIGNAL, fill a 12 ft
/// lane at 8 ft), about 280 m of lane and one truck station a line.
const CORRIDOR: &str = "STOP AHEAD SCHOOL XING SLOW BUS ONLY PED XING KEEP CLEAR SIGNAL \
                            AHEAD YIELD AHEAD BIKE LANE TURN ONLY RIGHT TURN ONLY STOP";

fn letters(msg: &str) -> u64 {
    msg.chars().filter(|c| !c.is_whitespace()).count() as u64
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("compile");
    g.sample_size(10);
    for (name, msg, secs) in [
        ("STOP", "STOP", 5),
        ("alphabet", ALPHABET, 10),
        ("corridor", CORRIDOR, 30),
    ] {
        let req = CompileRequest::message(msg);
        assert!(
            req.verify && req.film,
            "the figure is for compile with its verification and film check"
        );
        // Ten samples of the 100-letter job take ~20 s on a loaded 2-core
        // machine; a longer window only repeats them.
        g.measurement_time(Duration::from_secs(secs));
        g.throughput(Throughput::Elements(letters(msg)));
        g.bench_function(format!("{name} ({} letters)", letters(msg)), |b| {
            b.iter(|| compile_job(std::hint::black_box(&req)).expect("compiles"))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
