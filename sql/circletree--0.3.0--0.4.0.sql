-- circletree 0.3.0 -> 0.4.0 (ALTER EXTENSION circletree UPDATE).
-- 0.4.0 decodes a value once per ct_decode call: the rebuilt geometry comes back as EWKB (EWKT for
-- ct_decode_curved) with the SRID inside, instead of WKB plus a second decode for ct_srid. Stored
-- values and their format are unchanged; _ct_decode_wkb and _ct_decode_curved_wkt stay (0.3.0's
-- definitions call them until this update runs).
-- The definitions are those of a fresh 0.4.0 install (regress `upgrade` compares the two).

CREATE FUNCTION "_ct_decode_ewkb"(
	"ct" CircleTree, /* Option < CircleTree > */
	"arc_tolerance" double precision /* Option < f64 > */
) RETURNS bytea /* :: std :: option :: Option < Vec < u8 > > */
IMMUTABLE PARALLEL SAFE
LANGUAGE c /* Rust */
AS 'MODULE_PATHNAME', '_ct_decode_ewkb_wrapper';

CREATE FUNCTION "_ct_decode_curved_ewkt"(
	"ct" CircleTree /* CircleTree */
) RETURNS TEXT /* String */
IMMUTABLE STRICT PARALLEL SAFE
LANGUAGE c /* Rust */
AS 'MODULE_PATHNAME', '_ct_decode_curved_ewkt_wrapper';

CREATE OR REPLACE FUNCTION ct_decode(ct circletree) RETURNS geometry
    LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$ SELECT ST_GeomFromEWKB(_ct_decode_ewkb($1, NULL)) $$;
CREATE OR REPLACE FUNCTION ct_decode(ct circletree, arc_tolerance float8) RETURNS geometry
    LANGUAGE sql IMMUTABLE PARALLEL SAFE
    AS $$ SELECT ST_GeomFromEWKB(_ct_decode_ewkb($1, $2)) $$;
CREATE OR REPLACE FUNCTION ct_decode_curved(ct circletree) RETURNS geometry
    LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$ SELECT ST_GeomFromEWKT(_ct_decode_curved_ewkt($1)) $$;
