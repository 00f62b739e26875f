#![allow(unsafe_code)] // the datum layer: pgrx FFI traits and the RECEIVE StringInfo
//! Binary I/O (`circletree_send` / `circletree_recv`, our own bytes, not CBOR), the validated
//! casts to and from `bytea`, and byte equality and order (btree and hash).

use super::memory::StoredBytes;
use super::CircleTree;
use pgrx::datum::Internal;
use pgrx::pg_sys;
use pgrx::prelude::*;

/// `SEND`: the stored bytes as they are.
#[pg_extern(immutable, strict, parallel_safe)]
fn circletree_send(ct: StoredBytes) -> Vec<u8> {
    ct.0.to_vec()
}

/// `RECEIVE`: read the message's remaining bytes and validate them fully.
#[pg_extern(immutable, strict, parallel_safe)]
fn circletree_recv(mut internal: Internal) -> CircleTree {
    // SAFETY: PostgreSQL passes a StringInfo to a type's receive function.
    let Some(buf) = (unsafe { internal.get_mut::<pg_sys::StringInfoData>() }) else {
        pgrx::error!("circletree_recv: no message buffer");
    };
    let (cursor, len) = (buf.cursor.max(0) as usize, buf.len.max(0) as usize);
    let bytes: &[u8] = if buf.data.is_null() || cursor >= len {
        &[]
    } else {
        // SAFETY: data holds len bytes; we read [cursor, len).
        unsafe { std::slice::from_raw_parts((buf.data as *const u8).add(cursor), len - cursor) }
    };
    let ct = CircleTree::from_input(bytes);
    buf.cursor = buf.len;
    ct
}

/// `bytea -> circletree`: validates the bytes (ERROR 22P03 when they are not a circletree).
#[pg_extern(immutable, strict, parallel_safe)]
fn circletree_from_bytea(bytes: &[u8]) -> CircleTree {
    CircleTree::from_input(bytes)
}

/// `circletree -> bytea`: the stored bytes.
#[pg_extern(immutable, strict, parallel_safe)]
fn circletree_to_bytea(ct: StoredBytes) -> Vec<u8> {
    ct.0.to_vec()
}

/// `=`: same bytes.
#[pg_extern(immutable, strict, parallel_safe)]
fn circletree_eq(a: StoredBytes, b: StoredBytes) -> bool {
    a.0 == b.0
}

/// `<>`: different bytes.
#[pg_extern(immutable, strict, parallel_safe)]
fn circletree_ne(a: StoredBytes, b: StoredBytes) -> bool {
    a.0 != b.0
}

/// The btree order: the stored bytes compared as unsigned bytes, a shorter prefix first (no
/// spatial meaning; it gives `=`, `DISTINCT`, `GROUP BY`, `UNION`, sorts and merge joins).
// Declared in sql/in_place.sql (0.7.0 on).
#[pg_extern(sql = false)]
fn circletree_cmp(a: StoredBytes, b: StoredBytes) -> i32 {
    a.0.cmp(b.0) as i32
}

/// `<` in byte order.
// Declared in sql/in_place.sql (0.7.0 on).
#[pg_extern(sql = false)]
fn circletree_lt(a: StoredBytes, b: StoredBytes) -> bool {
    a.0 < b.0
}

/// `<=` in byte order.
// Declared in sql/in_place.sql (0.7.0 on).
#[pg_extern(sql = false)]
fn circletree_le(a: StoredBytes, b: StoredBytes) -> bool {
    a.0 <= b.0
}

/// `>` in byte order.
// Declared in sql/in_place.sql (0.7.0 on).
#[pg_extern(sql = false)]
fn circletree_gt(a: StoredBytes, b: StoredBytes) -> bool {
    a.0 > b.0
}

/// `>=` in byte order.
// Declared in sql/in_place.sql (0.7.0 on).
#[pg_extern(sql = false)]
fn circletree_ge(a: StoredBytes, b: StoredBytes) -> bool {
    a.0 >= b.0
}

extension_sql_file!(
    "../../sql/binary_io.sql",
    name = "circletree_binary_io",
    requires = [
        circletree_recv,
        circletree_send,
        circletree_to_bytea,
        circletree_from_bytea,
        circletree_eq,
        circletree_ne
    ]
);
