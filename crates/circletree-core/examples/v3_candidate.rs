//! A measured candidate for a format version 3, not a format: the circles of every value coded
//! with static canonical Huffman tables stored in the value (one symbol an integer: its class
//! relative to a prediction, jointly with a sign flip and, where the kind is not yet known, the
//! circle's kind), the bits below the leading one raw; read by table lookup with a 64-bit bit
//! buffer. Compared on the same values with version 2's stream (its adaptive binary range coder)
//! and version 1's varints, for bytes and for parse time. Prints one table row per bound:
//! `cargo run --release -p circletree-core --example v3_candidate -- 10 25 100`
//! (`CT_DATA=holdout` for the held-out set, `CT_WITHIN=1` for `encode_within`'s values).
//!
//! Symbols ([`sym`]: alphabet 0..128, `kind * 64 + flip * 32 + class difference + 16`, with
//! escapes for differences beyond -15..=14):
//! - table A, one a circle: a point's x class against the previous point's x class (kind 0), or a
//!   circle's radius class against the previous radius class (kind 1);
//! - table B: a circle's x class against `class(r) - 1`;
//! - table C: a point's y class against the previous point's y class; table D: a circle's y
//!   class against `class(r) - 1`.
#[path = "../tests/common/mod.rs"]
mod common;
use circletree_core::coder::class;
use circletree_core::format::{v2, Circle, Cursor};
use std::collections::BinaryHeap;
use std::hint::black_box;
use std::time::Instant;

const LIMIT: u32 = 11;
const NSYM: usize = 128;

/// Symbol of an integer of class `k` against the prediction `pred`: bit 6 the circle's kind
/// (table A), bit 5 "the sign differs from the last nonzero integer's of this table", bits 0-4 the
/// class difference + 16, where 0 and 31 are escapes (the class follows in 6 raw bits).
fn sym(kind: u32, v: i64, pred: u32, last_neg: bool) -> (usize, u32, bool) {
    let k = class(v.unsigned_abs());
    let d = k as i64 - pred as i64;
    let esc = !(-15..=14).contains(&d);
    let diff = if d < 0 && esc {
        0
    } else if esc {
        31
    } else {
        (d + 16) as u32
    };
    let flip = v != 0 && (v < 0) != last_neg;
    ((kind * 64 + u32::from(flip) * 32 + diff) as usize, k, esc)
}

/// Huffman code lengths of `freq`, at most [`LIMIT`] (frequencies halved until they fit).
fn lengths(freq: &[u64; NSYM]) -> [u8; NSYM] {
    let mut f = *freq;
    loop {
        let used: Vec<usize> = (0..NSYM).filter(|&s| f[s] > 0).collect();
        let mut len = [0u8; NSYM];
        if used.len() == 1 {
            len[used[0]] = 1;
            return len;
        }
        if used.is_empty() {
            return len;
        }
        // nodes: leaves then internal; parent links give depths
        let mut parent = vec![usize::MAX; 2 * used.len()];
        let mut heap: BinaryHeap<std::cmp::Reverse<(u64, usize)>> = used
            .iter()
            .enumerate()
            .map(|(i, &s)| std::cmp::Reverse((f[s], i)))
            .collect();
        let mut next = used.len();
        while heap.len() > 1 {
            let std::cmp::Reverse((a, i)) = heap.pop().expect("two nodes");
            let std::cmp::Reverse((b, j)) = heap.pop().expect("two nodes");
            parent[i] = next;
            parent[j] = next;
            heap.push(std::cmp::Reverse((a + b, next)));
            next += 1;
        }
        let mut ok = true;
        for (i, &s) in used.iter().enumerate() {
            let (mut d, mut p) = (0, i);
            while parent[p] != usize::MAX {
                p = parent[p];
                d += 1;
            }
            ok &= d <= LIMIT;
            len[s] = d as u8;
        }
        if ok {
            return len;
        }
        for v in f.iter_mut().filter(|v| **v > 0) {
            *v = (*v).div_ceil(2);
        }
    }
}

/// Canonical codes, bit-reversed for LSB-first output.
fn codes(len: &[u8; NSYM]) -> [u32; NSYM] {
    let mut code = [0u32; NSYM];
    let mut next = 0u32;
    for l in 1..=LIMIT as u8 {
        for s in 0..NSYM {
            if len[s] == l {
                code[s] = next.reverse_bits() >> (32 - l as u32);
                next += 1;
            }
        }
        next <<= 1;
    }
    code
}

#[derive(Default)]
struct BitWriter {
    acc: u64,
    n: u32,
    out: Vec<u8>,
}

