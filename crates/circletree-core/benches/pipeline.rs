//! Each pipeline step on real polygons, so a slowdown shows where it happens:
//! `cargo bench -p circletree-core --bench pipeline`.
#[path = "../tests/common/mod.rs"]
mod common;

use circletree_core::encode::{encode, Call, Options};
use circletree_core::{
    check, decode, geom, geom::wkb, internals::douglas_peucker, internals::filter,
    internals::medial,
};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::hint::black_box;

fn steps(c: &mut Criterion) {
    let opts = Options {
        min_radius: 5.0,
        overlap: 0.4,
        dp_tolerance: Some(10.0),
        max_error: None,
    };
    for s in common::load(&["kapiti_island_linz", "sicily"]) {
        let mut shape = wkb::read(&s.wkb).expect("wkb").shape;
        geom::orient(&mut shape);
        let ring = shape.parts[0][0].clone();
        let cands = medial::candidates(&ring, &mut || {});
        let runs = filter::map_runs(&ring, &cands, 5.0, 5.0, &mut || {});
        let ct = encode(&s.wkb, &opts, Call::new(s.srid))
            .expect("encode")
            .value;
        let mut g = c.benchmark_group(format!("{} ({} vertices)", s.name, s.npoints));
        g.sample_size(10);
        g.bench_function(BenchmarkId::new("1 medial", ""), |b| {
            b.iter(|| medial::candidates(black_box(&ring), &mut || {}))
        });
        g.bench_function(BenchmarkId::new("2 filter map_runs", ""), |b| {
            b.iter(|| filter::map_runs(black_box(&ring), &cands, 5.0, 5.0, &mut || {}))
        });
        g.bench_function(BenchmarkId::new("2 filter select", ""), |b| {
            b.iter(|| filter::select(ring.len(), black_box(runs.clone()), 0.4, &mut || {}))
        });
        g.bench_function(BenchmarkId::new("3 douglas_peucker", ""), |b| {
            b.iter(|| douglas_peucker::keep(black_box(&ring), 10.0))
        });
        g.bench_function(
            BenchmarkId::new("encode (all steps + repair loop)", ""),
            |b| b.iter(|| encode(black_box(&s.wkb), &opts, Call::new(s.srid))),
        );
        g.bench_function(BenchmarkId::new("decode to WKB", ""), |b| {
            b.iter(|| decode::to_wkb(black_box(&ct), None))
        });
        g.bench_function(BenchmarkId::new("hausdorff", ""), |b| {
            b.iter(|| check::value_hausdorff(black_box(&ct), &shape.parts, &mut || {}))
        });
        g.finish();
    }
}

criterion_group!(benches, steps);
criterion_main!(benches);
