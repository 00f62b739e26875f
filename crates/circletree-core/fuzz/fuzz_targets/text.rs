//! Arbitrary text to the text-form parser: an error or a value whose text reads back to itself.
#![no_main]
use circletree_core::format::{from_text, to_text};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(s) = std::str::from_utf8(data) {
        if let Ok(ct) = from_text(s) {
            assert_eq!(from_text(&to_text(&ct)), Ok(ct));
        }
    }
});