impl BitWriter {
    fn put(&mut self, v: u64, bits: u32) {
        if bits > 32 {
            self.put(v & 0xFFFF_FFFF, 32);
            self.put(v >> 32, bits - 32);
            return;
        }
        self.acc |= (v & ((1u64 << bits) - 1)) << self.n;
        self.n += bits;
        while self.n >= 8 {
            self.out.push(self.acc as u8);
            self.acc >>= 8;
            self.n -= 8;
        }
    }
    fn finish(mut self) -> Vec<u8> {
        if self.n > 0 {
            self.out.push(self.acc as u8);
        }
        self.out
    }
}

/// One integer: its symbol's code, the class when escaped, then the `k - 1` bits below the
/// leading one.
fn put_int(w: &mut BitWriter, len: &[u8; NSYM], code: &[u32; NSYM], x: Int) {
    w.put(u64::from(code[x.s]), u32::from(len[x.s]));
    if x.esc {
        w.put(u64::from(x.k), 6);
    }
    if x.k >= 2 {
        w.put(x.v.unsigned_abs(), x.k - 1);
    }
}

/// One coded integer.
#[derive(Clone, Copy)]
struct Int {
    s: usize,
    k: u32,
    esc: bool,
    v: i64,
}

/// Predictions carried from circle to circle: the last classes, and each table's last sign.
#[derive(Clone, Copy, Default)]
struct Pred {
    px: u32,
    py: u32,
    r: u32,
    neg: [bool; 4],
    neg_r: bool,
}

/// Tables: A (point x or radius), B (circle x), C (point y), D (circle y). Measured and not
/// kept: A by the last point's y class move and C by this point's x class move (three each):
/// 2% fewer bytes at 10 m, more at 100 m (the tables' own bytes), and the parse twice as slow
/// (eight 4096-entry lookup tables to build for every value and to keep in cache).
const NTABLES: usize = 4;

impl Pred {
    fn int(&mut self, slot: usize, kind: u32, v: i64, pred: u32) -> Int {
        let neg = if kind == 1 {
            &mut self.neg_r
        } else {
            &mut self.neg[slot]
        };
        let (s, k, esc) = sym(kind, v, pred, *neg);
        if v != 0 {
            *neg = v < 0;
        }
        Int { s, k, esc, v }
    }
}

/// Walk the circles, calling `f(table, integer)` for every integer in stream order.
fn symbols(parts: &[Vec<Vec<Circle>>], start: (i64, i64), mut f: impl FnMut(usize, Int)) {
    let mut p = Pred::default();
    let mut at = start;
    for c in parts.iter().flatten().flatten() {
        let (dx, dy) = (c.x - at.0, c.y - at.1);
        if c.r == 0 {
            let x = p.int(0, 0, dx, p.px);
            f(0, x);
            let y = p.int(2, 0, dy, p.py);
            f(2, y);
            p.px = x.k;
            p.py = y.k;
        } else {
            let r = p.int(0, 1, c.r, p.r);
            f(0, r);
            let pr = r.k.saturating_sub(1);
            let x = p.int(1, 0, dx, pr);
            f(1, x);
            let y = p.int(3, 0, dy, pr);
            f(3, y);
            p.r = r.k;
        }
        at = (c.x, c.y);
    }
}

/// Bits the symbols take as coded, and at their static entropy (what a fractional-bit coder
/// with the same static statistics, tANS or rANS, would approach, before its tables' cost).
fn symbol_bits(parts: &[Vec<Vec<Circle>>], start: (i64, i64)) -> (f64, f64) {
    let mut freq = [[0u64; NSYM]; NTABLES];
    symbols(parts, start, |t, x| freq[t][x.s] += 1);
    let (mut coded, mut entropy) = (0.0, 0.0);
    for f in &freq {
        let len = lengths(f);
        let total: u64 = f.iter().sum();
        for (s, &n) in f.iter().enumerate().filter(|(_, &n)| n > 0) {
            coded += (n * u64::from(len[s])) as f64;
            entropy -= n as f64 * (n as f64 / total as f64).log2();
        }
    }
    (coded, entropy)
}

