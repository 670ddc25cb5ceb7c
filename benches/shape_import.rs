//! Timing of what `basr import blob.svg --shape-height-m 2.5 -o blob.toml`
//! waits for: read an SVG of 1 000 cubic path segments, resolve it into
//! regions, decompose it into candidate strokes, compile and preview the
//! candidates the predictor ranks first until one is good
//! (`plan::shapes::import_measured`), check the kept one's font loads
//! back and write it (issue 14: under 2 s).

use basr::shape::Size;
use criterion::{black_box, criterion_group, criterion_main, Criterion};

/// A closed wavy blob with a hole: 1 000 cubic segments in all.
fn svg() -> String {
    let ring = |r: f64, n: usize, wave: f64| {
        let mut d = String::new();
        let pt = |i: usize| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            let rr = r * (1.0 + wave * (7.0 * a).sin());
            (500.0 + rr * a.cos(), 500.0 + rr * a.sin())
        };
        let (x0, y0) = pt(0);
        d.push_str(&format!("M {x0:.3},{y0:.3} "));
        for i in 0..n {
            let (a, b) = (pt(i), pt(i + 1));
            let (m1, m2) = (
                (a.0 + (b.0 - a.0) / 3.0, a.1 + (b.1 - a.1) / 3.0),
                (a.0 + 2.0 * (b.0 - a.0) / 3.0, a.1 + 2.0 * (b.1 - a.1) / 3.0),
            );
            d.push_str(&format!(
                "C {:.3},{:.3} {:.3},{:.3} {:.3},{:.3} ",
                m1.0, m1.1, m2.0, m2.1, b.0, b.1
            ));
        }
        d.push('Z');
        d
    };
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 1000 1000\">\
         <path fill-rule=\"evenodd\" d=\"{} {}\"/></svg>",
        ring(450.0, 700, 0.05),
        ring(200.0, 300, 0.05)
    )
}

fn import(c: &mut Criterion) {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("blob.svg");
    std::fs::write(&path, svg()).expect("write the SVG");
    let robot = basr::robot::AnyRobot::load_or_default(None).expect("embedded robot");
    let out = dir.path().join("blob.toml");
    let mut g = c.benchmark_group("shape");
    g.sample_size(10);
    g.bench_function(
        "basr import of an SVG of 1000 cubic segments (2.5 m)",
        |b| {
            b.iter(|| {
                basr::pipeline::shapes::import_to_file(
                    black_box(&path),
                    Size::HeightM(2.5),
                    &robot,
                    &out,
                )
                .map(|i| i.decomposition.strokes.len())
                .expect("imports")
            })
        },
    );
    g.finish();
}

criterion_group!(benches, import);
criterion_main!(benches);
