#![allow(unsafe_code)] // the datum layer: pgrx FFI traits and the RECEIVE StringInfo
//! The varlena bytes of a `circletree`: detoast, decode and validate on the way in, copy into a
//! palloc'd varlena on the way out. The datum layout is the same as `bytea`'s (a plain varlena),
//! so pgrx's `&[u8]` conversions do the detoasting and allocation.

use super::CircleTree;
use pgrx::callconv::{Arg, ArgAbi, BoxRet, FcInfo};
use pgrx::datum::{Datum, FromDatum, IntoDatum, UnboxDatum};
use pgrx::memcxt::PgMemoryContexts;
use pgrx::pg_sys;

impl IntoDatum for CircleTree {
    fn into_datum(self) -> Option<pg_sys::Datum> {
        self.bytes.as_slice().into_datum()
    }

    fn type_oid() -> pg_sys::Oid {
        pgrx::wrappers::rust_regtypein::<Self>()
    }
}

unsafe impl BoxRet for CircleTree {
    unsafe fn box_into<'fcx>(self, fcinfo: &mut FcInfo<'fcx>) -> Datum<'fcx> {
        match self.into_datum() {
            None => fcinfo.return_null(),
            Some(datum) => unsafe { fcinfo.return_raw_datum(datum) },
        }
    }
}

impl FromDatum for CircleTree {
    unsafe fn from_polymorphic_datum(
        datum: pg_sys::Datum,
        is_null: bool,
        typoid: pg_sys::Oid,
    ) -> Option<Self> {
        // SAFETY: a circletree datum is a varlena; `&[u8]` detoasts it.
        let bytes = unsafe { <&[u8]>::from_polymorphic_datum(datum, is_null, typoid) }?;
        Some(CircleTree::from_stored(bytes))
    }

    unsafe fn from_datum_in_memory_context(
        mut memory_context: PgMemoryContexts,
        datum: pg_sys::Datum,
        is_null: bool,
        typoid: pg_sys::Oid,
    ) -> Option<Self> {
        if is_null {
            return None;
        }
        // The decoded value owns its memory (Rust heap), so the context only matters for detoasting.
        memory_context.switch_to(|_| unsafe { Self::from_polymorphic_datum(datum, false, typoid) })
    }
}

unsafe impl UnboxDatum for CircleTree {
    type As<'dat>
        = Self
    where
        Self: 'dat;

    unsafe fn unbox<'dat>(datum: Datum<'dat>) -> Self::As<'dat>
    where
        Self: 'dat,
    {
        // SAFETY: Datum<'dat> is a transparent wrapper over pg_sys::Datum.
        let raw: pg_sys::Datum =
            unsafe { core::mem::transmute::<Datum<'dat>, pg_sys::Datum>(datum) };
        match unsafe { Self::from_polymorphic_datum(raw, false, pg_sys::InvalidOid) } {
            Some(v) => v,
            // ok: from_polymorphic_datum only returns None for a NULL datum, and unbox is never given one.
            None => pgrx::error!("circletree: unexpected NULL datum"),
        }
    }
}

unsafe impl<'fcx> ArgAbi<'fcx> for CircleTree
where
    Self: 'fcx,
{
    unsafe fn unbox_arg_unchecked(arg: Arg<'_, 'fcx>) -> Self {
        let index = arg.index();
        match unsafe { arg.unbox_arg_using_from_datum() } {
            Some(v) => v,
            None => pgrx::error!("circletree: argument {index} must not be NULL"),
        }
    }
}

/// A `circletree` argument as its detoasted stored bytes, neither decoded nor validated: for the
/// functions that need only the bytes (`=`, `<>`, `::bytea`, `ct_memsize`) or the header
/// (`ct_srid`). In SQL it is the same type as [`CircleTree`].
pub struct StoredBytes<'fcx>(pub &'fcx [u8]);

unsafe impl<'fcx> ArgAbi<'fcx> for StoredBytes<'fcx> {
    unsafe fn unbox_arg_unchecked(arg: Arg<'_, 'fcx>) -> Self {
        // SAFETY: a circletree datum is a plain varlena, as bytea's.
        StoredBytes(unsafe { <&'fcx [u8] as ArgAbi<'fcx>>::unbox_arg_unchecked(arg) })
    }

    unsafe fn unbox_nullable_arg(arg: Arg<'_, 'fcx>) -> pgrx::nullable::Nullable<Self> {
        match unsafe { <&'fcx [u8] as ArgAbi<'fcx>>::unbox_nullable_arg(arg) } {
            pgrx::nullable::Nullable::Valid(b) => pgrx::nullable::Nullable::Valid(StoredBytes(b)),
            _ => pgrx::nullable::Nullable::Null,
        }
    }
}

use pgrx::pgrx_sql_entity_graph::metadata::{
    ArgumentError, ReturnsError, ReturnsRef, SqlMappingRef, SqlTranslatable, TypeOrigin,
};

unsafe impl SqlTranslatable for StoredBytes<'_> {
    const TYPE_IDENT: &'static str = <CircleTree as SqlTranslatable>::TYPE_IDENT;
    const TYPE_ORIGIN: TypeOrigin = <CircleTree as SqlTranslatable>::TYPE_ORIGIN;
    const ARGUMENT_SQL: Result<SqlMappingRef, ArgumentError> =
        <CircleTree as SqlTranslatable>::ARGUMENT_SQL;
    const RETURN_SQL: Result<ReturnsRef, ReturnsError> =
        <CircleTree as SqlTranslatable>::RETURN_SQL;
}