/// The candidate's stream: counts (a 6-bit class and the bits), four tables, the circles.
fn write(parts: &[Vec<Vec<Circle>>], start: (i64, i64)) -> Vec<u8> {
    let mut freq = [[0u64; NSYM]; NTABLES];
    symbols(parts, start, |t, x| freq[t][x.s] += 1);
    let len: Vec<[u8; NSYM]> = freq.iter().map(lengths).collect();
    let code: Vec<[u32; NSYM]> = len.iter().map(codes).collect();
    let mut w = BitWriter::default();
    let count = |w: &mut BitWriter, v: u64| {
        let k = class(v);
        w.put(u64::from(k), 6);
        w.put(v, k);
    };
    for part in parts {
        count(&mut w, part.len() as u64 - 1);
    }
    for ring in parts.iter().flatten() {
        count(&mut w, ring.len() as u64);
    }
    for l in &len {
        let lo = l.iter().position(|&x| x > 0).unwrap_or(0);
        let hi = l.iter().rposition(|&x| x > 0).map_or(lo, |h| h + 1);
        w.put(lo as u64, 7);
        w.put((hi - lo) as u64, 8);
        for &x in &l[lo..hi] {
            w.put(u64::from(x), 4);
        }
    }
    symbols(parts, start, |t, x| put_int(&mut w, &len[t], &code[t], x));
    w.finish()
}

/// Lookup table: the next [`LIMIT`] bits give `(symbol, length)`.
fn lookup(len: &[u8]) -> Vec<(u8, u8)> {
    let mut lens = [0u8; NSYM];
    lens[..len.len()].copy_from_slice(len);
    let code = codes(&lens);
    let mut t = vec![(0u8, 0u8); 1 << LIMIT];
    for s in 0..NSYM {
        let l = lens[s] as u32;
        if l == 0 {
            continue;
        }
        let mut i = code[s] as usize;
        while i < 1 << LIMIT {
            t[i] = (s as u8, l as u8);
            i += 1 << l;
        }
    }
    t
}

struct BitReader<'a> {
    buf: &'a [u8],
    pos: usize,
    acc: u64,
    n: u32,
}

impl BitReader<'_> {
    /// At least 56 bits in the buffer (the input is padded with 16 zero bytes: up to 7 are loaded ahead of what is read).
    #[inline(always)]
    fn refill(&mut self) {
        let b = u64::from_le_bytes(
            self.buf[self.pos..self.pos + 8]
                .try_into()
                .expect("8 bytes"),
        );
        self.acc |= b << self.n;
        self.pos += (63 - self.n as usize) >> 3;
        self.n |= 56;
    }
    #[inline(always)]
    fn take(&mut self, bits: u32) -> u64 {
        let v = self.acc & ((1u64 << bits) - 1);
        self.acc >>= bits;
        self.n -= bits;
        v
    }
    fn big(&mut self, bits: u32) -> u64 {
        if bits <= 32 {
            self.refill();
            return self.take(bits);
        }
        let lo = self.big(32);
        lo | (self.big(bits - 32) << 32)
    }
    /// The next symbol of table `t`.
    #[inline(always)]
    fn symbol(&mut self, t: &[(u8, u8)]) -> u32 {
        self.refill();
        let (s, l) = t[(self.acc & ((1 << LIMIT) - 1)) as usize];
        self.take(u32::from(l));
        u32::from(s)
    }
    /// The integer of the symbol `s` read against `pred`, with the table's last sign `neg`:
    /// `(value, class)`.
    #[inline(always)]
    fn value(&mut self, s: u32, pred: u32, neg: &mut bool) -> (i64, u32) {
        let d = s & 31;
        let k = if d == 0 || d == 31 {
            self.take(6) as u32
        } else {
            (pred as i64 + d as i64 - 16).clamp(0, 63) as u32
        };
        if k == 0 {
            return (0, 0);
        }
        let rest = if k - 1 <= 36 {
            self.take(k - 1)
        } else {
            self.big(k - 1)
        };
        let v = ((1u64 << (k - 1)) | rest) as i64;
        *neg ^= s & 32 != 0;
        (if *neg { -v } else { v }, k)
    }
}

