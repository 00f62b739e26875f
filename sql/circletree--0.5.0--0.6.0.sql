-- circletree 0.5.0 -> 0.6.0 (ALTER EXTENSION circletree UPDATE).
-- 0.6.0's encoders ask PostGIS's ST_IsValid themselves (_ct_encode_geom and _ct_encode_within_geom,
-- given the geometry and the two PostGIS functions), so that on a large input the encoder runs
-- beside the check instead of after it; a Polygon or MultiPolygon with M values is now checked too
-- (GeometryType names it POLYGONM, which 0.5.0's _ct_invalid_reason did not ask about). 0.5.0's
-- _ct_encode_wkb and _ct_encode_within_wkb stay: 0.5.0's definitions call them until this update
-- runs. Stored values and their format are unchanged.
-- The definitions are those of a fresh 0.6.0 install (regress `upgrade` compares the two).

-- Every PostGIS-facing wrapper again: the same text as sql/postgis_wrappers.sql, which a fresh
-- install runs.
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

-- The catalog comments again: the same text as sql/comments.sql.
-- Catalog documentation: what \dT+ circletree and \df+ ct_* show. Loaded last by src/lib.rs
-- (extension_sql_file!), and repeated in the upgrade script of each release that changed it
-- (sql/circletree--0.3.0--0.4.0.sql introduced it; sql/circletree--0.5.0--0.6.0.sql holds this text).
COMMENT ON TYPE @extschema@.circletree IS
  'A polygon stored as ordered circles (x, y, ±r), rebuilt from tangents and arcs; valid and within its recorded max_error (Hausdorff) of the original. See docs/FORMAT.md.';
COMMENT ON FUNCTION @extschema@.ct_encode(geometry, float8, float8, float8, float8) IS
  'ct_encode(geom, min_radius, overlap DEFAULT 0.4, dp_tolerance DEFAULT NULL, max_error DEFAULT NULL): the paper''s circles (medial circles of at least min_radius, overlapping by at most overlap, Douglas-Peucker points at dp_tolerance), repaired until ct_decode is valid and within max_error (NULL: greatest(min_radius, dp_tolerance)). Lengths in the SRID''s units.';
COMMENT ON FUNCTION @extschema@.ct_encode_within(geometry, float8) IS
  'ct_encode_within(geom, max_error): the fewest bytes whose ct_decode is valid and within max_error (continuous Hausdorff, in the SRID''s units).';
COMMENT ON FUNCTION @extschema@.ct_encode(geography, float8, float8, float8, float8) IS
  'ct_encode(geog, min_radius, ...): ct_encode in metres for longitude/latitude data: the geography projected to the WGS 84 UTM zone of its centre (ct_utm_srid), whose SRID the value keeps; ct_decode_geography brings it back.';
COMMENT ON FUNCTION @extschema@.ct_encode_within(geography, float8) IS
  'ct_encode_within(geog, max_error): ct_encode_within in metres for longitude/latitude data, in the UTM zone of its centre (ct_utm_srid).';
COMMENT ON FUNCTION @extschema@.ct_encode(text, float8, float8, float8, float8) IS
  'ct_encode(text, ...): the text read as a geometry (so an untyped literal is not ambiguous between geometry and geography).';
COMMENT ON FUNCTION @extschema@.ct_encode_within(text, float8) IS
  'ct_encode_within(text, max_error): the text read as a geometry.';
COMMENT ON FUNCTION @extschema@.ct_utm_srid(geography) IS
  'ct_utm_srid(geog): the SRID of the WGS 84 UTM zone of the centre of geog''s bounding box (32601-32660 north, 32701-32760 south; UPS 32661 north of 84N, 32761 south of 80S), where the geography overloads encode.';
COMMENT ON FUNCTION @extschema@.ct_decode_geography(@extschema@.circletree, int) IS
  'ct_decode_geography(ct, srid DEFAULT 4326): ct_decode(ct) transformed to the longitude/latitude SRID srid, as geography.';
COMMENT ON FUNCTION @extschema@.ct_svg(@extschema@.circletree, geometry, int) IS
  'ct_svg(ct, geom DEFAULT NULL, width DEFAULT 800): an SVG picture: circles inside (blue) and outside (red), boundary points (green), the rebuilt polygon (black) and, when given, the original (grey), with a legend.';
COMMENT ON FUNCTION @extschema@._ct_svg_wkb(@extschema@.circletree, bytea, int) IS
  'Internal: ct_svg with the original as WKB.';
COMMENT ON FUNCTION @extschema@._ct_srid_is_lonlat(int) IS
  'Internal: whether spatial_ref_sys gives the SRID longitude/latitude units (degrees).';
COMMENT ON FUNCTION @extschema@._ct_check_degrees(bool, int, float8, float8, float8) IS
  'Internal: true, or an ERROR when a longitude/latitude SRID meets a length of a degree or more (metres given by mistake).';
COMMENT ON FUNCTION @extschema@._ct_invalid_reason(geometry) IS
  'Internal: ST_IsValidReason of an invalid Polygon or MultiPolygon, else NULL.';
COMMENT ON FUNCTION @extschema@.ct_decode(@extschema@.circletree) IS
  'ct_decode(ct): the rebuilt POLYGON or MULTIPOLYGON, SRID kept, arcs stroked to the value''s grid step.';
COMMENT ON FUNCTION @extschema@.ct_decode(@extschema@.circletree, float8) IS
  'ct_decode(ct, arc_tolerance): the rebuilt polygon with arcs stroked so no chord lies farther than arc_tolerance from its arc (NULL: the grid step; validity is guaranteed up to the grid step).';
COMMENT ON FUNCTION @extschema@.ct_decode_curved(@extschema@.circletree) IS
  'ct_decode_curved(ct): the rebuilt CURVEPOLYGON or MULTISURFACE with true circular arcs, SRID kept.';
COMMENT ON FUNCTION @extschema@.ct_envelope(@extschema@.circletree) IS
  'ct_envelope(ct): a box holding both the original and ct_decode(ct) (the stored bounding box widened by max_error), read from the header without decoding a circle: index it with CREATE INDEX ... USING gist (ct_envelope(ct)).';
COMMENT ON FUNCTION @extschema@._ct_envelope_ewkb(@extschema@.circletree) IS
  'Internal: ct_envelope as EWKB, from the header alone.';
COMMENT ON FUNCTION @extschema@.ct_circles(@extschema@.circletree) IS
  'ct_circles(ct): the stored circles in boundary order: part, ring, seq (1-based), centre x, y and signed radius r (> 0 inside, < 0 outside, 0 a boundary point).';
COMMENT ON FUNCTION @extschema@.ct_ncircles(@extschema@.circletree) IS
  'ct_ncircles(ct): number of stored circles in all rings (a repeated circle counts each time).';
COMMENT ON FUNCTION @extschema@.ct_srid(@extschema@.circletree) IS
  'ct_srid(ct): the SRID the value was encoded with (read from its header).';
COMMENT ON FUNCTION @extschema@.ct_memsize(@extschema@.circletree) IS
  'ct_memsize(ct): bytes of the value in memory, varlena header included (as ST_MemSize).';
COMMENT ON FUNCTION @extschema@.ct_summary(@extschema@.circletree) IS
  'ct_summary(ct): everything about a value as jsonb: format version, SRID, kind, parts, rings, circles by kind, grid, bytes, original vertices and WKB bytes, parameters.';
COMMENT ON FUNCTION @extschema@.ct_storage_ratio(@extschema@.circletree) IS
  'ct_storage_ratio(ct): ct_memsize over the WKB bytes of the original (recorded at encode time).';
COMMENT ON FUNCTION @extschema@.ct_storage_ratio(@extschema@.circletree, geometry) IS
  'ct_storage_ratio(ct, geom): pg_column_size(ct) over pg_column_size(geom).';
COMMENT ON FUNCTION @extschema@.ct_sliver_error(@extschema@.circletree, geometry) IS
  'ct_sliver_error(ct, geom): area of the symmetric difference between ct_decode(ct) and geom (the SRID''s units squared); an invalid geom is refused (22023).';
COMMENT ON FUNCTION @extschema@.ct_sliver_ratio(@extschema@.circletree, geometry) IS
  'ct_sliver_ratio(ct, geom): ct_sliver_error over ST_Area(geom).';
COMMENT ON FUNCTION @extschema@.ct_hausdorff(@extschema@.circletree, geometry) IS
  'ct_hausdorff(ct, geom): continuous Hausdorff distance between the boundaries of the rebuilt polygon (true arcs) and geom: whole segments, not only vertices.';
COMMENT ON FUNCTION @extschema@.ct_hausdorff(geometry, geometry) IS
  'ct_hausdorff(a, b): the same continuous Hausdorff distance between the boundaries of any two (Multi)Polygons, e.g. to measure ST_Simplify''s result the way circletree is measured.';
COMMENT ON FUNCTION @extschema@.ct_sweep(geometry, float8[], float8[], float8[]) IS
  'ct_sweep(geom, min_radius[], overlap[], dp_tolerance[]): the paper''s experiment: one ct_encode per combination, with circles by kind, bytes, storage ratio, sliver ratio, Hausdorff distance and validity.';
COMMENT ON FUNCTION @extschema@._ct_encode_wkb(bytea, int, text, float8, float8, float8, float8) IS
  'Internal: ct_encode on WKB with PostGIS''s verdict passed in (called by ct_encode up to release 0.5.0).';
COMMENT ON FUNCTION @extschema@._ct_encode_within_wkb(bytea, int, text, float8) IS
  'Internal: ct_encode_within on WKB with PostGIS''s verdict passed in (called by ct_encode_within up to release 0.5.0).';
COMMENT ON FUNCTION @extschema@._ct_encode_geom(geometry, bytea, int, regprocedure, regprocedure, float8, float8, float8, float8) IS
  'Internal: ct_encode of the geometry (its WKB and SRID), asking PostGIS''s ST_IsValid and ST_IsValidReason (the two functions given) beside the encoder (called by ct_encode).';
COMMENT ON FUNCTION @extschema@._ct_encode_within_geom(geometry, bytea, int, regprocedure, regprocedure, float8) IS
  'Internal: ct_encode_within of the geometry (its WKB and SRID), asking PostGIS''s ST_IsValid and ST_IsValidReason (the two functions given) beside the encoder (called by ct_encode_within).';
COMMENT ON FUNCTION @extschema@._ct_decode_ewkb(@extschema@.circletree, float8) IS
  'Internal: the rebuilt polygon as EWKB (called by ct_decode).';
COMMENT ON FUNCTION @extschema@._ct_decode_curved_ewkt(@extschema@.circletree) IS
  'Internal: the rebuilt polygon with true arcs as EWKT (called by ct_decode_curved).';
COMMENT ON FUNCTION @extschema@._ct_decode_wkb(@extschema@.circletree, float8) IS
  'Internal, kept for databases not yet updated from 0.3.0: the rebuilt polygon as WKB.';
COMMENT ON FUNCTION @extschema@._ct_decode_curved_wkt(@extschema@.circletree) IS
  'Internal, kept for databases not yet updated from 0.3.0: the rebuilt polygon with true arcs as WKT.';
COMMENT ON FUNCTION @extschema@._ct_sliver_error_wkb(@extschema@.circletree, bytea) IS
  'Internal: ct_sliver_error against WKB (0.4.0''s wrappers; 0.5.0''s pass the validity too).';
COMMENT ON FUNCTION @extschema@._ct_sliver_error_wkb(@extschema@.circletree, bytea, text) IS
  'Internal: ct_sliver_error against WKB, refusing an invalid original (its ST_IsValidReason).';
COMMENT ON FUNCTION @extschema@._ct_hausdorff_wkb(@extschema@.circletree, bytea) IS
  'Internal: ct_hausdorff against WKB.';
COMMENT ON FUNCTION @extschema@._ct_hausdorff_wkb2(bytea, bytea) IS
  'Internal: ct_hausdorff between two WKB polygons.';
COMMENT ON FUNCTION @extschema@.circletree_in(cstring) IS
  'Text input: SRID=n;CIRCLETREE(...) as circletree::text prints it (docs/FORMAT.md).';
COMMENT ON FUNCTION @extschema@.circletree_out(@extschema@.circletree) IS
  'Text output: every header field and circle, exact (reads back to the same bytes).';
COMMENT ON FUNCTION @extschema@.circletree_recv(internal) IS
  'Binary input (COPY BINARY, binary protocol): the stored bytes, fully checked.';
COMMENT ON FUNCTION @extschema@.circletree_send(@extschema@.circletree) IS
  'Binary output: the stored bytes.';
COMMENT ON FUNCTION @extschema@.circletree_eq(@extschema@.circletree, @extschema@.circletree) IS
  'Byte equality of two values.';
COMMENT ON FUNCTION @extschema@.circletree_ne(@extschema@.circletree, @extschema@.circletree) IS
  'Byte inequality of two values.';
COMMENT ON FUNCTION @extschema@.circletree_to_bytea(@extschema@.circletree) IS
  'The stored bytes as bytea (circletree::bytea).';
COMMENT ON FUNCTION @extschema@.circletree_from_bytea(bytea) IS
  'bytea::circletree: stored bytes of any format version, fully checked (22P03 when corrupt).';
COMMENT ON OPERATOR @extschema@.= (@extschema@.circletree, @extschema@.circletree) IS
  'Byte equality of two values.';
COMMENT ON OPERATOR @extschema@.<> (@extschema@.circletree, @extschema@.circletree) IS
  'Byte inequality of two values.';
