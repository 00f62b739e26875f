//! Stored values are forever: the version-1 bytes in `tests/data/golden_v1.tsv.gz` (written by
//! release 0.1.0's encoder, commit a6d793d) and the version-2 bytes in `golden_v2.tsv.gz` (written
//! by releases 0.2.0 and 0.3.0, fixed at commit 7964684 by `examples/write_golden.rs`) must keep
//! decoding, to the same geometry, in every later release, and must print and re-serialize to
//! exactly the same bytes.
use circletree_core::format::CircleTree;
use std::io::Read;

fn unhex(s: &str) -> Vec<u8> {
    (0..s.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(&s[i..i + 2], 16).expect("hex"))
        .collect()
}

#[test]
fn golden_v1_values_decode_unchanged() {
    check_fixture(1, 8);
}

#[test]
fn golden_v2_values_decode_unchanged() {
    check_fixture(2, 12);
}

fn check_fixture(version: u8, count: usize) {
    let path = format!(
        "{}/../../tests/data/golden_v{version}.tsv.gz",
        env!("CARGO_MANIFEST_DIR")
    );
    let mut text = String::new();
    flate2::read::GzDecoder::new(std::fs::File::open(path).expect("fixture"))
        .read_to_string(&mut text)
        .expect("gzip");
    let mut n = 0;
    for line in text.lines().skip(1) {
        let f: Vec<&str> = line.split('\t').collect();
        let (name, bytes, wkb) = (f[0], unhex(f[1]), unhex(f[2]));
        assert_eq!(
            bytes[0], version,
            "{name}: the fixture holds version-{version} values"
        );
        let ct = CircleTree::from_bytes(&bytes).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(ct.to_bytes(), bytes, "{name}: re-serialized bytes differ");
        let text = circletree_core::format::to_text(&ct);
        let back = circletree_core::format::from_text(&text).expect("text form");
        assert_eq!(back.to_bytes(), bytes, "{name}: text round trip");
        let decoded = circletree_core::decode::to_wkb(&ct, None).expect("decode");
        assert!(
            decoded == wkb,
            "{name}: decoded geometry differs from the fixture"
        );
        n += 1;
    }
    assert_eq!(n, count);
}
