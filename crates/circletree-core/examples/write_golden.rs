//! Writes a golden fixture of the format version this release writes:
//! `cargo run --release -p circletree-core --example write_golden -- tests/data/golden_vN.tsv`
//! (then gzip it). Run once, when a format version is new; an existing fixture is frozen forever
//! (`tests/golden.rs` reads it in every later release).
#[path = "../tests/common/mod.rs"]
mod common;
use circletree_core::encode::{encode, encode_within, Call, Options};
use std::io::Write;

fn hex(b: &[u8]) -> String {
    b.iter().map(|x| format!("{x:02x}")).collect()
}

fn main() {
    let path = std::env::args().nth(1).expect("output path");
    let mut out = std::fs::File::create(path).expect("create");
    writeln!(out, "name\tbytes\tdecoded_wkb").expect("write");
    let names = [
        "lake_tahoe",
        "rarotonga",
        "isles_of_scilly",
        "kapiti_island_linz",
    ];
    for s in common::load(&names) {
        for (r, t) in [(5.0, 10.0), (50.0, 100.0)] {
            let o = Options {
                min_radius: r,
                overlap: 0.4,
                dp_tolerance: Some(t),
                max_error: None,
            };
            let ct = encode(&s.wkb, &o, Call::new(s.srid))
                .expect("encodes")
                .value;
            let wkb = circletree_core::decode::to_wkb(&ct, None).expect("decodes");
            let name = format!("{}@encode({r},0.4,{t})", s.name);
            writeln!(out, "{name}\t{}\t{}", hex(&ct.to_bytes()), hex(&wkb)).expect("write");
        }
        let t = 25.0;
        let ct = encode_within(&s.wkb, t, Call::new(s.srid))
            .expect("encodes")
            .value;
        let wkb = circletree_core::decode::to_wkb(&ct, None).expect("decodes");
        let name = format!("{}@encode_within({t})", s.name);
        writeln!(out, "{name}\t{}\t{}", hex(&ct.to_bytes()), hex(&wkb)).expect("write");
    }
}
