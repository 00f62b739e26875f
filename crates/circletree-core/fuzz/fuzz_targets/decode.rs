//! Arbitrary bytes to the stored-value decoder: an error or a value that re-encodes to itself,
//! never a panic and never a large allocation.
#![no_main]
use circletree_core::format::CircleTree;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(ct) = CircleTree::from_bytes(data) {
        assert_eq!(ct.to_bytes(), data);
        let _ = circletree_core::decode::to_wkb(&ct, None);
    }
});
