//! Entropy coding of the integers of format version 2: adaptive binary models driven through a
//! binary range coder (the carry-propagating coder of LZMA: 32-bit range, 64-bit low, byte output;
//! symbols are decoded in the order they were encoded, so the models adapt identically on both
//! sides). A first version drove `constriction`'s range coder with these same models; its decode
//! of a value was 2.2-2.6x that of format version 1 (a 64-bit division per decision), against a
//! target of 1.2x, so the coder is ours: a binary decision here is a shift, a multiply and a
//! compare.
//!
//! An integer `v` is coded as its *class* `k` (the bit length of `|v|`, 0 for zero), predicted by
//! the class of the previous integer of the same [`IntModel`] (one bit "same class", one bit
//! "larger", then the distance in unary, each bit with its own adaptive probability); then the bit
//! below the leading one (adaptive, by class); then the remaining `k − 2` bits raw; then the sign
//! (adaptive, by the previous sign). Every model starts at even odds and adapts with a shift of
//! [`RATE`], so short values pay little to learn.
//!
//! The stored stream is the coder's bytes without its first (always zero) byte and with trailing
//! zero bytes removed: the decoder reads missing bytes as zero, which is what was removed.

use crate::error::{Error, Result};
/// Fixed-point precision of every probability.
pub const PRECISION: usize = 12;
const ONE: u16 = 1 << PRECISION;
/// Adaptation shift: each coded bit moves its probability 1/2^RATE of the way to the outcome.
pub const RATE: u32 = 5;
const TOP: u32 = 1 << 24;

/// An adaptive probability that a bit is `false`, in 1/4096.
#[derive(Clone, Copy, Debug)]
pub struct Bit(u16);

impl Default for Bit {
    fn default() -> Self {
        Bit(ONE / 2)
    }
}

impl Bit {
    /// The probability after coding `bit`, chosen without a branch on `bit` (an adaptive bit is
    /// often a coin toss, and a mispredicted branch costs more than the decision itself).
    #[inline(always)]
    fn after(self, bit: bool) -> Bit {
        let p = self.0;
        Bit(
            std::hint::select_unpredictable(bit, p - (p >> RATE), p + ((ONE - p) >> RATE))
                .clamp(32, ONE - 32),
        )
    }

    /// Bits the next symbol would cost (for the encoder's cost function).
    pub fn cost(&self, bit: bool) -> f64 {
        let p = self.0 as f64 / ONE as f64;
        -(if bit { 1.0 - p } else { p }).log2()
    }
}

/// The adaptive state for one kind of integer.
#[derive(Clone, Debug)]
pub struct IntModel {
    same: [Bit; 3],
    up: [Bit; 3],
    unary: [Bit; 12],
    top: [Bit; 65],
    sign: [Bit; 3],
    prev_class: u32,
    /// 0 same class as before, 1 larger, 2 smaller
    prev_move: usize,
    /// 0 none or zero, 1 positive, 2 negative
    prev_sign: usize,
}

impl Default for IntModel {
    fn default() -> Self {
        IntModel {
            same: [Bit::default(); 3],
            up: [Bit::default(); 3],
            unary: [Bit::default(); 12],
            top: [Bit::default(); 65],
            sign: [Bit::default(); 3],
            prev_class: 0,
            prev_move: 0,
            prev_sign: 0,
        }
    }
}

impl IntModel {
    /// Predict class `k` for the next integer (from something known to both sides).
    pub fn predict(&mut self, k: u32) {
        self.prev_class = k.min(64);
    }

    /// A model whose first prediction is class `k` (a sensible start for a kind of integer).
    pub fn expecting(k: u32) -> Self {
        IntModel {
            prev_class: k.min(64),
            ..IntModel::default()
        }
    }
}

