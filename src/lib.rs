//! circletree: a PostgreSQL extension that stores PostGIS polygons as ordered circles
//! `(x, y, ±r)` and rebuilds them from tangents and arcs. This crate is glue only: the algorithms,
//! the on-disk format and its validation live in `crates/circletree-core`.

use pgrx::prelude::*;

::pgrx::pg_module_magic!(name, version);

pub mod access;
pub mod datatype;
pub mod error;
pub mod functions;
pub mod index;
pub mod postgis;
pub mod settings;

/// Registers the settings (`circletree.max_encode_memory`).
#[pg_guard]
pub extern "C-unwind" fn _PG_init() {
    settings::init();
}

extension_sql_file!(
    "../sql/postgis_wrappers.sql",
    name = "postgis_wrappers",
    requires = [
        "circletree_binary_io",
        functions::_ct_decode_ewkb,
        functions::_ct_decode_curved_ewkt,
        functions::_ct_encode_wkb,
        functions::_ct_encode_within_wkb,
        functions::_ct_sliver_error_wkb,
        functions::_ct_sliver_error_checked_wkb,
        functions::_ct_check_degrees,
        functions::_ct_svg_wkb,
        functions::_ct_hausdorff_wkb,
        functions::_ct_hausdorff_wkb2,
        functions::ct_summary,
        functions::ct_srid
    ]
);

extension_sql_file!(
    "../sql/in_place.sql",
    name = "in_place",
    requires = ["circletree_binary_io", "postgis_wrappers"]
);

// Catalog documentation of every object (COMMENT ON), once everything exists.
extension_sql_file!("../sql/comments.sql", name = "comments", finalize);

/// `#[pg_test]`s: what needs a backend (datum round trips, SQLSTATEs). The SQL contract itself
/// is covered by the pg_regress files in tests/pg_regress.
#[cfg(any(test, feature = "pg_test"))]
#[pg_schema]
mod tests {
    use pgrx::prelude::*;

    const DISC: &str = "SRID=32760;CIRCLETREE(grid=0.5;min_radius=5;overlap=0.4;dp_tolerance=NULL;max_error=5;vertices=5;wkb_bytes=93;repaired=0;bbox=(0 0,10 10);POLYGON((5 5 5)))";

    #[pg_test]
    fn text_round_trip_keeps_bytes() {
        let same = Spi::get_one::<bool>(&format!(
            "SELECT c::text::circletree = c AND c::bytea = c::text::circletree::bytea FROM (SELECT '{DISC}'::circletree c) s"
        ));
        assert_eq!(same, Ok(Some(true)));
    }

    #[pg_test]
    fn datum_bytes_are_ours_not_cbor() {
        // version byte 1, kind 3 (Polygon)
        let head = Spi::get_one::<Vec<u8>>(&format!(
            "SELECT substring('{DISC}'::circletree::bytea from 1 for 2)"
        ));
        assert_eq!(head, Ok(Some(vec![1u8, 3])));
    }

    #[pg_test(
        error = "corrupt circletree value: format version 9 is not known to this release (it reads versions 1 and 2)"
    )]
    fn corrupt_bytea_is_a_clean_error() {
        let _ = Spi::get_one::<i32>("SELECT ct_ncircles('\\x0903'::bytea::circletree)");
    }

    #[pg_test]
    fn decode_disc_is_valid_with_srid() {
        let r = Spi::get_one::<String>(&format!(
            "SELECT ST_IsValid(g)::text || ' ' || ST_SRID(g) || ' ' || round(ST_Area(g)::numeric, 0) || ' ' || round(ST_Area(ct_decode(c))::numeric, 0) FROM (SELECT ct_decode(c, 0.001) g, c FROM (SELECT '{DISC}'::circletree c) v) s"
        ));
        // r = 5: 25π ≈ 78.5 with fine arcs; the default chord tolerance (the 0.5 grid) gives a 7-gon of 68.
        assert_eq!(r, Ok(Some("true 32760 79 68".to_string())));
    }
}

/// Required by `cargo pgrx test`.
#[cfg(test)]
pub mod pg_test {
    pub fn setup(_options: Vec<&str>) {}

    #[must_use]
    pub fn postgresql_conf_options() -> Vec<&'static str> {
        vec![]
    }
}
