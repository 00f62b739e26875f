//! Time the quick validity proof ([`circletree_core::check::proves_valid`]) against the core's own strict
//! check ([`circletree_core::check::problems`]) on every real polygon of a set:
//! `cargo run --release -p circletree-core --example proof_speed -- [polygons|holdout]`.
//! Prints, per set, how many inputs were proved valid and the best of five summed times.
#[path = "../tests/common/mod.rs"]
mod common;
use circletree_core::check::{problems, RingRef};
use std::time::Instant;

fn main() {
    let file = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "polygons".to_string());
    let inputs: Vec<_> = common::load_file(&file, &[])
        .into_iter()
        .map(|s| circletree_core::geom::wkb::read(&s.wkb).expect("reads"))
        .collect();
    let (mut proved, mut given) = (0, 0);
    let (mut best_proof, mut best_check) = (f64::MAX, f64::MAX);
    for _ in 0..5 {
        proved = 0;
        given = 0;
        let t = Instant::now();
        for i in &inputs {
            given += i.as_given as usize;
            proved +=
                (i.as_given && circletree_core::check::proves_valid(&i.shape, &mut || {})) as usize;
        }
        best_proof = best_proof.min(t.elapsed().as_secs_f64());
        let t = Instant::now();
        for i in &inputs {
            let rings: Vec<RingRef> = i
                .shape
                .parts
                .iter()
                .enumerate()
                .flat_map(|(part, p)| {
                    p.iter()
                        .enumerate()
                        .map(move |(ring, pts)| RingRef { part, ring, pts })
                })
                .collect();
            std::hint::black_box(problems(&rings, &mut || {}));
        }
        best_check = best_check.min(t.elapsed().as_secs_f64());
    }
    println!(
        "{file}: {} inputs, {given} as given, {proved} proved; proof {:.1} ms, validity::problems {:.1} ms",
        inputs.len(),
        best_proof * 1e3,
        best_check * 1e3
    );
}