impl IntModel {
    /// Bits that coding `v` next would cost, without coding it (the cost function an encoder
    /// that chooses between forms uses; the models are not updated).
    pub fn cost(&self, v: i64) -> f64 {
        let u = v.unsigned_abs();
        let k = class(u);
        let pred = self.prev_class;
        let ctx = self.prev_move;
        let mut bits = self.same[ctx].cost(k == pred);
        if k != pred {
            let up = k > pred;
            bits += self.up[ctx].cost(up);
            let (d, max) = if up {
                (k - pred - 1, 64 - pred - 1)
            } else {
                (pred - k - 1, pred - 1)
            };
            for j in 0..max {
                bits += self.unary[(j as usize).min(11)].cost(d > j);
                if d <= j {
                    break;
                }
            }
        }
        if k >= 2 {
            bits += self.top[k as usize].cost((u >> (k - 2)) & 1 == 1) + (k - 2) as f64;
        }
        if u != 0 {
            bits += self.sign[self.prev_sign].cost(v < 0);
        }
        bits
    }
}

/// The class of `u`: its bit length, 0 for zero.
pub fn class(u: u64) -> u32 {
    64 - u.leading_zeros()
}

/// Where coded symbols go: the [`Writer`], or a [`Meter`] that only counts what they would cost.
/// Both take the same decisions in the same order with the same models, so they agree.
pub trait Sink {
    /// One adaptive decision.
    fn bit(&mut self, m: &mut Bit, b: bool);
    /// `n` raw bits of `v` (its low `n`), most significant first.
    fn raw(&mut self, v: u64, n: u32);

    /// A flag with its adaptive model.
    fn flag(&mut self, m: &mut Bit, b: bool) {
        self.bit(m, b);
    }

    /// An integer with its adaptive model.
    fn int(&mut self, m: &mut IntModel, v: i64) {
        put_int(self, m, v);
    }
}

/// The symbols of one integer (see the module's description), into `s`.
#[inline(always)]
fn put_int<S: Sink + ?Sized>(s: &mut S, m: &mut IntModel, v: i64) {
    let u = v.unsigned_abs();
    let k = class(u);
    let pred = m.prev_class;
    let ctx = m.prev_move;
    s.bit(&mut m.same[ctx], k == pred);
    if k != pred {
        let up = k > pred;
        s.bit(&mut m.up[ctx], up);
        let (d, max) = if up {
            (k - pred - 1, 64 - pred - 1)
        } else {
            (pred - k - 1, pred - 1)
        };
        for j in 0..max {
            let more = d > j;
            s.bit(&mut m.unary[(j as usize).min(11)], more);
            if !more {
                break;
            }
        }
        m.prev_move = if up { 1 } else { 2 };
    } else {
        m.prev_move = 0;
    }
    if k >= 2 {
        s.bit(&mut m.top[k as usize], (u >> (k - 2)) & 1 == 1);
        s.raw(u, k - 2);
    }
    if u != 0 {
        s.bit(&mut m.sign[m.prev_sign], v < 0);
        m.prev_sign = if v < 0 { 2 } else { 1 };
    } else {
        m.prev_sign = 0;
    }
    m.prev_class = k;
}

/// Counts what coding symbols would cost, in 1/65536 bit, without coding them: each decision
/// costs `−log2` of its probability (from a table), each raw bit one bit. The [`Writer`]'s
/// stream for the same symbols is within [`Meter::bytes`]'s bounds.
pub struct Meter {
    cost: u64,
    decisions: u64,
    table: &'static [u32; ONE as usize + 1],
}

/// `−log2(p / 4096)` in 1/65536 bit, for `p` in 0..=4096 (0 unused).
fn cost_table() -> &'static [u32; ONE as usize + 1] {
    static TABLE: std::sync::OnceLock<[u32; ONE as usize + 1]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        let mut t = [0u32; ONE as usize + 1];
        for (p, c) in t.iter_mut().enumerate().skip(1) {
            *c = (-(p as f64 / f64::from(ONE)).log2() * 65536.0).round() as u32;
        }
        t
    })
}

impl Default for Meter {
    fn default() -> Self {
        Meter {
            cost: 0,
            decisions: 0,
            table: cost_table(),
        }
    }
}

impl Meter {
    /// What the symbols so far cost, in bits.
    pub fn bits(&self) -> f64 {
        self.cost as f64 / 65536.0
    }

