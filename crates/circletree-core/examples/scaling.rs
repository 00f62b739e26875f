//! Encode time for one synthetic coastline of 1e3 .. 1e6 vertices:
//! `cargo run --release -p circletree-core --example scaling [n ...]`. Peak memory: run under
//! `/usr/bin/time -v`, one size per run. `CT_WITHIN=1`: `encode_within(geom, 10)` instead of
//! `encode(geom, 5, 0.4, 10)`; `CT_THREADS=1`: never a second thread.
//!
//! The coastline keeps its resolution as it grows, as real data does (a bigger island has more
//! vertices at the same spacing, not a denser outline): vertices 10 m apart along a disc of
//! circumference 10·n m, with bays and headlands at wavelengths of 20 km, 2 km and 200 m
//! (amplitudes 1 km, 100 m, 10 m) and 2 m of vertex noise.
use circletree_core::encode::{encode, encode_within, Call, Options};
use circletree_core::geom::Kind;
use std::time::Instant;

fn main() {
    let sizes: Vec<usize> = std::env::args()
        .skip(1)
        .map(|s| s.parse().expect("size"))
        .collect();
    let sizes = if sizes.is_empty() {
        vec![1_000, 10_000, 100_000, 1_000_000]
    } else {
        sizes
    };
    // CT_THREADS=1: never a second thread (to compare against the single-threaded path)
    if let Ok(n) = std::env::var("CT_THREADS") {
        circletree_core::set_threads(n.parse().expect("CT_THREADS: a number"));
    }
    for n in sizes {
        let mut seed = 12345u64;
        let radius = 10.0 * n as f64 / std::f64::consts::TAU;
        // whole numbers of waves around the ring, so that it closes smoothly
        let waves = |wavelength: f64| (10.0 * n as f64 / wavelength).round().max(1.0);
        let (k1, k2, k3) = (waves(20_000.0), waves(2_000.0), waves(200.0));
        let ring: Vec<[f64; 2]> = (0..n)
            .map(|i| {
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let noise = (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
                let t = i as f64 / n as f64 * std::f64::consts::TAU;
                let r = radius
                    + 1_000.0 * (k1 * t).sin()
                    + 100.0 * (k2 * t).sin()
                    + 10.0 * (k3 * t).sin()
                    + 4.0 * noise;
                [500_000.0 + r * t.cos(), 6_000_000.0 + r * t.sin()]
            })
            .collect();
        let wkb = circletree_core::geom::wkb::write(Kind::Polygon, &[vec![ring]]);
        let opts = Options {
            min_radius: 5.0,
            overlap: 0.4,
            dp_tolerance: Some(10.0),
            max_error: None,
        };
        let t = Instant::now();
        let (ct, rep) = if std::env::var("CT_WITHIN").is_ok() {
            encode_within(&wkb, 10.0, Call::new(32760))
        } else {
            encode(&wkb, &opts, Call::new(32760))
        }
        .map(|e| (e.value, e.report))
        .expect("encode");
        let secs = t.elapsed().as_secs_f64();
        let bytes = ct.to_bytes();
        // FNV-1a of the stored bytes: two builds' values compared exactly, not by size
        let fnv = bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &x| {
            (h ^ u64::from(x)).wrapping_mul(0x0100_0000_01b3)
        });
        println!(
            "n={n:8} time={secs:.3}s circles={} repaired={} rounds={} bytes={} wkb={} fnv={fnv:016x}",
            ct.ncircles(),
            ct.repaired,
            rep.rounds,
            bytes.len(),
            wkb.len()
        );
    }
}
