//! What static (predefined) tables would cost against format 2's adaptive models, measured
//! before format 3's decoder is written (issue "The circle tree", item 4). Every polygon is encoded
//! by `ct_encode_within(geom, t)` and `ct_encode(geom, t/2, 0.4, t)`; its circles are walked in
//! format 2's order and model (counts, kind flags, radii, and the deltas by this and the
//! previous circle's kind, each delta model predicting the class of r/2 after a radius). Each
//! integer is a token (its class k, and for k >= 2 the bit below the leading one), a sign and
//! k - 2 raw bits. Static models price the tokens by a table fixed in advance:
//! - `static_prev`: the token by the model's previous class (format 2's context, not adapted);
//! - `static_pair`: the token by the previous class and the class of the other coordinate's
//!   latest delta (y knows this x; x knows the previous y).
//!
//! The sign is priced by the model's previous sign, the kind flag by the previous kind. Tables are counted
//! on the public set only (all t and both encoders) and applied to every set, so the held-out
//! and small sets say what predefined tables cost on data they were not made from. The bytes are
//! the ideal code lengths (an ANS coder adds a few bytes a value for its final state). Also the
//! bytes of a header holding only what decoding and the index need ([`short_header`]).
//! `cargo run --release -p circletree-core --example tokens -- 10 25 100`
#[path = "../tests/common/mod.rs"]
mod common;
use circletree_core::internals::class;
use std::collections::HashMap;

const KMAX: usize = 48;

/// One integer to price: which table, its contexts, and the value.
struct Sym {
    table: usize,
    prev: u32,
    other: u32,
    prev_sign: u8,
    v: i64,
}

/// Tables: 0 counts, 1 radius, 2.. delta models [axis][kind][prev kind].
fn symbols(ct: &circletree_core::format::CircleTree) -> (Vec<Sym>, Vec<(bool, bool)>) {
    let n = ct.ncircles().max(1) as u64;
    let b = ct.bbox.unwrap_or([0; 4]);
    let extent = ((b[2] - b[0]) + (b[3] - b[1])) as u64;
    let step = class(extent.saturating_mul(3) / n);
    let rclass = class((ct.params.min_radius.to_f64() / ct.grid.to_f64()) as u64 * 2);
    let mut prev = [0u32; 10];
    let mut sign = [0u8; 10];
    prev[0] = 4;
    prev[1] = rclass;
    for p in prev.iter_mut().skip(2) {
        *p = step;
    }
    let mut out = Vec::new();
    let mut flags = Vec::new();
    let push = |out: &mut Vec<Sym>,
                t: usize,
                other: u32,
                v: i64,
                prev: &mut [u32; 10],
                sign: &mut [u8; 10]| {
        out.push(Sym {
            table: t,
            prev: prev[t],
            other,
            prev_sign: sign[t],
            v,
        });
        prev[t] = class(v.unsigned_abs());
        sign[t] = if v > 0 {
            1
        } else if v < 0 {
            2
        } else {
            0
        };
    };
    for part in &ct.parts {
        push(&mut out, 0, 0, part.len() as i64 - 1, &mut prev, &mut sign);
    }
    for ring in ct.parts.iter().flatten() {
        push(&mut out, 0, 0, ring.len() as i64, &mut prev, &mut sign);
    }
    let mut at = b.first().map(|_| (b[0], b[1])).unwrap_or((0, 0));
    let (mut pc, mut last_y) = (false, step);
    for c in ct.parts.iter().flatten().flatten() {
        let is = c.r != 0;
        flags.push((pc, is));
        let (k, p) = (is as usize, pc as usize);
        let tx = 2 + k * 2 + p;
        let ty = 6 + k * 2 + p;
        if is {
            push(&mut out, 1, 0, c.r, &mut prev, &mut sign);
            let cl = class(c.r.unsigned_abs()).saturating_sub(1);
            prev[tx] = cl;
            prev[ty] = cl;
        }
        let dx = c.x - at.0;
        push(&mut out, tx, last_y, dx, &mut prev, &mut sign);
        let dy = c.y - at.1;
        push(
            &mut out,
            ty,
            class(dx.unsigned_abs()),
            dy,
            &mut prev,
            &mut sign,
        );
        last_y = class(dy.unsigned_abs());
        at = (c.x, c.y);
        pc = is;
    }
    (out, flags)
}

fn varint(u: u64) -> f64 {
    (class(u).max(1).div_ceil(7)) as f64
}

fn zigzag(v: i64) -> f64 {
    varint(((v << 1) ^ (v >> 63)) as u64)
}

fn decimal(d: circletree_core::format::Decimal) -> f64 {
    zigzag(d.mantissa) + 1.0
}

