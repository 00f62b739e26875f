//! What nested levels would cost, measured before format 3 is written (issue "The circle tree").
//! For every polygon of a set, levels k = 0 .. n-1 with bounds e0 × s^k (s = 4 unless given), chosen coarsest first by
//! the encoder's fewest-points search (`min_points`) on the original ring, each level keeping the
//! coarser level's points, so the levels nest. Level k's coordinates lie on a grid of g0 × R^k
//! (R = 1 and R = s; g0: the grid `ct_encode_within(geom, e0)` chose). The stream is priced by format 2's adaptive
//! models (`Meter`): the coarsest level as format 2 codes points (a delta from the previous one);
//! then per finer level, each coarser point's correction to the finer grid, and per segment of
//! the level above the number of points inserted and each point's delta from the point that
//! spaces the rest evenly to the segment's end.
//! Not checked here: validity of the coarse levels, touch points, the repair loop's points.
//! Prints CSV per set, R and level: points, the prefix's bytes (stream only), and
//! `ct_encode_within(geom, e_k)` alone (its points, stream and header bytes).
//! `cargo run --release -p circletree-core --example levels -- 10 4 [4]` (e0, levels, s)
#[path = "../tests/common/mod.rs"]
mod common;
use circletree_core::encode::{encode_within, Call};
use circletree_core::geom::Pt;
use circletree_core::internals::{class, min_points, IntModel, Meter, Sink};

type P = (i64, i64);

struct Models {
    count: IntModel,
    corr: [IntModel; 2],
    dx: IntModel,
    dy: IntModel,
}

impl Models {
    fn new(extent: u64, n: usize, ratio: i64) -> Models {
        let d = IntModel::expecting(class(extent.saturating_mul(3) / n.max(1) as u64));
        let c = IntModel::expecting(class(ratio as u64 / 2));
        Models {
            count: IntModel::expecting(4),
            corr: [c.clone(), c],
            dx: d.clone(),
            dy: d,
        }
    }
}

/// Bits of each prefix, finest level first. `levels[k][ring]`: indices kept (ascending);
/// `coords[k][ring][i]`: vertex i on level k's grid.
fn nested(
    levels: &[Vec<Vec<usize>>],
    coords: &[Vec<Vec<P>>],
    extent0: u64,
    ratio: i64,
) -> Vec<f64> {
    let nl = levels.len();
    let mut m = Meter::default();
    let mut out = vec![0.0; nl];
    let top = nl - 1;
    let scale = ratio.pow(top as u32) as u64;
    let n: usize = levels[top].iter().map(Vec::len).sum();
    let mut md = Models::new(extent0 / scale, n, ratio);
    let mut at = (0, 0);
    for (r, keep) in levels[top].iter().enumerate() {
        m.int(&mut md.count, keep.len() as i64);
        for &i in keep {
            let p = coords[top][r][i];
            m.int(&mut md.dx, p.0 - at.0);
            m.int(&mut md.dy, p.1 - at.1);
            at = p;
        }
    }
    out[top] = m.bits();
    for k in (0..top).rev() {
        let n: usize = levels[k].iter().map(Vec::len).sum();
        let mut md = Models::new(extent0 / ratio.pow(k as u32) as u64, n, ratio);
        for (r, up) in levels[k + 1].iter().enumerate() {
            if ratio > 1 {
                for &i in up {
                    let (f, c) = (coords[k][r][i], coords[k + 1][r][i]);
                    m.int(&mut md.corr[0], f.0 - ratio * c.0);
                    m.int(&mut md.corr[1], f.1 - ratio * c.1);
                }
            }
            let here = &levels[k][r];
            let nr = coords[k][r].len();
            let mut h = 0;
            for (j, &a) in up.iter().enumerate() {
                let b = up.get(j + 1).copied().unwrap_or(up[0] + nr);
                let mut ins = Vec::new();
                while h < here.len() && here[h] <= a {
                    h += 1;
                }
                while h < here.len() && here[h] < b {
                    ins.push(here[h]);
                    h += 1;
                }
                // the ring's last segment wraps: indices below the first anchor
                if j + 1 == up.len() {
                    ins.extend(here.iter().filter(|&&i| i < up[0]));
                }
                m.int(&mut md.count, ins.len() as i64);
                let end = coords[k][r][b % nr];
                let mut prev = coords[k][r][a];
                for (i, &q) in ins.iter().enumerate() {
                    let q = coords[k][r][q];
                    let left = (ins.len() - i + 1) as i64;
                    let base = (
                        prev.0 + (end.0 - prev.0) / left,
                        prev.1 + (end.1 - prev.1) / left,
                    );
                    m.int(&mut md.dx, q.0 - base.0);
                    m.int(&mut md.dy, q.1 - base.1);
                    prev = q;
                }
            }
        }
        out[k] = m.bits();
    }
    out
}

