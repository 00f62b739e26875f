-- PostGIS-facing wrappers (loaded by src/lib.rs with extension_sql_file!, and repeated as they are in
-- the upgrade script of each release that changed them: sql/circletree--0.4.0--0.5.0.sql holds
-- 0.5.0's, sql/circletree--0.5.0--0.6.0.sql this text).
--
-- They are SQL functions so the planner can inline them. Every function they call is schema-qualified,
-- so a schema ahead of PostGIS's in a caller's search_path cannot change what they compute (the
-- CVE-2018-1058 class of bug): PostGIS's own functions through the schema PostGIS is installed in,
-- read here at install time (PostgreSQL 15 has no @extschema:postgis@), circletree's through
-- @extschema@, the built-ins through pg_catalog. The types in the signatures are resolved once, here.
-- The envelope from the header alone: the C function takes the circletree datum as its bytes.
CREATE OR REPLACE FUNCTION @extschema@._ct_envelope_ewkb(ct @extschema@.circletree) RETURNS bytea
    IMMUTABLE STRICT PARALLEL SAFE
    LANGUAGE c AS 'MODULE_PATHNAME', '_ct_envelope_ewkb_wrapper';

DO $install$
DECLARE
  pg text := (SELECT n.nspname FROM pg_catalog.pg_extension e
                JOIN pg_catalog.pg_namespace n ON n.oid = e.extnamespace
               WHERE e.extname = 'postgis');
BEGIN
  EXECUTE pg_catalog.format($sql$
CREATE OR REPLACE FUNCTION @extschema@.ct_decode(ct @extschema@.circletree) RETURNS %1$I.geometry
    LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$ SELECT %1$I.ST_GeomFromEWKB(@extschema@._ct_decode_ewkb($1, NULL)) $$;
CREATE OR REPLACE FUNCTION @extschema@.ct_decode(ct @extschema@.circletree, arc_tolerance float8) RETURNS %1$I.geometry
    LANGUAGE sql IMMUTABLE PARALLEL SAFE
    AS $$ SELECT %1$I.ST_GeomFromEWKB(@extschema@._ct_decode_ewkb($1, $2)) $$;
CREATE OR REPLACE FUNCTION @extschema@.ct_decode_curved(ct @extschema@.circletree) RETURNS %1$I.geometry
    LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$ SELECT %1$I.ST_GeomFromEWKT(@extschema@._ct_decode_curved_ewkt($1)) $$;

-- A box holding the original and ct_decode(ct), from the header alone (cheap: no circle is decoded),
-- for an expression index: CREATE INDEX ... USING gist (ct_envelope(ct)).
CREATE OR REPLACE FUNCTION @extschema@.ct_envelope(ct @extschema@.circletree) RETURNS %1$I.geometry
    LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$ SELECT %1$I.ST_GeomFromEWKB(@extschema@._ct_envelope_ewkb($1)) $$;

-- Whether an SRID's units are degrees of longitude and latitude (from PostGIS's spatial_ref_sys).
-- IMMUTABLE as PostGIS's ST_Transform is (an SRID's definition does not change), so ct_encode
-- stays inlinable.
CREATE OR REPLACE FUNCTION @extschema@._ct_srid_is_lonlat(srid int) RETURNS bool
    LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$ SELECT COALESCE((SELECT s.proj4text LIKE '%%+proj=longlat%%' OR s.srtext LIKE 'GEOGCS%%'
                                        OR s.srtext LIKE 'GEOGCRS%%'
                                       FROM %1$I.spatial_ref_sys s WHERE s.srid = $1), false) $$;

-- PostGIS's reason when a (Multi)Polygon is not valid, else NULL (other types are refused later,
-- by their type; with M values GeometryType says POLYGONM).
CREATE OR REPLACE FUNCTION @extschema@._ct_invalid_reason(geom %1$I.geometry) RETURNS text
    LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$ SELECT CASE WHEN %1$I.GeometryType($1) IN ('POLYGON', 'MULTIPOLYGON', 'POLYGONM', 'MULTIPOLYGONM')
                       AND NOT %1$I.ST_IsValid($1)
                      THEN %1$I.ST_IsValidReason($1) END $$;

-- The encoders (0.6.0 on): the geometry, its WKB and PostGIS's ST_IsValid and ST_IsValidReason
-- (resolved, schema-qualified, when the calling query is planned), which the encoder calls itself,
-- beside its own work on a large input (src/postgis.rs).
CREATE OR REPLACE FUNCTION @extschema@._ct_encode_geom(geom %1$I.geometry, wkb bytea, srid int,
        is_valid pg_catalog.regprocedure, reason pg_catalog.regprocedure, min_radius float8,
        overlap float8, dp_tolerance float8, max_error float8)
    RETURNS @extschema@.circletree IMMUTABLE PARALLEL SAFE
    LANGUAGE c AS 'MODULE_PATHNAME', '_ct_encode_geom_wrapper';
