-- Using a circletree where it is stored (0.7.0 on; loaded by src/lib.rs with extension_sql_file!,
-- and repeated as it is in sql/circletree--0.6.0--0.7.0.sql): byte order and hashing (btree and
-- hash operator classes), the casts to geometry and geography, the predicates and distances
-- answered from a cached, edge-indexed rebuild (src/access.rs), the && operators, and the native
-- GiST index with the planner support that makes ct_intersects, ct_contains and ct_dwithin use it
-- (src/index.rs). PostGIS's schema is read at install time, as in sql/postgis_wrappers.sql.

-- Byte order: =, DISTINCT, GROUP BY, UNION, ORDER BY, merge and hash joins. No spatial meaning.
CREATE FUNCTION @extschema@.circletree_cmp(a @extschema@.circletree, b @extschema@.circletree) RETURNS int4
    IMMUTABLE STRICT PARALLEL SAFE LANGUAGE c AS 'MODULE_PATHNAME', 'circletree_cmp_wrapper';
CREATE FUNCTION @extschema@.circletree_lt(a @extschema@.circletree, b @extschema@.circletree) RETURNS bool
    IMMUTABLE STRICT PARALLEL SAFE LANGUAGE c AS 'MODULE_PATHNAME', 'circletree_lt_wrapper';
CREATE FUNCTION @extschema@.circletree_le(a @extschema@.circletree, b @extschema@.circletree) RETURNS bool
    IMMUTABLE STRICT PARALLEL SAFE LANGUAGE c AS 'MODULE_PATHNAME', 'circletree_le_wrapper';
CREATE FUNCTION @extschema@.circletree_gt(a @extschema@.circletree, b @extschema@.circletree) RETURNS bool
    IMMUTABLE STRICT PARALLEL SAFE LANGUAGE c AS 'MODULE_PATHNAME', 'circletree_gt_wrapper';
CREATE FUNCTION @extschema@.circletree_ge(a @extschema@.circletree, b @extschema@.circletree) RETURNS bool
    IMMUTABLE STRICT PARALLEL SAFE LANGUAGE c AS 'MODULE_PATHNAME', 'circletree_ge_wrapper';
-- PostgreSQL's own hash of a varlena's bytes (bytea's).
CREATE FUNCTION @extschema@.circletree_hash(ct @extschema@.circletree) RETURNS int4
    IMMUTABLE STRICT PARALLEL SAFE LANGUAGE internal AS 'hashvarlena';
CREATE OPERATOR @extschema@.< (LEFTARG = @extschema@.circletree, RIGHTARG = @extschema@.circletree,
    PROCEDURE = @extschema@.circletree_lt, COMMUTATOR = >, NEGATOR = >=, RESTRICT = scalarltsel, JOIN = scalarltjoinsel);
CREATE OPERATOR @extschema@.<= (LEFTARG = @extschema@.circletree, RIGHTARG = @extschema@.circletree,
    PROCEDURE = @extschema@.circletree_le, COMMUTATOR = >=, NEGATOR = >, RESTRICT = scalarlesel, JOIN = scalarlejoinsel);
CREATE OPERATOR @extschema@.> (LEFTARG = @extschema@.circletree, RIGHTARG = @extschema@.circletree,
    PROCEDURE = @extschema@.circletree_gt, COMMUTATOR = <, NEGATOR = <=, RESTRICT = scalargtsel, JOIN = scalargtjoinsel);
CREATE OPERATOR @extschema@.>= (LEFTARG = @extschema@.circletree, RIGHTARG = @extschema@.circletree,
    PROCEDURE = @extschema@.circletree_ge, COMMUTATOR = <=, NEGATOR = <, RESTRICT = scalargesel, JOIN = scalargejoinsel);
CREATE OPERATOR CLASS @extschema@.circletree_btree_ops DEFAULT FOR TYPE @extschema@.circletree USING btree AS
    OPERATOR 1 @extschema@.<, OPERATOR 2 @extschema@.<=, OPERATOR 3 @extschema@.=,
    OPERATOR 4 @extschema@.>=, OPERATOR 5 @extschema@.>,
    FUNCTION 1 @extschema@.circletree_cmp(@extschema@.circletree, @extschema@.circletree);
CREATE OPERATOR CLASS @extschema@.circletree_hash_ops DEFAULT FOR TYPE @extschema@.circletree USING hash AS
    OPERATOR 1 @extschema@.=,
    FUNCTION 1 @extschema@.circletree_hash(@extschema@.circletree);

-- The GiST support of circletree's own (the key is PostgreSQL's box; union, penalty, split and
-- same are the built-in box ones).
CREATE FUNCTION @extschema@._ct_gist_compress(internal) RETURNS internal
    IMMUTABLE STRICT PARALLEL SAFE LANGUAGE c AS 'MODULE_PATHNAME', '_ct_gist_compress_wrapper';
