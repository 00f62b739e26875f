//! Arbitrary rings to both encoders: a clean refusal, or a value that reads back, rebuilds valid
//! (by `geo`'s OGC validation, not the encoder's own checker) and within its bound. The first
//! byte picks the bound and the encoder; then either a star-shaped shell with an optional hole
//! (always valid: most inputs exercise the encoder) or free points (mostly invalid: the encoder
//! must not panic on what PostGIS would have refused first).
#![no_main]
use circletree_core::encode::{encode, encode_within, Call, HostCheck, Options, Validity};
use circletree_core::format::CircleTree;
use circletree_core::geom::{Kind, Pt};
use circletree_core::{check, decode, geom::wkb, Error};
use geo::Validation;
use libfuzzer_sys::fuzz_target;

fn star(n: &[u8], r0: f64, scale: f64) -> Vec<Pt> {
    let k = n.len();
    n.iter()
        .enumerate()
        .map(|(i, &b)| {
            let t = i as f64 / k as f64 * std::f64::consts::TAU;
            let r = r0 + f64::from(b) * scale;
            [r * t.cos(), r * t.sin()]
        })
        .collect()
}

fn ring_area(r: &[Pt]) -> f64 {
    r.iter()
        .zip(r.iter().cycle().skip(1))
        .map(|(a, b)| a[0] * b[1] - a[1] * b[0])
        .sum::<f64>()
        / 2.0
}

fuzz_target!(|data: &[u8]| {
    if data.len() < 5 {
        return;
    }
    let (head, body) = data.split_at(2);
    let bound = [0.5, 2.0, 10.0, 50.0][usize::from(head[0] & 3)];
    let within = head[0] & 4 != 0;
    let mut rings = Vec::new();
    if head[0] & 8 != 0 {
        // free points, 2 bytes a coordinate
        let pts: Vec<Pt> = body
            .chunks_exact(4)
            .take(300)
            .map(|c| {
                [
                    f64::from(i16::from_le_bytes([c[0], c[1]])),
                    f64::from(i16::from_le_bytes([c[2], c[3]])),
                ]
            })
            .collect();
        rings.push(pts);
    } else {
        let split = usize::from(head[1]) % body.len();
        let (shell, hole) = body.split_at(split.max(3).min(body.len()));
        let scale = 1.0 + f64::from(head[1] >> 4) * 4.0;
        rings.push(star(&shell[..shell.len().min(600)], 300.0 * scale, scale));
        if hole.len() >= 3 {
            let mut h = star(&hole[..hole.len().min(200)], 10.0 * scale, scale);
            h.reverse();
            rings.push(h);
        }
    }
    if rings[0].len() < 3 {
        return;
    }
    let parts = vec![rings];
    // geo's OGC validation passes a ring whose edges fold back onto each other (zero area, e.g.
    // (0 0, 1000 0, 18 0, 0 0): the fuzzer's first finding); PostGIS calls that a self-intersection
    // and the SQL wrappers refuse it before the encoder sees it, so it is not a valid polygon here.
    let valid =
        wkb::to_geo(&parts).is_valid() && parts.iter().flatten().all(|r| ring_area(r).abs() > 0.0);
    let input = wkb::write(Kind::Polygon, &parts);
    let o = Options {
        min_radius: bound / 2.0,
        overlap: 0.4,
        dp_tolerance: Some(bound),
        max_error: None,
    };
    let res = if within {
        encode_within(&input, bound, Call::new(0))
    } else {
        encode(&input, &o, Call::new(0))
    }
    .map(|e| e.value);
    if head[0] & 16 != 0 {
        // the host's verdict asked beside the encoder (ct_encode and ct_encode_within in SQL since
        // 0.6.0; these inputs are below the size that starts a thread, so the order is the
        // sequential one): a valid verdict gives what the verdict passed in gives, an invalid one
        // the host's reason, or the error found while reading, as before
        let call = Call::new(0).validity(Validity::Host(HostCheck {
            is_valid: Box::new(|| valid),
            reason: Box::new(|| "host says no".to_string()),
        }));
        let host = if within {
            encode_within(&input, bound, call)
        } else {
            encode(&input, &o, call)
        }
        .map(|e| e.value);
        match (&host, &res) {
            (Ok(a), Ok(b)) if valid => assert_eq!(a.to_bytes(), b.to_bytes()),
            (Err(a), Err(b)) if valid => assert_eq!(a.to_string(), b.to_string()),
            (Err(Error::InvalidPolygon(r)), _) if !valid => assert_eq!(r, "host says no"),
            (Err(a), Err(b)) if !valid => assert_eq!(a.to_string(), b.to_string()),
            _ => {
                panic!("host check {host:?} against the verdict passed in {res:?} (valid: {valid})")
            }
        }
    }
    let ct = match res {
        Ok(ct) => ct,
        Err(Error::InvalidParameter { .. }) => return,
        Err(e) => {
            assert!(!valid, "a valid polygon was refused: {e}");
            return;
        }
    };
    if !valid {
        return;
    }
    let back = CircleTree::from_bytes(&ct.to_bytes()).expect("what the encoder returns reads back");
    assert_eq!(back, ct);
    let g = ct.grid_f64();
    for tol in [g, g / 100.0] {
        let rebuilt = decode::polygons(&ct, tol);
        let geo = wkb::to_geo(&rebuilt);
        assert!(
            geo.is_valid(),
            "invalid at arc tolerance {tol}: {:?}",
            geo.validation_errors()
        );
    }
    let h = check::value_hausdorff(&ct, &parts, &mut || {});
    assert!(h <= bound * (1.0 + 1e-9), "Hausdorff {h} > {bound}");
});