CREATE OR REPLACE FUNCTION @extschema@._ct_encode_within_geom(geom %1$I.geometry, wkb bytea, srid int,
        is_valid pg_catalog.regprocedure, reason pg_catalog.regprocedure, max_error float8)
    RETURNS @extschema@.circletree IMMUTABLE PARALLEL SAFE
    LANGUAGE c AS 'MODULE_PATHNAME', '_ct_encode_within_geom_wrapper';

-- Validity is PostGIS's own (ST_IsValid), so what PostGIS accepts, circletree accepts. On a
-- longitude/latitude SRID a length of a degree or more is refused (metres given by mistake).
CREATE OR REPLACE FUNCTION @extschema@.ct_encode(geom %1$I.geometry, min_radius float8, overlap float8 DEFAULT 0.4,
                          dp_tolerance float8 DEFAULT NULL, max_error float8 DEFAULT NULL)
    RETURNS @extschema@.circletree LANGUAGE sql IMMUTABLE PARALLEL SAFE
    AS $$ SELECT CASE WHEN @extschema@._ct_check_degrees(@extschema@._ct_srid_is_lonlat(%1$I.ST_SRID($1)),
                                                       %1$I.ST_SRID($1), $2, $4, $5)
            THEN @extschema@._ct_encode_geom($1, %1$I.ST_AsBinary($1), %1$I.ST_SRID($1),
            %2$L::pg_catalog.regprocedure, %3$L::pg_catalog.regprocedure,
            $2, $3, $4, $5) END $$;
-- The fewest bytes whose ct_decode is valid and within max_error (points only, on the grid that
-- gives the fewest bytes; see docs/ALGORITHM.md).
CREATE OR REPLACE FUNCTION @extschema@.ct_encode_within(geom %1$I.geometry, max_error float8)
    RETURNS @extschema@.circletree LANGUAGE sql IMMUTABLE PARALLEL SAFE
    AS $$ SELECT CASE WHEN @extschema@._ct_check_degrees(@extschema@._ct_srid_is_lonlat(%1$I.ST_SRID($1)),
                                                       %1$I.ST_SRID($1), NULL, NULL, $2)
            THEN @extschema@._ct_encode_within_geom($1, %1$I.ST_AsBinary($1), %1$I.ST_SRID($1),
            %2$L::pg_catalog.regprocedure, %3$L::pg_catalog.regprocedure,
            $2) END $$;

-- Longitude/latitude data in metres: a geography is encoded in the WGS 84 UTM zone of its bounding
-- box's centre (UPS north of 84N and south of 80S), where lengths are metres; the value keeps that
-- SRID, and ct_decode_geography brings it back to longitude/latitude.
CREATE OR REPLACE FUNCTION @extschema@.ct_utm_srid(geog %1$I.geography) RETURNS int
    LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$ SELECT CASE WHEN lat > 84 THEN 32661 WHEN lat < -80 THEN 32761
                      WHEN lat >= 0 THEN 32600 + zone ELSE 32700 + zone END
            FROM (SELECT (%1$I.ST_YMin(b) + %1$I.ST_YMax(b)) / 2 AS lat,
                         LEAST(60, GREATEST(1,
                           pg_catalog.floor(((%1$I.ST_XMin(b) + %1$I.ST_XMax(b)) / 2 + 180) / 6)::int + 1)) AS zone
                    FROM (SELECT %1$I.Box3D($1::%1$I.geometry) AS b) bb) c $$;
CREATE OR REPLACE FUNCTION @extschema@.ct_encode(geog %1$I.geography, min_radius float8, overlap float8 DEFAULT 0.4,
                          dp_tolerance float8 DEFAULT NULL, max_error float8 DEFAULT NULL)
    RETURNS @extschema@.circletree LANGUAGE sql IMMUTABLE PARALLEL SAFE
    AS $$ SELECT @extschema@.ct_encode(%1$I.ST_Transform($1::%1$I.geometry, @extschema@.ct_utm_srid($1)),
                                       $2, $3, $4, $5) $$;
CREATE OR REPLACE FUNCTION @extschema@.ct_encode_within(geog %1$I.geography, max_error float8)
    RETURNS @extschema@.circletree LANGUAGE sql IMMUTABLE PARALLEL SAFE
    AS $$ SELECT @extschema@.ct_encode_within(%1$I.ST_Transform($1::%1$I.geometry, @extschema@.ct_utm_srid($1)), $2) $$;
