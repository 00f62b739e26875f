//! The input's validity asked of the host (PostGIS's `ST_IsValid`) while the encoder works.
//!
//! Both encoders refuse an invalid input with the host's reason, and the host's check is the
//! slower part of a fast encode (`ct_encode_within` of a coastline: PostGIS's check about a
//! quarter of the time). On a large input the check runs on the caller's thread (the host's
//! functions may only be called there) while the encoder runs on a second one
//! ([`crate::parallel::join`]); on a small one the check runs first, as before. Either way the
//! outcome is what the caller would get by checking first and encoding after: an error found while
//! reading the input or its parameters comes first, then the host's verdict, then the encoder's
//! result. An invalid verdict stops the encoder at its next interrupt check.
//!
//! Before either, the input is read once and [`crate::check::proof`] asked whether it is valid beyond
//! doubt (every real polygon of `tests/data`, in about a third of the host's time): then the
//! host is not asked at all and the encoder starts from what was read. Only an input the proof
//! cannot decide goes to the host, so what is accepted and refused, and with which reason, stays
//! the host's.

use super::Error;
use crate::error::Result;
use crate::parallel;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, Ordering};

/// The host's validity check of the input: `is_valid` first, `reason` (the text the error
/// carries) only when it says no. Both are called on the caller's thread.
pub struct HostCheck<'a> {
    /// Whether the input is valid (PostGIS: `ST_IsValid`).
    pub is_valid: Box<dyn FnOnce() -> bool + 'a>,
    /// Why it is not (PostGIS: `ST_IsValidReason`).
    pub reason: Box<dyn FnOnce() -> String + 'a>,
}

