//! Shared by the integration tests and benches: the real polygons shipped in tests/data.
#![allow(dead_code)]

use circletree_core::encode::{encode, encode_within, Call, Options, Report};
use circletree_core::format::CircleTree;
use std::io::Read;
use std::str::FromStr;

/// A sample encoded at bound `t` as the benchmarks compare encoders: `ct_encode(geom, t/2, 0.4,
/// t)`, or with `within`, `ct_encode_within(geom, t)`.
pub fn encode_at(
    s: &Sample,
    t: f64,
    within: bool,
) -> circletree_core::Result<(CircleTree, Report)> {
    if within {
        return encode_within(&s.wkb, t, Call::new(s.srid)).map(|e| (e.value, e.report));
    }
    let o = Options {
        min_radius: t / 2.0,
        overlap: 0.4,
        dp_tolerance: Some(t),
        max_error: None,
    };
    encode(&s.wkb, &o, Call::new(s.srid)).map(|e| (e.value, e.report))
}

/// One real polygon: name, SRID, ST_NPoints, WKB.
pub struct Sample {
    pub name: String,
    /// The data set the polygon comes from: `GSHHG`, `LINZ` or `Stats NZ`.
    pub family: &'static str,
    pub srid: i32,
    pub npoints: usize,
    pub wkb: Vec<u8>,
}

/// All polygons of tests/data/polygons.tsv.gz (or only those named); with `CT_DATA=holdout` in
/// the environment, those of tests/data/holdout.tsv.gz instead.
pub fn load(only: &[&str]) -> Vec<Sample> {
    let file = match std::env::var("CT_DATA").as_deref() {
        Ok("holdout") => "holdout",
        _ => "polygons",
    };
    load_file(file, only)
}

/// The polygons of tests/data/`file`.tsv.gz (or only those named).
pub fn load_file(file: &str, only: &[&str]) -> Vec<Sample> {
    let path = format!(
        "{}/../../tests/data/{file}.tsv.gz",
        env!("CARGO_MANIFEST_DIR")
    );
    let mut text = String::new();
    flate2::read::GzDecoder::new(std::fs::File::open(&path).expect("tests/data/*.tsv.gz"))
        .read_to_string(&mut text)
        .expect("gzip");
    let mut out = Vec::new();
    for line in text.lines().skip(1) {
        let f: Vec<&str> = line.split('\t').collect();
        if !only.is_empty() && !only.contains(&f[0]) {
            continue;
        }
        let wkt = wkt::Wkt::<f64>::from_str(f[4]).expect("wkt");
        let geom: geo_types::Geometry<f64> = wkt.try_into().expect("geometry");
        let mut wkb = Vec::new();
        wkb::writer::write_geometry(&mut wkb, &geom, &Default::default()).expect("wkb");
        out.push(Sample {
            name: f[0].to_string(),
            family: if f[1].starts_with("GSHHG") {
                "GSHHG"
            } else if f[1].starts_with("LINZ") {
                "LINZ"
            } else {
                "Stats NZ"
            },
            srid: f[2].parse().expect("srid"),
            npoints: f[3].parse().expect("npoints"),
            wkb,
        });
    }
    out
}
