//! The `circletree` SQL type: bytes in [`memory`], text in [`text`], send/recv and bytea in [`binary`].

pub mod binary;
pub mod memory;
pub mod text;

use crate::error::OrRaise;
use circletree_core::format;
use pgrx::prelude::*;

/// A `circletree` value: its decoded, validated form and its stored bytes.
#[derive(PostgresType, Debug, Clone, PartialEq)]
#[inoutfuncs]
#[bikeshed_postgres_type_manually_impl_from_into_datum]
pub struct CircleTree {
    /// The decoded value.
    pub value: format::CircleTree,
    /// Its stored bytes (format v1 or v2), as written by `to_bytes`.
    pub bytes: Vec<u8>,
}

impl CircleTree {
    /// Wrap a value (encodes it).
    pub fn new(value: format::CircleTree) -> Self {
        let bytes = value.to_bytes();
        CircleTree { value, bytes }
    }

    /// Decode and validate stored bytes (a datum this extension wrote), or raise 22P03.
    pub fn from_stored(bytes: &[u8]) -> Self {
        let value = format::CircleTree::from_stored_bytes(bytes).or_raise();
        CircleTree {
            value,
            bytes: bytes.to_vec(),
        }
    }

    /// Decode and validate bytes from outside (binary COPY, `bytea::circletree`), also checking
    /// that they are exactly the bytes their value encodes to; or raise 22P03.
    pub fn from_input(bytes: &[u8]) -> Self {
        let value = format::CircleTree::from_bytes(bytes).or_raise();
        CircleTree {
            value,
            bytes: bytes.to_vec(),
        }
    }
}