    /// Bounds on the length of the [`Writer`]'s finished stream for the same symbols, in bytes.
    /// The coder's range is at least 2^24 before each decision, so its truncated split loses at
    /// most 2^-12 of the range (under 0.00036 bit) and gains no more; the table is rounded to
    /// 2^-17 bit; raw bits lose under 2^-16 bit each. The finished stream is the bytes shifted
    /// out (a byte per 8 bits of cost, less up to one), plus the flush, less the first byte and
    /// the trailing zeros (a few bytes, more only when the last symbols are nearly free):
    /// margins of a few bytes either way cover both, and are checked against the writer.
    pub fn bytes(&self) -> (usize, usize) {
        let slack = self.decisions * 24 + (1 << 16); // 0.00037 bit a decision, and one bit
        let lo = self.cost.saturating_sub(slack) / (8 << 16);
        let hi = (self.cost + slack).div_ceil(8 << 16);
        (
            lo.saturating_sub(METER_MARGIN) as usize,
            (hi + METER_MARGIN) as usize,
        )
    }
}

/// Bytes either side of [`Meter::bytes`]'s estimate for the flush and the trimmed zeros.
const METER_MARGIN: u64 = 8;

impl Sink for Meter {
    #[inline(always)]
    fn bit(&mut self, m: &mut Bit, b: bool) {
        let p = u32::from(m.0);
        let q = std::hint::select_unpredictable(b, ONE as u32 - p, p);
        self.cost += u64::from(self.table[q as usize]);
        self.decisions += 1;
        *m = m.after(b);
    }

    #[inline(always)]
    fn raw(&mut self, _v: u64, n: u32) {
        self.cost += u64::from(n) << 16;
    }
}

impl Sink for Writer {
    #[inline(always)]
    fn bit(&mut self, m: &mut Bit, b: bool) {
        Writer::bit(self, m, b);
    }

    #[inline(always)]
    fn raw(&mut self, v: u64, n: u32) {
        Writer::raw(self, v, n);
    }
}

/// Writes integers and bits.
pub struct Writer {
    low: u64,
    range: u32,
    cache: u8,
    cache_size: u64,
    out: Vec<u8>,
}

impl Default for Writer {
    fn default() -> Self {
        Writer {
            low: 0,
            range: u32::MAX,
            cache: 0,
            cache_size: 1,
            out: Vec::new(),
        }
    }
}

impl Writer {
    fn shift_low(&mut self) {
        if (self.low as u32) < 0xFF00_0000 || (self.low >> 32) != 0 {
            let carry = (self.low >> 32) as u8;
            let mut temp = self.cache;
            loop {
                self.out.push(temp.wrapping_add(carry));
                temp = 0xFF;
                self.cache_size -= 1;
                if self.cache_size == 0 {
                    break;
                }
            }
            self.cache = ((self.low >> 24) & 0xFF) as u8;
        }
        self.cache_size += 1;
        self.low = (self.low & 0x00FF_FFFF) << 8;
    }

    /// One byte out when the range has fallen below 2^24; one is always enough (see
    /// [`Reader`]'s `normalize`).
    #[inline(always)]
    fn normalize(&mut self) {
        if self.range < TOP {
            self.range <<= 8;
            self.shift_low();
        }
        debug_assert!(self.range >= TOP);
    }

    /// One adaptive decision, without a branch on its outcome (as the reader's).
    #[inline(always)]
    fn bit(&mut self, m: &mut Bit, b: bool) {
        let bound = (self.range >> PRECISION) * u32::from(m.0);
        let (add, range) =
            std::hint::select_unpredictable(b, (bound, self.range - bound), (0, bound));
        self.low += u64::from(add);
        self.range = range;
        *m = m.after(b);
        self.normalize();
    }

    /// `n` raw bits, up to 8 at a time (the range stays at least 2^16 before normalizing).
    fn raw(&mut self, v: u64, mut n: u32) {
        while n > 0 {
            let c = n.min(8);
            n -= c;
            self.range >>= c;
            self.low += ((v >> n) & ((1 << c) - 1)) * u64::from(self.range);
            self.normalize();
        }
    }

    /// The coded bytes: the first (always zero) byte and trailing zero bytes dropped.
    pub fn finish(mut self) -> Vec<u8> {
        for _ in 0..5 {
            self.shift_low();
        }
        let mut out = self.out;
        if !out.is_empty() {
            out.remove(0);
        }
        while out.last() == Some(&0) {
            out.pop();
        }
        out
    }
}

/// Reads what a [`Writer`] wrote.
pub struct Reader<'a> {
    buf: &'a [u8],
    pos: usize,
    range: u32,
    code: u32,
}