/// A header holding only what decoding and the index need: version and kind in one byte, the
/// SRID, the grid, the bound (and `ct_encode`'s three parameters), the part count and the box;
/// not the original's vertex count, WKB size or the repaired count.
fn short_header(ct: &circletree_core::format::CircleTree, within: bool) -> f64 {
    let p = &ct.params;
    let mut n = 1.0 + zigzag(ct.srid as i64) + decimal(ct.grid) + decimal(p.max_error);
    if !within {
        n += decimal(p.min_radius)
            + decimal(p.overlap)
            + p.dp_tolerance.map_or(1.0, |d| 1.0 + decimal(d));
    }
    n += varint(ct.parts.len() as u64);
    if let Some(b) = ct.bbox {
        n += zigzag(b[0])
            + zigzag(b[1])
            + varint((b[2] - b[0]) as u64)
            + varint((b[3] - b[1]) as u64);
    }
    n
}

fn token(v: i64) -> (usize, u32) {
    let u = v.unsigned_abs();
    let k = class(u);
    if k >= 2 {
        (2 * k as usize - 2 + ((u >> (k - 2)) & 1) as usize, k - 2)
    } else {
        (k as usize, 0)
    }
}

#[derive(Default)]
struct Counts(
    HashMap<(usize, u32, u32), Vec<f64>>,
    HashMap<(usize, u8), [f64; 2]>,
    HashMap<bool, [f64; 2]>,
);

impl Counts {
    fn ctx(s: &Sym, pair: bool) -> (usize, u32, u32) {
        (
            s.table,
            s.prev.min(24),
            if pair { s.other.min(24) } else { 0 },
        )
    }
    fn add(&mut self, syms: &[Sym], flags: &[(bool, bool)], pair: bool) {
        for s in syms {
            let (t, _) = token(s.v);
            self.0
                .entry(Self::ctx(s, pair))
                .or_insert_with(|| vec![0.0; 2 * KMAX])[t] += 1.0;
            if s.v != 0 {
                self.1.entry((s.table, s.prev_sign)).or_insert([0.0; 2])[(s.v < 0) as usize] += 1.0;
            }
        }
        for &(p, k) in flags {
            self.2.entry(p).or_insert([0.0; 2])[k as usize] += 1.0;
        }
    }
    /// Ideal bits with these counts as a fixed table (each count plus 1/2; an unseen context
    /// falls back to the table's context without the pair, then to uniform over 2 KMAX tokens).
    fn bits(
        &self,
        fallback: Option<&Counts>,
        syms: &[Sym],
        flags: &[(bool, bool)],
        pair: bool,
    ) -> f64 {
        let mut bits = 0.0;
        for s in syms {
            let (t, raw) = token(s.v);
            let row = self
                .0
                .get(&Self::ctx(s, pair))
                .or_else(|| fallback.and_then(|f| f.0.get(&Self::ctx(s, false))));
            bits += match row {
                Some(row) => {
                    let tot: f64 = row.iter().sum::<f64>() + 0.5 * row.len() as f64;
                    -((row[t] + 0.5) / tot).log2()
                }
                None => (2.0 * KMAX as f64).log2(),
            };
            bits += raw as f64;
            if s.v != 0 {
                let c = self
                    .1
                    .get(&(s.table, s.prev_sign))
                    .copied()
                    .unwrap_or([1.0, 1.0]);
                bits -= ((c[(s.v < 0) as usize] + 0.5) / (c[0] + c[1] + 1.0)).log2();
            }
        }
        for &(p, k) in flags {
            let c = self.2.get(&p).copied().unwrap_or([1.0, 1.0]);
            bits -= ((c[k as usize] + 0.5) / (c[0] + c[1] + 1.0)).log2();
        }
        bits
    }
}