CREATE OR REPLACE FUNCTION @extschema@.ct_decode_geography(ct @extschema@.circletree, srid int DEFAULT 4326)
    RETURNS %1$I.geography LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$ SELECT %1$I.ST_Transform(@extschema@.ct_decode($1), $2)::%1$I.geography $$;
-- Text (an untyped literal) reads as geometry, as PostGIS's own text variants do: with both a
-- geometry and a geography ct_encode, ct_encode('POLYGON(...)', 5) would otherwise be ambiguous.
CREATE OR REPLACE FUNCTION @extschema@.ct_encode(geom text, min_radius float8, overlap float8 DEFAULT 0.4,
                          dp_tolerance float8 DEFAULT NULL, max_error float8 DEFAULT NULL)
    RETURNS @extschema@.circletree LANGUAGE sql IMMUTABLE PARALLEL SAFE
    AS $$ SELECT @extschema@.ct_encode($1::%1$I.geometry, $2, $3, $4, $5) $$;
CREATE OR REPLACE FUNCTION @extschema@.ct_encode_within(geom text, max_error float8)
    RETURNS @extschema@.circletree LANGUAGE sql IMMUTABLE PARALLEL SAFE
    AS $$ SELECT @extschema@.ct_encode_within($1::%1$I.geometry, $2) $$;

CREATE OR REPLACE FUNCTION @extschema@.ct_storage_ratio(ct @extschema@.circletree, geom %1$I.geometry) RETURNS float8
    LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$ SELECT pg_catalog.pg_column_size($1)::float8 / pg_catalog.pg_column_size($2) $$;
CREATE OR REPLACE FUNCTION @extschema@.ct_sliver_error(ct @extschema@.circletree, geom %1$I.geometry) RETURNS float8
    LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$ SELECT @extschema@._ct_sliver_error_wkb($1, %1$I.ST_AsBinary($2), @extschema@._ct_invalid_reason($2)) $$;
CREATE OR REPLACE FUNCTION @extschema@.ct_sliver_ratio(ct @extschema@.circletree, geom %1$I.geometry) RETURNS float8
    LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$ SELECT @extschema@._ct_sliver_error_wkb($1, %1$I.ST_AsBinary($2), @extschema@._ct_invalid_reason($2))
                 / NULLIF(%1$I.ST_Area($2), 0) $$;
CREATE OR REPLACE FUNCTION @extschema@.ct_hausdorff(ct @extschema@.circletree, geom %1$I.geometry) RETURNS float8
    LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$ SELECT @extschema@._ct_hausdorff_wkb($1, %1$I.ST_AsBinary($2)) $$;
-- The same measure between any two (Multi)Polygons, to compare other simplifications fairly.
CREATE OR REPLACE FUNCTION @extschema@.ct_hausdorff(a %1$I.geometry, b %1$I.geometry) RETURNS float8
    LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$ SELECT @extschema@._ct_hausdorff_wkb2(%1$I.ST_AsBinary($1), %1$I.ST_AsBinary($2)) $$;

-- A picture of the value, like the paper's figures 9, 10 and 15 (the original drawn beneath it when given).
CREATE OR REPLACE FUNCTION @extschema@.ct_svg(ct @extschema@.circletree, geom %1$I.geometry DEFAULT NULL,
                                              width int DEFAULT 800) RETURNS text
    LANGUAGE sql IMMUTABLE PARALLEL SAFE
    AS $$ SELECT @extschema@._ct_svg_wkb($1, %1$I.ST_AsBinary($2), $3) $$;

-- The paper's experiment (figures 11-14) on one polygon: every combination of the three arrays.
CREATE OR REPLACE FUNCTION @extschema@.ct_sweep(geom %1$I.geometry,
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
           (s->>'storage_ratio')::float8, @extschema@.ct_sliver_ratio(ct, $1), @extschema@.ct_hausdorff(ct, $1),
           %1$I.ST_IsValid(@extschema@.ct_decode(ct))
      FROM pg_catalog.unnest($2) m, pg_catalog.unnest($3) o, pg_catalog.unnest($4) d,
           LATERAL (SELECT @extschema@.ct_encode($1, m, o, d) AS ct) e,
           LATERAL (SELECT @extschema@.ct_summary(e.ct) AS s) x
     ORDER BY d NULLS FIRST, o, m
    $$;
$sql$, pg, pg_catalog.format('%I.st_isvalid(%I.geometry)', pg, pg),
        pg_catalog.format('%I.st_isvalidreason(%I.geometry)', pg, pg));
END
$install$;
