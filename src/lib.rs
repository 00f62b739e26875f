//! circletree: a PostgreSQL extension that stores PostGIS polygons as ordered circles
//! `(x, y, ±r)` and rebuilds them from tangents and arcs. This crate is glue only: the algorithms,
//! the on-disk format and its validation live in `crates/circletree-core`.

use pgrx::prelude::*;

::pgrx::pg_module_magic!(name, version);

pub mod datatype;
pub mod error;
pub mod functions;

extension_sql!(
    r#"
-- PostGIS-facing wrappers. They are SQL functions so the planner can inline them; PostGIS is
-- resolved through the caller's search_path (PostgreSQL 15 has no @extschema:postgis@).
CREATE FUNCTION ct_decode(ct circletree) RETURNS geometry
    LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$ SELECT ST_GeomFromEWKB(_ct_decode_ewkb($1, NULL)) $$;
CREATE FUNCTION ct_decode(ct circletree, arc_tolerance float8) RETURNS geometry
    LANGUAGE sql IMMUTABLE PARALLEL SAFE
    AS $$ SELECT ST_GeomFromEWKB(_ct_decode_ewkb($1, $2)) $$;
CREATE FUNCTION ct_decode_curved(ct circletree) RETURNS geometry
    LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$ SELECT ST_GeomFromEWKT(_ct_decode_curved_ewkt($1)) $$;

-- Validity is PostGIS's own (ST_IsValid), so what PostGIS accepts, circletree accepts.
CREATE FUNCTION ct_encode(geom geometry, min_radius float8, overlap float8 DEFAULT 0.4,
                          dp_tolerance float8 DEFAULT NULL, max_error float8 DEFAULT NULL)
    RETURNS circletree LANGUAGE sql IMMUTABLE PARALLEL SAFE
    AS $$ SELECT _ct_encode_wkb(ST_AsBinary($1), ST_SRID($1),
            CASE WHEN GeometryType($1) IN ('POLYGON', 'MULTIPOLYGON') AND NOT ST_IsValid($1)
                 THEN ST_IsValidReason($1) END,
            $2, $3, $4, $5) $$;
-- The fewest bytes whose ct_decode is valid and within max_error (points only, on the grid that
-- gives the fewest bytes; see docs/ALGORITHM.md).
CREATE FUNCTION ct_encode_within(geom geometry, max_error float8)
    RETURNS circletree LANGUAGE sql IMMUTABLE PARALLEL SAFE
    AS $$ SELECT _ct_encode_within_wkb(ST_AsBinary($1), ST_SRID($1),
            CASE WHEN GeometryType($1) IN ('POLYGON', 'MULTIPOLYGON') AND NOT ST_IsValid($1)
                 THEN ST_IsValidReason($1) END,
            $2) $$;

CREATE FUNCTION ct_storage_ratio(ct circletree, geom geometry) RETURNS float8
    LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$ SELECT pg_column_size($1)::float8 / pg_column_size($2) $$;
CREATE FUNCTION ct_sliver_error(ct circletree, geom geometry) RETURNS float8
    LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$ SELECT _ct_sliver_error_wkb($1, ST_AsBinary($2)) $$;
CREATE FUNCTION ct_sliver_ratio(ct circletree, geom geometry) RETURNS float8
    LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$ SELECT _ct_sliver_error_wkb($1, ST_AsBinary($2)) / NULLIF(ST_Area($2), 0) $$;
CREATE FUNCTION ct_hausdorff(ct circletree, geom geometry) RETURNS float8
    LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$ SELECT _ct_hausdorff_wkb($1, ST_AsBinary($2)) $$;
-- The same measure between any two (Multi)Polygons, to compare other simplifications fairly.
CREATE FUNCTION ct_hausdorff(a geometry, b geometry) RETURNS float8
    LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$ SELECT _ct_hausdorff_wkb2(ST_AsBinary($1), ST_AsBinary($2)) $$;

-- The paper's experiment (figures 11-14) on one polygon: every combination of the three arrays.
CREATE FUNCTION ct_sweep(geom geometry,
        min_radius float8[] DEFAULT '{1,5,10,15,25}',
        overlap float8[] DEFAULT '{0,0.1,0.4,0.6,0.9}',
        dp_tolerance float8[] DEFAULT '{NULL,1,5,10,15,25}')
    RETURNS TABLE(min_radius float8, overlap float8, dp_tolerance float8, circles int, internal int,
                  external int, zero int, added_by_repair int, bytes int, storage_ratio float8,
                  sliver_ratio float8, hausdorff float8, valid bool)
    LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$
    SELECT m, o, d, (s->>'circles')::int, (s->>'internal')::int, (s->>'external')::int,
           (s->>'zero')::int, (s->>'added_by_repair')::int, (s->>'bytes')::int,
           (s->>'storage_ratio')::float8, ct_sliver_ratio(ct, $1), ct_hausdorff(ct, $1),
           ST_IsValid(ct_decode(ct))
      FROM unnest($2) m, unnest($3) o, unnest($4) d,
           LATERAL (SELECT ct_encode($1, m, o, d) AS ct) e,
           LATERAL (SELECT ct_summary(e.ct) AS s) x
     ORDER BY d NULLS FIRST, o, m
    $$;
"#,
    name = "postgis_wrappers",
    requires = [
        "circletree_binary_io",
        functions::_ct_decode_ewkb,
        functions::_ct_decode_curved_ewkt,
        functions::_ct_encode_within_wkb,
        functions::ct_srid
    ]
);

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
