//! Done criteria of the codec on every real polygon of tests/data/polygons.tsv.gz, at the three
//! settings of the issue and a coarse one: encoding succeeds, the rebuilt geometry is valid, keeps its parts and its
//! rings (with arcs stroked at the default tolerance and 300 times finer, judged by the exact checker
//! and, below 20,000 vertices, by `geo`'s OGC validation too), and its continuous Hausdorff distance to the original is at most max_error,
//! measured by `metrics` (arcs stroked a hundred times finer than the encoder's own check).
mod common;

use circletree_core::check::{problems, RingRef};
use circletree_core::encode::{encode, encode_within, Call, Options, Report};
use circletree_core::format::CircleTree;
use circletree_core::{check, decode, geom::wkb};
use geo::Validation;

fn check(min_radius: f64, dp: f64) {
    check_only(min_radius, dp, &[]);
}

/// [`check`] on the named polygons (all when empty).
fn check_only(min_radius: f64, dp: f64, names: &[&str]) {
    let opts = Options {
        min_radius,
        overlap: 0.4,
        dp_tolerance: Some(dp),
        max_error: None,
    };
    check_encoder(min_radius.max(dp), names, |s| {
        encode(&s.wkb, &opts, Call::new(s.srid)).map(|e| (e.value, e.report))
    });
}

/// The promise for any encoder of the corpus's polygons.
fn check_encoder(
    max_error: f64,
    names: &[&str],
    encoder: impl Fn(&common::Sample) -> circletree_core::Result<(CircleTree, Report)>,
) {
    let mut failures = Vec::new();
    for s in common::load(names) {
        let original = wkb::read(&s.wkb).expect("read").shape;
        let (ct, _) = match encoder(&s) {
            Ok(v) => v,
            Err(e) => {
                failures.push(format!("{}: {e}", s.name));
                continue;
            }
        };
        // stored bytes round trip
        let ct = CircleTree::from_bytes(&ct.to_bytes()).expect("stored bytes decode");
        assert_eq!(ct.srid, s.srid);
        assert_eq!(ct.parts.len(), original.parts.len(), "{}", s.name);
        // valid at the default arc tolerance (the grid) and far finer (Cyprus at (100, 0.4, 200)
        // was not, at a 300th of the grid, before the encoder checked the true arcs)
        for tol in [ct.grid_f64(), ct.grid_f64() / 300.0] {
            let polys = decode::polygons(&ct, tol);
            let refs: Vec<RingRef> = polys
                .iter()
                .enumerate()
                .flat_map(|(p, part)| {
                    part.iter().enumerate().map(move |(r, pts)| RingRef {
                        part: p,
                        ring: r,
                        pts,
                    })
                })
                .collect();
            if !problems(&refs, &mut || {}).is_empty() {
                failures.push(format!("{}: not valid at arc tolerance {tol}", s.name));
            }
            // geo's validation is independent but slow on large polygons: the smaller ones
            if s.npoints > 20_000 {
                continue;
            }
            let rebuilt = wkb::to_geo(&polys);
            if !rebuilt.is_valid() {
                failures.push(format!(
                    "{}: not valid at arc tolerance {tol}: {:?}",
                    s.name,
                    rebuilt.validation_errors()
                ));
            }
        }
        let h = check::value_hausdorff(&ct, &original.parts, &mut || {});
        if h > max_error {
            failures.push(format!("{}: Hausdorff {h} > {max_error}", s.name));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn every_polygon_at_5_10() {
    check(5.0, 10.0);
}

#[test]
fn every_polygon_at_25_50() {
    check(25.0, 50.0);
}

#[test]
fn every_polygon_at_100_200() {
    check(100.0, 200.0);
}

#[test]
fn every_polygon_at_250_500() {
    // Coarse: small islands of Chatham sat inside their neighbour's coarse rebuild, which was
    // never the ring blamed (0.2.0 before the fix: "rebuilt rings touch or cross").
    check(250.0, 500.0);
}

#[test]
fn every_polygon_within_10_25_100() {
    // ct_encode_within: every plan it keeps passed the same closed loop; checked again here.
    for t in [10.0, 25.0, 100.0] {
        check_encoder(t, &[], |s| {
            let (ct, bytes, report) = encode_within(&s.wkb, t, Call::new(s.srid))?.into_parts();
            // the bytes it hands the glue to store are the value's own
            assert_eq!(bytes, ct.to_bytes(), "{} at {t}", s.name);
            // the bounds that rank the plans hold the value's size
            let (lo, hi) = ct.size_bounds();
            assert!(lo <= bytes.len() && bytes.len() <= hi, "{} at {t}", s.name);
            Ok((ct, report))
        });
    }
}

#[test]
fn islands_at_kilometres() {
    // Rocks far smaller than max_error need a grid far finer than max_error/2 (0.2.0 stopped at a
    // hundredfold), and an island kept to its last vertex can sit inside its neighbour's rebuild.
    let names = [
        "chatham_island_linz",
        "isles_of_scilly",
        "cook_islands_south",
    ];
    check_only(2000.0, 5000.0, &names);
    check_only(20000.0, 50000.0, &names);
}

#[test]
fn kapiti_at_the_papers_scale() {
    // 2029 vertices at 13.6 m spacing, like the paper's Rarotonga.
    let s = common::load(&["kapiti_island_linz"]).pop().expect("kapiti");
    let opts = Options {
        min_radius: 5.0,
        overlap: 0.4,
        dp_tolerance: Some(10.0),
        max_error: None,
    };
    let e = encode(&s.wkb, &opts, Call::new(s.srid)).expect("encode");
    let (ct, report) = (e.value, e.report);
    let all: Vec<_> = ct.parts.iter().flatten().flatten().collect();
    let internal = all.iter().filter(|c| c.r > 0).count();
    let external = all.iter().filter(|c| c.r < 0).count();
    let zero = all.iter().filter(|c| c.r == 0).count();
    assert!(
        internal > 50 && external > 50 && zero > 0,
        "{internal} {external} {zero}"
    );
    // (0.1.0, on a grid of max_error/10, kept 488; 0.2.0's grid of about max_error/2 leaves less
    // of the budget to the circles, so the repair loop keeps more points, in fewer bytes)
    assert!(
        all.len() < s.npoints / 2,
        "{} circles for {} vertices",
        all.len(),
        s.npoints
    );
    assert!(report.filtered_circles > 100);
    // far smaller than the WKB
    assert!(ct.to_bytes().len() * 10 < s.wkb.len());
}
