-- circletree 0.2.0 -> 0.3.0 (ALTER EXTENSION circletree UPDATE).
-- 0.3.0 adds ct_encode_within(geom, max_error): the fewest bytes whose ct_decode is valid and within
-- max_error. It writes format version 2, like ct_encode; every stored value stays as it is.
-- The definitions are those of a fresh 0.3.0 install (regress `upgrade` compares the two).

CREATE FUNCTION "_ct_encode_within_wkb"(
	"wkb" bytea, /* Option < & [u8] > */
	"srid" INT, /* Option < i32 > */
	"invalid_reason" TEXT, /* Option < & str > */
	"max_error" double precision /* Option < f64 > */
) RETURNS CircleTree /* Option < CircleTree > */
IMMUTABLE PARALLEL SAFE
LANGUAGE c /* Rust */
AS 'MODULE_PATHNAME', '_ct_encode_within_wkb_wrapper';

-- The fewest bytes whose ct_decode is valid and within max_error (points only, on the grid that
-- gives the fewest bytes; see docs/ALGORITHM.md).
CREATE FUNCTION ct_encode_within(geom geometry, max_error float8)
    RETURNS circletree LANGUAGE sql IMMUTABLE PARALLEL SAFE
    AS $$ SELECT _ct_encode_within_wkb(ST_AsBinary($1), ST_SRID($1),
            CASE WHEN GeometryType($1) IN ('POLYGON', 'MULTIPOLYGON') AND NOT ST_IsValid($1)
                 THEN ST_IsValidReason($1) END,
            $2) $$;
