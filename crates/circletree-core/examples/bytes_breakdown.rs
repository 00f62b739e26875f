//! Where the bytes go, per bound and data set: every polygon of tests/data (and of the held-out
//! set) encoded by `ct_encode(geom, t/2, 0.4, t)` and by `ct_encode_within(geom, t)`; prints CSV
//! (one row per data set, family, encoder and t) of format-version-1 bytes of the same circles,
//! version-2 bytes, and the version-2 bytes split into header, counts, flags, point deltas, circle
//! deltas and radii. Run by scripts/bench.sh:
//! `cargo run --release -p circletree-core --example bytes_breakdown -- 10 25 100`
#[path = "../tests/common/mod.rs"]
mod common;
use std::collections::BTreeMap;

#[derive(Default)]
struct Sum {
    polygons: usize,
    circles: usize,
    v1: usize,
    v2: usize,
    header: usize,
    bits: [f64; 5],
}

fn main() {
    let ts: Vec<f64> = std::env::args()
        .skip(1)
        .map(|s| s.parse().expect("a bound"))
        .collect();
    let mut sums: BTreeMap<(String, String, &str, String), Sum> = BTreeMap::new();
    for (dataset, file) in [("public", "polygons"), ("holdout", "holdout")] {
        let samples = common::load_file(file, &[]);
        for &t in &ts {
            for s in &samples {
                for encoder in ["ct_encode", "ct_encode_within"] {
                    let res = common::encode_at(s, t, encoder == "ct_encode_within");
                    let (mut ct, _) = res.unwrap_or_else(|e| panic!("{} at {t}: {e}", s.name));
                    let (header, b) = ct.breakdown();
                    let b = b.expect("version 2");
                    let v2 = ct.to_bytes().len();
                    ct.version = 1;
                    let v1 = ct.to_bytes().len();
                    for family in [s.family, "all"] {
                        let e = sums
                            .entry((dataset.into(), family.into(), encoder, format!("{t}")))
                            .or_default();
                        e.polygons += 1;
                        e.circles += ct.ncircles();
                        e.v1 += v1;
                        e.v2 += v2;
                        e.header += header;
                        for (k, v) in [b.counts, b.flags, b.point_deltas, b.circle_deltas, b.radii]
                            .into_iter()
                            .enumerate()
                        {
                            e.bits[k] += v;
                        }
                    }
                }
            }
        }
    }
    println!("dataset,family,encoder,t,polygons,circles,v1_bytes,v2_bytes,header_bytes,counts_bytes,flags_bytes,point_bytes,circle_bytes,radius_bytes");
    for ((d, f, e, t), s) in &sums {
        let b = s.bits.map(|x| x / 8.0);
        println!(
            "{d},{f},{e},{t},{},{},{},{},{},{:.0},{:.0},{:.0},{:.0},{:.0}",
            s.polygons, s.circles, s.v1, s.v2, s.header, b[0], b[1], b[2], b[3], b[4]
        );
    }
}
