//! Decode speed of format versions 1 and 2 on the same values: every polygon of tests/data
//! encoded once by `ct_encode(geom, t/2, 0.4, t)`, written in both versions, then read back
//! (`from_stored_bytes`, what `ct_decode` does to a stored datum) and rebuilt to WKB, many times.
//! `cargo run --release -p circletree-core --example decode_speed -- 10 25 100`
#[path = "../tests/common/mod.rs"]
mod common;
use circletree_core::format::CircleTree;
use std::hint::black_box;
use std::time::Instant;

/// Seconds for one pass over `values`, the best of 20 passes (the least disturbed by whatever
/// else the machine runs).
fn time(values: &[Vec<u8>], full: bool) -> f64 {
    (0..20)
        .map(|_| {
            let t = Instant::now();
            for b in values {
                let v = CircleTree::from_stored_bytes(b).expect("reads back");
                if full {
                    black_box(circletree_core::decode::to_wkb(&v, None).expect("decodes"));
                }
                black_box(v);
            }
            t.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

fn main() {
    let samples = common::load(&[]);
    println!("| t | circles | v1 bytes | v2 bytes | v1 parse ms | v2 parse ms | v1 decode ms | v2 decode ms | v2/v1 decode |");
    println!("|---|---|---|---|---|---|---|---|---|");
    for t in std::env::args().skip(1) {
        let t: f64 = t.parse().expect("a bound");
        let (mut v1, mut v2, mut n) = (Vec::new(), Vec::new(), 0);
        for s in &samples {
            let (mut ct, _) = common::encode_at(s, t, false).expect("encodes");
            n += ct.ncircles();
            v2.push(ct.to_bytes());
            ct.version = 1;
            v1.push(ct.to_bytes());
        }
        if let Ok(reps) = std::env::var("CT_PROFILE_PARSE") {
            // for a profiler: nothing but the version-2 parse, many times
            for _ in 0..reps.parse::<usize>().expect("a count") {
                time(&v2, false);
            }
            return;
        }
        let size = |v: &[Vec<u8>]| v.iter().map(Vec::len).sum::<usize>();
        let (p1, p2) = (time(&v1, false), time(&v2, false));
        let (d1, d2) = (time(&v1, true), time(&v2, true));
        println!(
            "| {t} | {n} | {} | {} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} |",
            size(&v1),
            size(&v2),
            p1 * 1e3,
            p2 * 1e3,
            d1 * 1e3,
            d2 * 1e3,
            d2 / d1
        );
    }
}
