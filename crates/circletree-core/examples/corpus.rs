//! Encode every real polygon at one setting and print circles, bytes and time:
//! `cargo run --release -p circletree-core --example corpus -- 5 0.4 10`; with `CT_WITHIN=1`,
//! `encode_within` at the third number; `CT_NO_DECODE=1` skips the decode timing (for profiles);
//! `CT_THREADS=1` never starts a second thread.
#[path = "../tests/common/mod.rs"]
mod common;
use circletree_core::encode::{encode, encode_within, Call, Options};
use circletree_core::format::CircleTree;
use std::time::Instant;

fn main() {
    let a: Vec<f64> = std::env::args()
        .skip(1)
        .map(|s| s.parse().expect("number"))
        .collect();
    let o = Options {
        min_radius: a.first().copied().unwrap_or(5.0),
        overlap: a.get(1).copied().unwrap_or(0.4),
        dp_tolerance: a.get(2).copied(),
        max_error: a.get(3).copied(),
    };
    let (mut tb, mut tw, mut tt, mut t1) = (0usize, 0usize, 0.0, 0usize);
    // decode time (bytes -> validated value -> WKB at the default arc tolerance), v1 and v2 bytes
    let (mut d1, mut d2) = (0.0f64, 0.0f64);
    let no_decode = std::env::var("CT_NO_DECODE").is_ok();
    let decode_time = |bytes: &[u8]| {
        if no_decode {
            return 0.0;
        }
        let t = Instant::now();
        for _ in 0..5 {
            let v = CircleTree::from_stored_bytes(bytes).expect("reads back");
            if std::env::var("CT_PARSE_ONLY").is_err() {
                std::hint::black_box(circletree_core::decode::to_wkb(&v, None).expect("decodes"));
            }
            std::hint::black_box(v);
        }
        t.elapsed().as_secs_f64() / 5.0
    };
    // CT_THREADS=1: never a second thread (to compare against the single-threaded path)
    if let Ok(n) = std::env::var("CT_THREADS") {
        circletree_core::set_threads(n.parse().expect("CT_THREADS: a number"));
    }
    let only: Vec<String> = std::env::var("CT_ONLY")
        .map(|v| v.split(',').map(String::from).collect())
        .unwrap_or_default();
    let only: Vec<&str> = only.iter().map(|s| s.as_str()).collect();
    for s in common::load(&only) {
        let t = Instant::now();
        let res = if std::env::var("CT_WITHIN").is_ok() {
            encode_within(&s.wkb, o.dp_tolerance.expect("t"), Call::new(s.srid))
        } else {
            encode(&s.wkb, &o, Call::new(s.srid))
        }
        .map(|e| (e.value, e.report));
        let dt = t.elapsed().as_secs_f64();
        tt += dt;
        match res {
            Ok((ct, rep)) => {
                let bytes = ct.to_bytes();
                let b = bytes.len();
                // FNV-1a of the stored bytes: two runs' values compared exactly, not by size
                let hash = bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &x| {
                    (h ^ u64::from(x)).wrapping_mul(0x0100_0000_01b3)
                });
                let mut old = ct.clone();
                old.version = 1;
                let old_bytes = old.to_bytes();
                let b1 = old_bytes.len();
                d1 += decode_time(&old_bytes);
                d2 += decode_time(&ct.to_bytes());
                t1 += b1;
                tb += b;
                tw += s.wkb.len();
                let all: Vec<_> = ct.parts.iter().flatten().flatten().collect();
                let (i, e) = (
                    all.iter().filter(|c| c.r > 0).count(),
                    all.iter().filter(|c| c.r < 0).count(),
                );
                println!("{:28} n={:6} circles={:6} int={:5} ext={:5} zero={:6} repaired={:6} filt={:5} dp={:5} rounds={:3} grid={} bytes={:7} v1={:7} wkb={:8} ratio={:.3} fnv={hash:016x} {:.3}s",
                    s.name, s.npoints, all.len(), i, e, all.len() - i - e, ct.repaired, rep.filtered_circles, rep.dp_points, rep.rounds, ct.grid, b, b1, s.wkb.len(), b as f64 / s.wkb.len() as f64, dt);
            }
            Err(e) => println!("{:28} ERROR {e}", s.name),
        }
    }
    println!(
        "TOTAL bytes={tb} v1={t1} v2/v1={:.3} wkb={tw} ratio={:.4} time={tt:.2}s decode v1={d1:.4}s v2={d2:.4}s v2/v1={:.2}",
        tb as f64 / t1 as f64,
        tb as f64 / tw as f64,
        d2 / d1
    );
}
