//! Text input and output (`circletree_in` / `circletree_out`): the core's text form.

use super::CircleTree;
use crate::error::OrRaise;
use circletree_core::format;
use pgrx::inoutfuncs::InOutFuncs;
use pgrx::StringInfo;
use std::ffi::CStr;

impl InOutFuncs for CircleTree {
    fn input(input: &CStr) -> Self {
        let s = match input.to_str() {
            Ok(s) => s,
            Err(_) => crate::error::raise(circletree_core::Error::Syntax {
                expected: "UTF-8 text".into(),
                position: 1,
            }),
        };
        CircleTree::new(format::from_text(s).or_raise())
    }

    fn output(&self, buffer: &mut StringInfo) {
        buffer.push_str(&format::to_text(&self.value));
    }
}