fn read(bytes: &[u8], nparts: usize, start: (i64, i64)) -> Vec<Vec<Vec<Circle>>> {
    let mut r = BitReader {
        buf: bytes,
        pos: 0,
        acc: 0,
        n: 0,
    };
    let count = |r: &mut BitReader| {
        r.refill();
        let k = r.take(6) as u32;
        r.big(k) as usize
    };
    let nrings: Vec<usize> = (0..nparts).map(|_| count(&mut r) + 1).collect();
    let sizes: Vec<usize> = (0..nrings.iter().sum::<usize>())
        .map(|_| count(&mut r))
        .collect();
    let tables: Vec<Vec<(u8, u8)>> = (0..NTABLES)
        .map(|_| {
            r.refill();
            let lo = r.take(7) as usize;
            let n = r.take(8) as usize;
            let mut l = vec![0u8; lo + n];
            for x in l.iter_mut().skip(lo) {
                r.refill();
                *x = r.take(4) as u8;
            }
            lookup(&l)
        })
        .collect();
    let mut p = Pred::default();
    let mut at = start;
    let mut sizes = sizes.into_iter();
    let mut parts = Vec::with_capacity(nparts);
    for nr in nrings {
        let mut rings = Vec::with_capacity(nr);
        for _ in 0..nr {
            let n = sizes.next().expect("a size per ring");
            let mut ring = Vec::with_capacity(n);
            for _ in 0..n {
                let s = r.symbol(&tables[0]);
                let c = if s < 64 {
                    let (dx, kx) = r.value(s, p.px, &mut p.neg[0]);
                    let t = r.symbol(&tables[2]);
                    let (dy, ky) = r.value(t, p.py, &mut p.neg[2]);
                    p.px = kx;
                    p.py = ky;
                    Circle {
                        x: at.0 + dx,
                        y: at.1 + dy,
                        r: 0,
                    }
                } else {
                    let (rad, kr) = r.value(s, p.r, &mut p.neg_r);
                    p.r = kr;
                    let pr = kr.saturating_sub(1);
                    let t = r.symbol(&tables[1]);
                    let (dx, _) = r.value(t, pr, &mut p.neg[1]);
                    let t = r.symbol(&tables[3]);
                    let (dy, _) = r.value(t, pr, &mut p.neg[3]);
                    Circle {
                        x: at.0 + dx,
                        y: at.1 + dy,
                        r: rad,
                    }
                };
                at = (c.x, c.y);
                ring.push(c);
            }
            rings.push(ring);
        }
        parts.push(rings);
    }
    parts
}

/// Best of 20 passes, seconds.
fn time(mut f: impl FnMut()) -> f64 {
    (0..20)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

fn main() {
    let samples = common::load(&[]);
    println!("| t | circles | v1 bytes | v2 bytes | candidate bytes | candidate/v1 | candidate/v2 | v2 parse ms | candidate parse ms | symbol bytes | at static entropy |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for t in std::env::args().skip(1) {
        let t: f64 = t.parse().expect("a bound");
        let (mut b1, mut b2, mut b3, mut n) = (0, 0, 0, 0);
        let (mut coded, mut entropy) = (0.0, 0.0);
        let mut streams = Vec::new();
        for s in &samples {
            let within = std::env::var_os("CT_WITHIN").is_some();
            let (mut ct, _) = common::encode_at(s, t, within).expect("encodes");
            n += ct.ncircles();
            let bytes2 = ct.to_bytes();
            let total2 = bytes2.len();
            let (header, _) = ct.breakdown();
            let bb = ct.bbox.expect("not empty");
            let cur = Cursor {
                start: (bb[0], bb[1]),
                extent: (bb[2] - bb[0]) as u64 + (bb[3] - bb[1]) as u64,
                min_radius: (ct.params.min_radius.to_f64() / ct.grid.to_f64()) as u64,
            };
            let s2 = v2::write(&ct.parts, cur);
            assert!(
                header + s2.len() == total2 && bytes2.ends_with(&s2),
                "the stored value is its header and this stream"
            );
            let mut s3 = write(&ct.parts, cur.start);
            let (c, e) = symbol_bits(&ct.parts, cur.start);
            coded += c;
            entropy += e;
            b2 += total2;
            b3 += header + s3.len();
            s3.extend([0u8; 16]);
            assert_eq!(read(&s3, ct.parts.len(), cur.start), ct.parts, "round trip");
            assert_eq!(v2::read(&s2, ct.parts.len(), cur).expect("reads"), ct.parts);
            ct.version = 1;
            b1 += ct.to_bytes().len();
            streams.push((s2, s3, ct.parts.len(), cur));
        }
        let p2 = time(|| {
            for (s2, _, np, cur) in &streams {
                black_box(v2::read(s2, *np, *cur).expect("reads"));
            }
        });
        let p3 = time(|| {
            for (_, s3, np, cur) in &streams {
                black_box(read(s3, *np, cur.start));
            }
        });
        println!(
            "| {t} | {n} | {b1} | {b2} | {b3} | {:.3} | {:.3} | {:.2} | {:.2} | {:.0} | {:.0} |",
            b3 as f64 / b1 as f64,
            b3 as f64 / b2 as f64,
            p2 * 1e3,
            p3 * 1e3,
            coded / 8.0,
            entropy / 8.0
        );
    }
}