fn main() {
    let ts: Vec<f64> = std::env::args()
        .skip(1)
        .map(|s| s.parse().expect("a bound"))
        .collect();
    let mut encoded = Vec::new();
    for set in ["polygons", "holdout", "small"] {
        for s in common::load_file(set, &[]) {
            for &t in &ts {
                for within in [true, false] {
                    let (ct, _) = common::encode_at(&s, t, within).expect("encodes");
                    let (header, _) = ct.breakdown();
                    let stream = ct.to_bytes().len() - header;
                    let (syms, flags) = symbols(&ct);
                    let short = short_header(&ct, within);
                    encoded.push((set, t, within, stream, header, syms, flags, short));
                }
            }
        }
    }
    let (mut prev_t, mut pair_t) = (Counts::default(), Counts::default());
    for e in encoded.iter().filter(|e| e.0 == "polygons") {
        prev_t.add(&e.5, &e.6, false);
        pair_t.add(&e.5, &e.6, true);
    }
    println!("set,encoder,t,values,v2_stream_bytes,static_prev_bytes,static_pair_bytes,header_bytes,short_header_bytes");
    let mut rows: std::collections::BTreeMap<(&str, &str, String), [f64; 6]> = Default::default();
    for (set, t, within, stream, header, syms, flags, short) in &encoded {
        let r = rows
            .entry((
                set,
                if *within {
                    "ct_encode_within"
                } else {
                    "ct_encode"
                },
                format!("{t}"),
            ))
            .or_default();
        r[0] += 1.0;
        r[1] += *stream as f64;
        r[2] += (prev_t.bits(None, syms, flags, false) / 8.0).ceil();
        r[3] += (pair_t.bits(Some(&prev_t), syms, flags, true) / 8.0).ceil();
        r[4] += *header as f64;
        r[5] += short;
    }
    for ((set, enc, t), r) in rows {
        println!(
            "{set},{enc},{t},{},{},{},{},{},{}",
            r[0], r[1], r[2], r[3], r[4], r[5]
        );
    }
    // the prototype decoder against format 2's parse, points-only values, best of 7
    let tables = proto::tables(&prev_t);
    println!("set,t,points,proto_bytes,v2_bytes,proto_decode_ns_per_point,v2_parse_ns_per_point");
    for set in ["polygons", "holdout", "small"] {
        for &t in &ts {
            let vals: Vec<_> = encoded
                .iter()
                .filter(|e| e.0 == set && e.1 == t && e.2)
                .collect();
            let mut coded = Vec::new();
            let mut v2 = Vec::new();
            let mut points = 0usize;
            for e in &vals {
                let (a, b) = proto::encode(&tables, &e.5);
                let layout: Vec<u8> = e.5.iter().map(|s| s.table as u8).collect();
                let mut init = [(0u32, 0u8); 10];
                for s in e.5.iter().rev() {
                    init[s.table] = (s.prev, s.prev_sign);
                }
                let truth: i64 = e.5.iter().map(|s| s.v).sum();
                assert_eq!(proto::decode(&tables, &a, &b, &layout, &init), truth);
                points += e.6.len();
                coded.push((a, b, layout, init));
            }
            for s in common::load_file(set, &[]) {
                v2.push(
                    common::encode_at(&s, t, true)
                        .expect("encodes")
                        .0
                        .to_bytes(),
                );
            }
            let best = |f: &mut dyn FnMut() -> i64| {
                (0..7)
                    .map(|_| {
                        let at = std::time::Instant::now();
                        std::hint::black_box(f());
                        at.elapsed().as_nanos() as f64
                    })
                    .fold(f64::MAX, f64::min)
            };
            let p = best(&mut || {
                coded
                    .iter()
                    .map(|(a, b, l, i)| proto::decode(&tables, a, b, l, i))
                    .sum()
            });
            let q = best(&mut || {
                v2.iter()
                    .map(|b| {
                        circletree_core::format::CircleTree::from_stored_bytes(b)
                            .expect("reads")
                            .ncircles() as i64
                    })
                    .sum()
            });
            let pb: usize = coded.iter().map(|(a, b, _, _)| a.len() + b.len()).sum();
            let vb: usize = vals.iter().map(|e| e.3).sum();
            println!(
                "{set},{t},{points},{pb},{vb},{:.1},{:.1}",
                p / points as f64,
                q / points as f64
            );
        }
    }
}

/// A prototype of the decoder such tables allow, to time it: static rANS (12-bit frequencies, a
/// 32-bit state, bytes in) over the tokens and signs by `static_prev`'s contexts, raw bits in a
/// stream of their own. Only points-only values (`ct_encode_within`). Not a format.
mod proto {
    use super::{token, Counts, Sym};
    use circletree_core::internals::class;

    const M: u32 = 1 << 12;
    const L: u32 = 1 << 23;

    pub struct Table {
        freq: Vec<u32>,
        cum: Vec<u32>,
        slot: Vec<u8>,
    }

    fn table(counts: &[f64]) -> Table {
        let tot: f64 = counts.iter().map(|c| c + 0.5).sum();
        let mut freq: Vec<u32> = counts
            .iter()
            .map(|c| (((c + 0.5) / tot) * M as f64).floor().max(1.0) as u32)
            .collect();
        let sum: u32 = freq.iter().sum();
        let big = (0..freq.len()).max_by_key(|&i| freq[i]).unwrap_or(0);
        freq[big] = (freq[big] as i64 + M as i64 - sum as i64) as u32;
        let mut cum = vec![0; freq.len() + 1];
        for i in 0..freq.len() {
            cum[i + 1] = cum[i] + freq[i];
        }
        let mut slot = vec![0u8; M as usize];
        for i in 0..freq.len() {
            for s in cum[i]..cum[i + 1] {
                slot[s as usize] = i as u8;
            }
        }
        Table { freq, cum, slot }
    }

    /// Flat: a token table per (model, previous class), a sign table per (model, previous sign).
    pub struct Tables {
        tok: Vec<Table>,
        sign: Vec<Table>,
    }