CREATE FUNCTION @extschema@._ct_gist_consistent(internal, @extschema@.circletree, int2, oid, internal) RETURNS bool
    IMMUTABLE STRICT PARALLEL SAFE LANGUAGE c AS 'MODULE_PATHNAME', '_ct_gist_consistent_wrapper';
CREATE FUNCTION @extschema@._ct_support(internal) RETURNS internal
    IMMUTABLE STRICT PARALLEL SAFE LANGUAGE c AS 'MODULE_PATHNAME', '_ct_support_wrapper';
CREATE FUNCTION @extschema@._ct_overlaps_ct(a @extschema@.circletree, b @extschema@.circletree) RETURNS bool
    IMMUTABLE STRICT PARALLEL SAFE LANGUAGE c AS 'MODULE_PATHNAME', '_ct_overlaps_ct_wrapper';
CREATE OPERATOR @extschema@.&& (LEFTARG = @extschema@.circletree, RIGHTARG = @extschema@.circletree,
    PROCEDURE = @extschema@._ct_overlaps_ct, COMMUTATOR = &&, RESTRICT = areasel, JOIN = areajoinsel);

DO $install$
DECLARE
  pg text := (SELECT n.nspname FROM pg_catalog.pg_extension e
                JOIN pg_catalog.pg_namespace n ON n.oid = e.extnamespace
               WHERE e.extname = 'postgis');
