-- ct_encode_within(geom, t): the fewest bytes whose ct_decode is valid and within t, against what
-- PostGIS users do today at the same t: ST_AsTWKB(ST_Simplify(geom, t, true), ceil(-log(t / 10)))
-- (issue 13's comparison). Every polygon of the corpus at t = 10, 25 and 100 m.
CREATE TABLE within_enc AS
SELECT c.name, t, c.geom, ct_encode_within(c.geom, t) AS ct,
       ST_AsTWKB(ST_Simplify(c.geom, t, true), ceil(-log(t / 10))::int) AS twkb
  FROM coast c, (VALUES (10.0::float8), (25), (100)) v(t);
-- valid, same SRID and parts, within t (continuous Hausdorff), and the stored form
SELECT t, count(*) AS polygons,
       count(*) FILTER (WHERE ST_IsValid(ct_decode(ct))) AS valid,
       count(*) FILTER (WHERE ST_SRID(ct_decode(ct)) = ST_SRID(geom)) AS same_srid,
       count(*) FILTER (WHERE ST_NumGeometries(ct_decode(ct)) = ST_NumGeometries(geom)) AS same_parts,
       count(*) FILTER (WHERE ct_hausdorff(ct, geom) <= t) AS within_t,
       count(*) FILTER (WHERE ct_summary(ct)->>'format_version' = '2') AS format_v2,
       count(*) FILTER (WHERE (ct_summary(ct)->'params'->>'max_error')::float8 = t) AS bound_recorded,
       count(*) FILTER (WHERE (ct_summary(ct)->>'internal')::int + (ct_summary(ct)->>'external')::int = 0) AS points_only
  FROM within_enc GROUP BY t ORDER BY t;
-- Issue 13's target: at most 0.8x the bytes of DP + TWKB, summed over the set (the ratio is shown
-- to two decimals, so a change of the encoder shows here)
SELECT t, sum(ct_memsize(ct)) <= 0.8 * sum(octet_length(twkb)) AS at_most_0_8_of_twkb,
       round(sum(ct_memsize(ct))::numeric / sum(octet_length(twkb)), 2) AS ratio
  FROM within_enc GROUP BY t ORDER BY t;
-- never larger than ct_encode at the same bound (t/2, 0.4, t), summed
SELECT t, sum(ct_memsize(ct)) < sum(ct_memsize(ct_encode(geom, t / 2, 0.4, t))) AS smaller_than_ct_encode
  FROM within_enc GROUP BY t ORDER BY t;
-- NULLs give NULL; parameters are checked like ct_encode's (22023, naming max_error)
SELECT ct_encode_within(NULL, 10) IS NULL AS null_geom, ct_encode_within(geom, NULL) IS NULL AS null_bound
  FROM coast WHERE name = 'lake_tahoe';
SELECT sqlstate_of('SELECT ct_encode_within(''POLYGON((0 0,10 0,10 10,0 10,0 0))'', 0)');
SELECT sqlstate_of('SELECT ct_encode_within(''POLYGON((0 0,10 0,10 10,0 10,0 0))'', -1)');
SELECT sqlstate_of('SELECT ct_encode_within(''POLYGON((0 0,10 0,10 10,0 10,0 0))'', ''NaN'')');
SELECT sqlstate_of('SELECT ct_encode_within(''POLYGON((0 0,10 0,10 10,0 10,0 0))'', 1e-12)');
SELECT sqlstate_of('SELECT ct_encode_within(''POINT(0 0)'', 1)');
SELECT sqlstate_of('SELECT ct_encode_within(''POLYGON((0 0,10 10,10 0,0 10,0 0))'', 1)');
-- a polygon far from the origin with a tiny bound: refused up front, naming max_error
SELECT sqlstate_of('SELECT ct_encode_within(''POLYGON((1e12 1e12,1.000001e12 1e12,1.000001e12 1.000001e12,1e12 1e12))'', 1e-3)');
-- touching parts (issue 8) encode and stay valid
SELECT ST_IsValid(ct_decode(ct_encode_within(g, 1))) AS valid, ST_NumGeometries(ct_decode(ct_encode_within(g, 1))) AS parts
  FROM (SELECT 'MULTIPOLYGON(((0 0,10 0,10 10,0 10,0 0)),((10 10,20 10,20 20,10 20,10 10)))'::geometry g) s;