fn corrupt() -> Error {
    Error::Corrupt("the coded circles are not a valid range-coded stream".into())
}

impl<'a> Reader<'a> {
    /// Start reading coded bytes.
    pub fn new(bytes: &'a [u8]) -> Result<Reader<'a>> {
        let mut r = Reader {
            buf: bytes,
            pos: 0,
            range: u32::MAX,
            code: 0,
        };
        for _ in 0..4 {
            r.code = (r.code << 8) | u32::from(r.next());
        }
        Ok(r)
    }

    #[inline]
    fn next(&mut self) -> u8 {
        let b = self.buf.get(self.pos).copied().unwrap_or(0);
        self.pos += 1;
        b
    }

    /// Take in one byte when the range has fallen below 2^24. One is always enough: a decision
    /// leaves at least `(range >> PRECISION) * 32 >= 2^17`, raw bits at least `range >> 8 >= 2^16`.
    #[inline(always)]
    fn normalize(&mut self) {
        if self.range < TOP {
            self.range <<= 8;
            self.code = (self.code << 8) | u32::from(self.next());
        }
        debug_assert!(self.range >= TOP);
    }

    /// One adaptive decision, without a branch on its outcome.
    #[inline(always)]
    fn bit(&mut self, m: &mut Bit) -> bool {
        let bound = (self.range >> PRECISION) * u32::from(m.0);
        let b = self.code >= bound;
        let (range, taken) =
            std::hint::select_unpredictable(b, (self.range - bound, bound), (bound, 0));
        self.range = range;
        self.code -= taken;
        *m = m.after(b);
        self.normalize();
        b
    }

    #[inline(always)]
    fn raw(&mut self, mut n: u32) -> Result<u64> {
        let mut v = 0u64;
        while n > 0 {
            let c = n.min(8);
            n -= c;
            self.range >>= c;
            let q = self.code / self.range;
            if q >> c != 0 {
                return Err(corrupt());
            }
            self.code -= q * self.range;
            v = (v << c) | u64::from(q);
            self.normalize();
        }
        Ok(v)
    }

    /// Read a flag.
    #[inline(always)]
    pub fn flag(&mut self, m: &mut Bit) -> Result<bool> {
        Ok(self.bit(m))
    }

    /// Read an integer.
    #[inline(always)]
    pub fn int(&mut self, m: &mut IntModel) -> Result<i64> {
        let pred = m.prev_class;
        let ctx = m.prev_move;
        let k = if self.bit(&mut m.same[ctx]) {
            m.prev_move = 0;
            pred
        } else {
            let up = self.bit(&mut m.up[ctx]);
            let max = if up {
                // (a class above 63 is refused below; from a predicted 64 a stream cannot go up)
                match 63u32.checked_sub(pred) {
                    Some(max) => max,
                    None => return Err(corrupt()),
                }
            } else {
                pred.saturating_sub(1)
            };
            let mut d = 0;
            while d < max && self.bit(&mut m.unary[(d as usize).min(11)]) {
                d += 1;
            }
            m.prev_move = if up { 1 } else { 2 };
            if up {
                pred + d + 1
            } else if pred == 0 {
                return Err(corrupt());
            } else {
                pred - d - 1
            }
        };
        if k > 63 {
            return Err(Error::Corrupt("a coded integer is out of range".into()));
        }
        let u: u64 = match k {
            0 => 0,
            1 => 1,
            _ => {
                let top = u64::from(self.bit(&mut m.top[k as usize]));
                let rest = self.raw(k - 2)?;
                (1 << (k - 1)) | (top << (k - 2)) | rest
            }
        };
        let v = if u != 0 {
            let neg = self.bit(&mut m.sign[m.prev_sign]);
            m.prev_sign = if neg { 2 } else { 1 };
            let v = i64::try_from(u).map_err(|_| corrupt())?;
            if neg {
                -v
            } else {
                v
            }
        } else {
            m.prev_sign = 0;
            0
        };
        m.prev_class = k;
        Ok(v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn small_deltas_cost_few_bits() {
        let vals: Vec<i64> = (0..1000).map(|i| ((i * 7919) % 61) - 30).collect();
        let mut w = Writer::default();
        let mut m = IntModel::default();
        for &v in &vals {
            w.int(&mut m, v);
        }
        let bytes = w.finish();
        // uniform on 61 values: log2(61) = 5.93 bits; a varint spends 8
        assert!(bytes.len() < 1000 * 7 / 8, "{}", bytes.len());
        let mut r = Reader::new(&bytes).unwrap();
        let mut m = IntModel::default();
        for &v in &vals {
            assert_eq!(r.int(&mut m).unwrap(), v);
        }
    }

    /// The meter's bounds hold the writer's finished length for `f`'s symbols.
    fn metered_within_bounds(
        f: impl Fn(&mut dyn FnMut(usize, i64, bool)),
    ) -> (usize, usize, usize) {
        let (mut w, mut m) = (Writer::default(), Meter::default());
        let mut wm = [IntModel::default(), IntModel::expecting(5)];
        let mut mm = wm.clone();
        let (mut wf, mut mf) = (Bit::default(), Bit::default());
        f(&mut |k, v, flag| {
            w.int(&mut wm[k], v);
            w.flag(&mut wf, flag);
            m.int(&mut mm[k], v);
            m.flag(&mut mf, flag);
        });
        let n = w.finish().len();
        let (lo, hi) = m.bytes();
        assert!(lo <= n && n <= hi, "{lo} <= {n} <= {hi}");
        (lo, n, hi)
    }

    #[test]
    fn the_meter_bounds_long_runs_and_skewed_streams() {
        // nearly free symbols at the end (the trimmed zero bytes), both ways round, and raw bits
        for (v, flag) in [(0, false), (0, true), (1, false), (-3, true)] {
            metered_within_bounds(|put| (0..20_000).for_each(|_| put(0, v, flag)));
            metered_within_bounds(|put| {
                (0..5_000).for_each(|i| put(1, (i * 7919) % 20_000 - 10_000, i % 3 == 0));
                (0..20_000).for_each(|_| put(0, v, flag));
            });
        }
        let (lo, n, hi) = metered_within_bounds(|put| {
            (0..100_000).for_each(|i| put(i % 2, (i as i64 * 7919) % 601 - 300, i % 5 == 0))
        });
        // and are tight enough to rank plans: a few bytes in a thousand
        assert!(hi - lo < n / 100 + 20, "{lo} {n} {hi}");
    }

    proptest! {
        #[test]
        fn integers_round_trip(vals in proptest::collection::vec(any::<i64>().prop_filter("not MIN", |v| *v != i64::MIN), 0..200),
                               small in proptest::collection::vec(-300i64..300, 0..200)) {
            let mut w = Writer::default();
            let (mut a, mut b, mut f) = (IntModel::default(), IntModel::expecting(5), Bit::default());
            for (&x, &y) in vals.iter().zip(small.iter().cycle()) {
                w.int(&mut a, x);
                w.int(&mut b, y);
                w.flag(&mut f, x > y);
            }
            let bytes = w.finish();
            let mut r = Reader::new(&bytes).unwrap();
            let (mut a, mut b, mut f) = (IntModel::default(), IntModel::expecting(5), Bit::default());
            for (&x, &y) in vals.iter().zip(small.iter().cycle()) {
                prop_assert_eq!(r.int(&mut a).unwrap(), x);
                prop_assert_eq!(r.int(&mut b).unwrap(), y);
                prop_assert_eq!(r.flag(&mut f).unwrap(), x > y);
            }
        }

        #[test]
        fn the_meter_bounds_the_writer(vals in proptest::collection::vec(any::<i64>().prop_filter("not MIN", |v| *v != i64::MIN), 0..300),
                                       small in proptest::collection::vec(-300i64..300, 1..300)) {
            metered_within_bounds(|put| {
                for (&x, &y) in vals.iter().zip(small.iter().cycle()) {
                    put(0, x, x > y);
                    put(1, y, y > 0);
                }
            });
        }

        #[test]
        fn garbage_never_panics(bytes in proptest::collection::vec(any::<u8>(), 0..64)) {
            if let Ok(mut r) = Reader::new(&bytes) {
                let mut m = IntModel::default();
                for _ in 0..100 {
                    if r.int(&mut m).is_err() {
                        break;
                    }
                }
            }
        }
    }
}
