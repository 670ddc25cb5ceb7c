//! Timing of font loading (parse, expand, validate) and of subdivision.

use basr::font::Font;
use criterion::{black_box, criterion_group, criterion_main, Criterion};

fn load(c: &mut Criterion) {
    let src = Font::embedded_source();
    c.bench_function("load and validate the embedded font", |b| {
        b.iter(|| Font::from_toml_str(black_box(src), "bench").map(|f| f.chars().len()))
    });
    let s = Font::embedded()
        .glyph('S')
        .map(|g| g.strokes.clone())
        .unwrap_or_default();
    c.bench_function("subdivide S at n = 60 (all strokes, both edges)", |b| {
        b.iter(|| {
            s.iter()
                .map(|st| st.rungs(black_box(60)).len())
                .sum::<usize>()
        })
    });
}

criterion_group!(benches, load);
criterion_main!(benches);