/// What the encoder knows of the input's validity when it has read it.
#[derive(Clone, Copy)]
pub(super) enum Verdict<'a> {
    /// The caller's answer: the host's reason when the input is not valid.
    Known(Option<&'a str>),
    /// Asked beside the encoder, which sets this flag once the input and the parameters have been
    /// read without error (an error after that point yields to an invalid verdict).
    Pending(&'a AtomicBool),
}

/// A WKB input of at least this many bytes (16 a vertex) is checked beside the encoder.
const MIN_WKB_BYTES: usize = parallel::MIN_VERTICES as usize * 16;

/// The payload the encoder unwinds with once the verdict is invalid (caught here).
struct Invalid;

/// Run `encode` with the host's `check` beside it; see the module's documentation.
pub(super) fn beside<T: Send>(
    wkb: &[u8],
    check: HostCheck<'_>,
    interrupt: &mut dyn FnMut(),
    encode: impl FnOnce(Verdict<'_>, Option<crate::geom::wkb::Input>, &mut dyn FnMut()) -> Result<T>
        + Send,
) -> Result<T> {
    // (an input that cannot be read is left to the encoder, which reads it again and says why in
    // its own order; one that can is handed to the encoder either way, not read twice)
    let given = match crate::geom::wkb::read(wkb) {
        Ok(input)
            if input.as_given && crate::check::proof::proves_valid(&input.shape, interrupt) =>
        {
            return encode(Verdict::Known(None), Some(input), interrupt);
        }
        other => other.ok(),
    };
    let read = AtomicBool::new(false);
    let invalid = AtomicBool::new(false);
    let (reason, encoded) = parallel::join(
        wkb.len() >= MIN_WKB_BYTES,
        interrupt,
        |_| {
            if (check.is_valid)() {
                None
            } else {
                invalid.store(true, Ordering::Release);
                Some((check.reason)())
            }
        },
        |i| {
            let mut stop_if_invalid = || {
                if invalid.load(Ordering::Acquire) && read.load(Ordering::Acquire) {
                    resume_unwind(Box::new(Invalid));
                }
                i();
            };
            let run = catch_unwind(AssertUnwindSafe(|| {
                encode(Verdict::Pending(&read), given, &mut stop_if_invalid)
            }));
            match run {
                Ok(result) => Some(result),
                Err(payload) if payload.is::<Invalid>() => None,
                Err(payload) => resume_unwind(payload),
            }
        },
    );
    match (encoded, reason) {
        // the input or a parameter could not be read: that error comes first, as it did when
        // the host's verdict was passed in
        (Some(Err(e)), _) if !read.load(Ordering::Acquire) => Err(e),
        (_, Some(reason)) => Err(Error::InvalidPolygon(reason)),
        (Some(result), None) => result,
        // stopped only on an invalid verdict, which the arm above took
        (None, None) => Err(Error::Unencodable(
            "the encoder stopped without a reason".to_string(),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::super::{encode, encode_within, Call, Validity};
    use super::*;

    fn square(n: usize) -> Vec<u8> {
        square_as(n, false)
    }

    /// The same square, its first point given twice when `repeat`: still valid, but not read
    /// as given, so [`crate::check::proof`] leaves it to the host.
    fn repeated(n: usize) -> Vec<u8> {
        square_as(n, true)
    }

    fn square_as(n: usize, repeat: bool) -> Vec<u8> {
        // a square with `n` vertices a side, as little-endian WKB
        let mut pts = Vec::new();
        if repeat {
            pts.push((0.0, 0.0));
        }
        for k in 0..4 {
            for j in 0..n {
                let t = j as f64 / n as f64 * 1000.0;
                pts.push(match k {
                    0 => (t, 0.0),
                    1 => (1000.0, t),
                    2 => (1000.0 - t, 1000.0),
                    _ => (0.0, 1000.0 - t),
                });
            }
        }
        pts.push((0.0, 0.0));
        let mut w = vec![1u8];
        w.extend(3u32.to_le_bytes());
        w.extend(1u32.to_le_bytes());
        w.extend((pts.len() as u32).to_le_bytes());
        for (x, y) in pts {
            w.extend(x.to_le_bytes());
            w.extend(y.to_le_bytes());
        }
        w
    }

    fn within(wkb: &[u8], max_error: f64, valid: bool) -> (Result<Vec<u8>>, usize) {
        within_asked(wkb, max_error, valid).0
    }

    /// [`within`], and whether the host was asked at all.
    fn within_asked(wkb: &[u8], max_error: f64, valid: bool) -> ((Result<Vec<u8>>, usize), bool) {
        let mut reasons = 0;
        let asked = std::cell::Cell::new(false);
        let check = HostCheck {
            is_valid: Box::new(|| {
                asked.set(true);
                valid
            }),
            reason: Box::new(|| {
                reasons += 1;
                "Self-intersection[5 5]".to_string()
            }),
        };
        let call = Call::new(0).validity(Validity::Host(check));
        let r = encode_within(wkb, max_error, call).map(|e| e.into_parts().1);
        ((r, reasons), asked.get())
    }

    #[test]
    fn valid_inputs_give_the_bytes_of_a_check_made_first() {
        // below and above the size checked beside the encoder
        for n in [10, 2_000] {
            for (wkb, proved) in [(square(n), true), (repeated(n), false)] {
                let ((beside, reasons), asked) = within_asked(&wkb, 0.5, true);
                let first = encode_within(&wkb, 0.5, Call::new(0))
                    .unwrap()
                    .into_parts()
                    .1;
                assert_eq!(beside.unwrap(), first);
                assert_eq!(reasons, 0);
                // the plain square is proved valid here: the host is not asked
                assert_eq!(asked, !proved, "n = {n}, proved = {proved}");
            }
        }
    }

    #[test]
    fn errors_keep_the_order_of_a_check_made_first() {
        for n in [10, 2_000] {
            let wkb = repeated(n);
            // an invalid verdict: the host's reason, asked once
            let (r, reasons) = within(&wkb, 0.5, false);
            assert!(
                matches!(&r, Err(Error::InvalidPolygon(m)) if m == "Self-intersection[5 5]"),
                "{r:?}"
            );
            assert_eq!(reasons, 1);
            // a parameter error comes before the verdict, as does unreadable WKB
            let (r, _) = within(&wkb, -1.0, false);
            assert!(matches!(r, Err(Error::InvalidParameter { .. })), "{r:?}");
            let (r, _) = within(&wkb[..wkb.len() - 3], 0.5, false);
            assert!(matches!(r, Err(Error::BadWkb(_))), "{r:?}");
            // an error found after reading yields to the verdict: coordinates too large for
            // this bound's grid
            let big: Vec<u8> = {
                let mut w = wkb.clone();
                let last = w.len() - 16;
                for at in [13, last] {
                    w[at..at + 8].copy_from_slice(&1e300f64.to_le_bytes());
                }
                w
            };
            let (r, _) = within(&big, 0.5, false);
            assert!(matches!(r, Err(Error::InvalidPolygon(_))), "{r:?}");
            let (r, _) = within(&big, 0.5, true);
            assert!(!matches!(r, Err(Error::InvalidPolygon(_)) | Ok(_)), "{r:?}");
        }
    }

    #[test]
    fn ct_encode_is_checked_the_same_way() {
        let wkb = repeated(2_000);
        let opts = super::super::Options {
            min_radius: 5.0,
            overlap: 0.4,
            dp_tolerance: Some(10.0),
            max_error: None,
        };
        let host = |valid: bool| {
            Call::new(0).validity(Validity::Host(HostCheck {
                is_valid: Box::new(move || valid),
                reason: Box::new(|| "Ring Self-intersection[0 0]".to_string()),
            }))
        };
        let beside = encode(&wkb, &opts, host(true)).unwrap();
        let first = encode(&wkb, &opts, Call::new(0)).unwrap();
        assert_eq!(beside.value.to_bytes(), first.value.to_bytes());
        let r = encode(&wkb, &opts, host(false));
        assert!(matches!(r, Err(Error::InvalidPolygon(_))), "{r:?}");
    }
}