    pub fn tables(c: &Counts) -> Tables {
        let uniform = vec![0.0; 96];
        let even = [1.0, 1.0];
        let tok = (0..10 * 25)
            .map(|i| table(c.0.get(&(i / 25, (i % 25) as u32, 0)).unwrap_or(&uniform)))
            .collect();
        let sign = (0..10 * 3)
            .map(|i| table(c.1.get(&(i / 3, (i % 3) as u8)).unwrap_or(&even)))
            .collect();
        Tables { tok, sign }
    }

    impl Tables {
        #[inline(always)]
        fn tok(&self, t: usize, prev: u32) -> &Table {
            &self.tok[t * 25 + prev.min(24) as usize]
        }
        #[inline(always)]
        fn sign(&self, t: usize, prev: u8) -> &Table {
            &self.sign[t * 3 + prev as usize]
        }
    }

    /// (rANS bytes, raw bytes) of a value's symbols.
    pub fn encode(t: &Tables, syms: &[Sym]) -> (Vec<u8>, Vec<u8>) {
        let mut put: Vec<(u32, u32)> = Vec::new();
        let mut raw = Vec::new();
        let (mut acc, mut nacc) = (0u64, 0u32);
        for s in syms {
            let (tk, nraw) = token(s.v);
            let tb = t.tok(s.table, s.prev);
            put.push((tb.cum[tk], tb.freq[tk]));
            if s.v != 0 {
                let sb = t.sign(s.table, s.prev_sign);
                let neg = (s.v < 0) as usize;
                put.push((sb.cum[neg], sb.freq[neg]));
            }
            let u = s.v.unsigned_abs();
            for i in (0..nraw).rev() {
                acc = (acc << 1) | ((u >> i) & 1);
                nacc += 1;
                if nacc == 8 {
                    raw.push(acc as u8);
                    (acc, nacc) = (0, 0);
                }
            }
        }
        if nacc > 0 {
            raw.push((acc << (8 - nacc)) as u8);
        }
        let mut x = L;
        let mut out = Vec::new();
        for &(cum, freq) in put.iter().rev() {
            let xmax = ((L >> 12) << 8) * freq;
            while x >= xmax {
                out.push(x as u8);
                x >>= 8;
            }
            x = (x / freq) * M + (x % freq) + cum;
        }
        out.extend_from_slice(&x.to_le_bytes());
        out.reverse();
        (out, raw)
    }

    /// Decode `n` integers of the layout `symbols` walks (counts, then points), returning the
    /// sum of coordinates (so nothing is optimised away).
    pub fn decode(
        t: &Tables,
        bytes: &[u8],
        raw: &[u8],
        layout: &[u8],
        init: &[(u32, u8); 10],
    ) -> i64 {
        let mut pos = 4;
        let mut x = u32::from_be_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]);
        let (mut rpos, mut acc, mut nacc) = (0usize, 0u64, 0u32);
        let mut prev = init.map(|i| i.0);
        let mut psign = init.map(|i| i.1);
        let mut sum = 0i64;
        let step = |tb: &Table, x: &mut u32, pos: &mut usize| -> usize {
            let s = (*x & (M - 1)) as usize;
            let sym = tb.slot[s] as usize;
            *x = tb.freq[sym] * (*x >> 12) + s as u32 - tb.cum[sym];
            while *x < L {
                *x = (*x << 8) | u32::from(*bytes.get(*pos).unwrap_or(&0));
                *pos += 1;
            }
            sym
        };
        for &tbl in layout {
            let tbl = tbl as usize;
            let tk = step(t.tok(tbl, prev[tbl]), &mut x, &mut pos);
            let (k, top) = if tk >= 2 {
                ((tk as u32 + 2) / 2, (tk as u64) & 1)
            } else {
                (tk as u32, 0)
            };
            let mut u = if k >= 2 {
                (1u64 << (k - 1)) | (top << (k - 2))
            } else {
                k as u64
            };
            if k >= 2 {
                let n = k - 2;
                while nacc < n {
                    acc = (acc << 8) | u64::from(*raw.get(rpos).unwrap_or(&0));
                    rpos += 1;
                    nacc += 8;
                }
                u |= (acc >> (nacc - n)) & ((1u64 << n) - 1);
                nacc -= n;
            }
            let v = if u != 0 {
                let neg = step(t.sign(tbl, psign[tbl]), &mut x, &mut pos) == 1;
                psign[tbl] = 1 + neg as u8;
                if neg {
                    -(u as i64)
                } else {
                    u as i64
                }
            } else {
                psign[tbl] = 0;
                0
            };
            prev[tbl] = class(v.unsigned_abs());
            sum = sum.wrapping_add(v);
        }
        sum
    }
}