BEGIN
  EXECUTE pg_catalog.format($sql$
-- Casts: circletree::geometry is ct_decode; circletree::geography is ct_decode_geography (to
-- longitude/latitude, EPSG:4326).
CREATE CAST (@extschema@.circletree AS %1$I.geometry) WITH FUNCTION @extschema@.ct_decode(@extschema@.circletree);
CREATE FUNCTION @extschema@._ct_to_geography(ct @extschema@.circletree) RETURNS %1$I.geography
    LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE
    AS $$ SELECT @extschema@.ct_decode_geography($1) $$;
CREATE CAST (@extschema@.circletree AS %1$I.geography) WITH FUNCTION @extschema@._ct_to_geography(@extschema@.circletree);

-- && between a circletree's envelope and a geometry's box (PostGIS's own box for the geometry).
CREATE FUNCTION @extschema@._ct_overlaps(ct @extschema@.circletree, geom %1$I.geometry) RETURNS bool
    IMMUTABLE STRICT PARALLEL SAFE LANGUAGE c AS 'MODULE_PATHNAME', '_ct_overlaps_wrapper';
CREATE FUNCTION @extschema@._ct_overlaps_g(geom %1$I.geometry, ct @extschema@.circletree) RETURNS bool
    IMMUTABLE STRICT PARALLEL SAFE LANGUAGE c AS 'MODULE_PATHNAME', '_ct_overlaps_g_wrapper';
CREATE OPERATOR @extschema@.&& (LEFTARG = @extschema@.circletree, RIGHTARG = %1$I.geometry,
    PROCEDURE = @extschema@._ct_overlaps, COMMUTATOR = &&, RESTRICT = areasel, JOIN = areajoinsel);
CREATE OPERATOR @extschema@.&& (LEFTARG = %1$I.geometry, RIGHTARG = @extschema@.circletree,
    PROCEDURE = @extschema@._ct_overlaps_g, COMMUTATOR = &&, RESTRICT = areasel, JOIN = areajoinsel);

CREATE OPERATOR CLASS @extschema@.circletree_gist_ops DEFAULT FOR TYPE @extschema@.circletree USING gist AS
    STORAGE pg_catalog.box,
    OPERATOR 3 @extschema@.&& (@extschema@.circletree, %1$I.geometry),
    OPERATOR 3 @extschema@.&& (@extschema@.circletree, @extschema@.circletree),
    FUNCTION 1 @extschema@._ct_gist_consistent(internal, @extschema@.circletree, int2, oid, internal),
    FUNCTION 2 pg_catalog.gist_box_union(internal, internal),
    FUNCTION 3 @extschema@._ct_gist_compress(internal),
    FUNCTION 5 pg_catalog.gist_box_penalty(internal, internal, internal),
    FUNCTION 6 pg_catalog.gist_box_picksplit(internal, internal),
    FUNCTION 7 pg_catalog.gist_box_same(pg_catalog.box, pg_catalog.box, internal);

-- The predicates and distances, PostGIS's answers on ct_decode(ct), in both argument orders.
CREATE FUNCTION @extschema@.ct_intersects(ct @extschema@.circletree, geom %1$I.geometry) RETURNS bool
    IMMUTABLE STRICT PARALLEL SAFE COST 1000 SUPPORT @extschema@._ct_support
    LANGUAGE c AS 'MODULE_PATHNAME', '_ct_intersects_wrapper';
CREATE FUNCTION @extschema@.ct_intersects(geom %1$I.geometry, ct @extschema@.circletree) RETURNS bool
    IMMUTABLE STRICT PARALLEL SAFE COST 1000 SUPPORT @extschema@._ct_support
    LANGUAGE c AS 'MODULE_PATHNAME', '_ct_intersects_g_wrapper';
CREATE FUNCTION @extschema@.ct_contains(ct @extschema@.circletree, geom %1$I.geometry) RETURNS bool
    IMMUTABLE STRICT PARALLEL SAFE COST 1000 SUPPORT @extschema@._ct_support
    LANGUAGE c AS 'MODULE_PATHNAME', '_ct_contains_wrapper';
CREATE FUNCTION @extschema@.ct_contains(geom %1$I.geometry, ct @extschema@.circletree) RETURNS bool
    IMMUTABLE STRICT PARALLEL SAFE COST 1000 SUPPORT @extschema@._ct_support
    LANGUAGE c AS 'MODULE_PATHNAME', '_ct_contains_g_wrapper';
CREATE FUNCTION @extschema@.ct_dwithin(ct @extschema@.circletree, geom %1$I.geometry, distance float8) RETURNS bool
    IMMUTABLE STRICT PARALLEL SAFE COST 1000 SUPPORT @extschema@._ct_support
    LANGUAGE c AS 'MODULE_PATHNAME', '_ct_dwithin_wrapper';
CREATE FUNCTION @extschema@.ct_dwithin(geom %1$I.geometry, ct @extschema@.circletree, distance float8) RETURNS bool
    IMMUTABLE STRICT PARALLEL SAFE COST 1000 SUPPORT @extschema@._ct_support
    LANGUAGE c AS 'MODULE_PATHNAME', '_ct_dwithin_g_wrapper';
CREATE FUNCTION @extschema@.ct_distance(ct @extschema@.circletree, geom %1$I.geometry) RETURNS float8
    IMMUTABLE STRICT PARALLEL SAFE COST 1000
    LANGUAGE c AS 'MODULE_PATHNAME', '_ct_distance_wrapper';
CREATE FUNCTION @extschema@.ct_distance(geom %1$I.geometry, ct @extschema@.circletree) RETURNS float8
    IMMUTABLE STRICT PARALLEL SAFE COST 1000
    LANGUAGE c AS 'MODULE_PATHNAME', '_ct_distance_g_wrapper';
$sql$, pg);
END
$install$;