fn main() {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .map(|s| s.parse().expect("a number"))
        .collect();
    let e0 = args.first().copied().unwrap_or(10.0);
    let nl = args.get(1).copied().unwrap_or(4.0) as usize;
    let step = args.get(2).copied().unwrap_or(4.0);
    let bounds: Vec<f64> = (0..nl).map(|k| e0 * step.powi(k as i32)).collect();
    let ratios = [1i64, step as i64];
    println!("set,ratio,level,bound,points,prefix_stream_bytes,single_points,single_stream_bytes,single_header_bytes");
    for set in ["polygons", "holdout", "small"] {
        let samples = common::load_file(set, &[]);
        let mut points = vec![vec![0usize; nl]; ratios.len()];
        let mut bits = vec![vec![0.0; nl]; ratios.len()];
        let mut single = vec![(0usize, 0usize, 0usize); nl];
        for s in &samples {
            for (k, &e) in bounds.iter().enumerate() {
                let one = encode_within(&s.wkb, e, Call::new(s.srid))
                    .expect("encodes")
                    .value;
                let (header, _) = one.breakdown();
                single[k].0 += one.ncircles();
                single[k].1 += one.to_bytes().len() - header;
                single[k].2 += header;
            }
            let ct = encode_within(&s.wkb, e0, Call::new(s.srid))
                .expect("encodes")
                .value;
            let g0 = ct.grid.to_f64();
            let b = ct.bbox.expect("not empty");
            let extent0 = ((b[2] - b[0]) + (b[3] - b[1])) as u64;
            let (ox, oy) = (b[0] as f64 * g0, b[1] as f64 * g0);
            let input = circletree_core::geom::wkb::read(&s.wkb).expect("wkb");
            let rings: Vec<&Vec<Pt>> = input.shape.parts.iter().flatten().collect();
            for (ri, &ratio) in ratios.iter().enumerate() {
                let grids: Vec<f64> = (0..nl)
                    .map(|k| g0 * (ratio as f64).powi(k as i32))
                    .collect();
                let coords: Vec<Vec<Vec<P>>> = grids
                    .iter()
                    .map(|&g| {
                        rings
                            .iter()
                            .map(|r| {
                                r.iter()
                                    .map(|p| {
                                        (
                                            ((p[0] - ox) / g).round() as i64,
                                            ((p[1] - oy) / g).round() as i64,
                                        )
                                    })
                                    .collect()
                            })
                            .collect()
                    })
                    .collect();
                let mut levels: Vec<Vec<Vec<usize>>> = vec![Vec::new(); nl];
                for k in (0..nl).rev() {
                    let g = grids[k];
                    let snap = move |p: Pt| {
                        [
                            ((p[0] - ox) / g).round() * g + ox,
                            ((p[1] - oy) / g).round() * g + oy,
                        ]
                    };
                    levels[k] = rings
                        .iter()
                        .enumerate()
                        .map(|(r, ring)| {
                            let fixed = if k + 1 < nl {
                                levels[k + 1][r].clone()
                            } else {
                                Vec::new()
                            };
                            min_points(ring, bounds[k], &fixed, &snap, &mut || {})
                        })
                        .collect();
                }
                for k in 0..nl {
                    points[ri][k] += levels[k].iter().map(Vec::len).sum::<usize>();
                }
                for (k, v) in nested(&levels, &coords, extent0, ratio)
                    .into_iter()
                    .enumerate()
                {
                    bits[ri][k] += v;
                }
            }
        }
        for (ri, ratio) in ratios.iter().enumerate() {
            for k in 0..nl {
                println!(
                    "{set},{ratio},{k},{},{},{:.0},{},{},{}",
                    bounds[k],
                    points[ri][k],
                    bits[ri][k] / 8.0,
                    single[k].0,
                    single[k].1,
                    single[k].2
                );
            }
        }
    }
}
