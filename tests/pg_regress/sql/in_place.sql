-- Using a value where it is stored (0.7.0): the predicates and distances give PostGIS's answers on
-- ct_decode(ct) for every pair, boundary points included; the native GiST index, equality and
-- the casts.
CREATE TABLE ip AS SELECT name, ct_encode_within(geom, 10) AS ct FROM coast;
CREATE TABLE ipd AS SELECT name, ct, ct_decode(ct) AS g FROM ip;
-- points: 40 pseudo-random ones in each envelope, and about 100 vertices of each rebuilt polygon
-- (every vertex of the small ones), the midpoints of their edges and points 1 m beside them
SELECT setseed(0.25);
CREATE TABLE env AS SELECT name, ST_SRID(g) AS srid, ST_XMin(g) AS x0, ST_XMax(g) AS x1, ST_YMin(g) AS y0, ST_YMax(g) AS y1,
       ST_NPoints(g) AS n FROM ipd;
CREATE TABLE vtx AS
SELECT i.name, d.path, d.geom, lead(d.geom) OVER (PARTITION BY i.name, d.path[1:array_upper(d.path, 1) - 1] ORDER BY d.path) AS next
  FROM ipd i JOIN env e USING (name), LATERAL ST_DumpPoints(i.g) d
 WHERE d.path[array_upper(d.path, 1)] % greatest(1, e.n / 100) IN (0, 1);
CREATE TABLE pts AS
SELECT name, ST_SetSRID(ST_MakePoint(x0 + random() * (x1 - x0), y0 + random() * (y1 - y0)), srid) AS pt, 'random' AS kind
  FROM env, generate_series(1, 40)
UNION ALL
SELECT name, geom, 'vertex' FROM vtx v JOIN env e USING (name) WHERE path[array_upper(path, 1)] % greatest(1, e.n / 100) = 0
UNION ALL
SELECT name, ST_LineInterpolatePoint(ST_MakeLine(geom, next), 0.5), 'midpoint' FROM vtx v JOIN env e USING (name)
 WHERE next IS NOT NULL AND path[array_upper(path, 1)] % greatest(1, e.n / 100) = 0
UNION ALL
SELECT name, ST_Translate(geom, 1, 0.5), 'beside' FROM vtx v JOIN env e USING (name)
 WHERE path[array_upper(path, 1)] % greatest(1, e.n / 100) = 1;
SELECT kind, count(*) > 1000 AS many FROM pts GROUP BY kind ORDER BY kind;
-- every point against its own polygon, answers compared with PostGIS's on the rebuilt polygon
CREATE VIEW pairs AS SELECT p.kind, d.ct, d.g, p.pt FROM pts p JOIN ipd d USING (name);
SELECT kind, count(*) AS pairs,
       count(*) FILTER (WHERE ct_intersects(ct, pt) IS DISTINCT FROM ST_Intersects(g, pt)) AS intersects_differ,
       count(*) FILTER (WHERE ct_intersects(pt, ct) IS DISTINCT FROM ST_Intersects(pt, g)) AS commuted_differ,
       count(*) FILTER (WHERE ct_contains(ct, pt) IS DISTINCT FROM ST_Contains(g, pt)) AS contains_differ,
       count(*) FILTER (WHERE ct_contains(pt, ct) IS DISTINCT FROM ST_Contains(pt, g)) AS contained_differ,
       count(*) FILTER (WHERE ct_dwithin(ct, pt, 10) IS DISTINCT FROM ST_DWithin(g, pt, 10)
                           OR ct_dwithin(pt, ct, 500) IS DISTINCT FROM ST_DWithin(pt, g, 500)) AS dwithin_differ,
       count(*) FILTER (WHERE ct_distance(ct, pt) IS DISTINCT FROM ST_Distance(g, pt)
                           OR ct_distance(pt, ct) IS DISTINCT FROM ST_Distance(pt, g)) AS distance_differ,
       count(*) FILTER (WHERE ST_Intersects(g, pt) AND NOT ST_Contains(g, pt)) > 0 AS some_on_the_boundary
  FROM pairs GROUP BY kind ORDER BY kind;
-- points on the boundary, exactly: every vertex is on it, as PostGIS says
SELECT count(*) AS vertices, count(*) FILTER (WHERE ct_intersects(ct, pt) AND NOT ct_contains(ct, pt)) AS on_boundary
  FROM pairs WHERE kind = 'vertex';
-- windows of 2 km and lines (ct_intersects answered by circletree; the others by PostGIS's own
-- function on the rebuilt polygon)
CREATE TABLE wins AS
SELECT name, ST_Expand(pt, 1000) AS w, ST_MakeLine(pt, ST_Translate(pt, 3000, 1000)) AS l
  FROM (SELECT name, pt, row_number() OVER (PARTITION BY name) AS k FROM pts WHERE kind = 'random') s WHERE k <= 8;
SELECT count(*) AS windows,
       count(*) FILTER (WHERE ct_intersects(d.ct, w.w) IS DISTINCT FROM ST_Intersects(d.g, w.w)
                           OR ct_intersects(w.l, d.ct) IS DISTINCT FROM ST_Intersects(w.l, d.g)) AS intersects_differ,
       count(*) FILTER (WHERE ct_contains(d.ct, w.w) IS DISTINCT FROM ST_Contains(d.g, w.w)
                           OR ct_contains(w.w, d.ct) IS DISTINCT FROM ST_Contains(w.w, d.g)) AS contains_differ,
       count(*) FILTER (WHERE ct_dwithin(d.ct, w.l, 100) IS DISTINCT FROM ST_DWithin(d.g, w.l, 100)
                           OR ct_distance(w.w, d.ct) IS DISTINCT FROM ST_Distance(w.w, d.g)) AS distance_differ,
       count(*) FILTER (WHERE ct_intersects(d.ct, w.w)) > 0 AND count(*) FILTER (WHERE NOT ct_intersects(d.ct, w.w)) > 0 AS both_answers
  FROM wins w JOIN ipd d USING (name);
-- lines and polygons touching the rebuilt rings exactly (circletree answers ct_intersects with
-- exact predicates): windows with a corner on a vertex, the edges themselves, triangles on an
-- edge, lines from an edge's midpoint, two windows as one MultiPolygon, lines as a MultiLineString
CREATE TABLE touch AS
SELECT v.name, s.kind, s.g
  FROM vtx v JOIN env e USING (name),
       LATERAL (VALUES
         ('corner', ST_MakeEnvelope(ST_X(v.geom), ST_Y(v.geom), ST_X(v.geom) + 500, ST_Y(v.geom) + 500, e.srid)),
         ('corner', ST_MakeEnvelope(ST_X(v.geom) - 300, ST_Y(v.geom) - 300, ST_X(v.geom), ST_Y(v.geom), e.srid)),
         ('edge', ST_MakeLine(v.geom, v.next)),
         ('triangle', ST_MakePolygon(ST_MakeLine(ARRAY[v.geom, v.next, ST_Translate(v.geom, 200, 300), v.geom]))),
         ('midpoint', ST_MakeLine(ST_LineInterpolatePoint(ST_MakeLine(v.geom, v.next), 0.5), ST_Translate(v.geom, 0, 700))),
         ('multi', ST_Collect(ST_Expand(ST_Translate(v.geom, 2000, 0), 100), ST_Expand(v.next, 1e-3))),
         ('multi', ST_Collect(ST_MakeLine(ST_Translate(v.geom, 5, 5), ST_Translate(v.geom, 50, 5)), ST_MakeLine(v.geom, ST_Translate(v.next, 0, 1))))) s(kind, g)
 WHERE v.next IS NOT NULL AND v.path[array_upper(v.path, 1)] % greatest(1, e.n / 20) = 0;
SELECT kind, count(*) AS pairs,
       count(*) FILTER (WHERE ct_intersects(d.ct, t.g) IS DISTINCT FROM ST_Intersects(d.g, t.g)
                           OR ct_intersects(t.g, d.ct) IS DISTINCT FROM ST_Intersects(t.g, d.g)) AS intersects_differ,
       count(*) FILTER (WHERE ct_intersects(d.ct, ST_Force3D(t.g)) IS DISTINCT FROM ST_Intersects(d.g, t.g)) AS with_z_differ,
       count(*) FILTER (WHERE ST_Intersects(d.g, t.g)) > 0 AS some_meet
  FROM touch t JOIN ipd d USING (name) GROUP BY kind ORDER BY kind;
-- a point in a hole, in a second part, on a hole's ring; NULL and empty values as PostGIS
CREATE TABLE holed AS SELECT ct_encode_within('MULTIPOLYGON(((0 0,10 0,10 10,0 10,0 0),(2 2,2 8,8 8,8 2,2 2)),((20 0,30 0,30 10,20 10,20 0)))', 0.001) AS ct;
SELECT p, ct_intersects(ct, p::geometry) AS intersects, ct_contains(ct, p::geometry) AS contains,
       ct_distance(ct, p::geometry) AS distance,
       ct_intersects(ct, p::geometry) = ST_Intersects(ct_decode(ct), p::geometry)
       AND ct_contains(ct, p::geometry) = ST_Contains(ct_decode(ct), p::geometry)
       AND ct_distance(ct, p::geometry) = ST_Distance(ct_decode(ct), p::geometry) AS as_postgis
  FROM holed, unnest(ARRAY['POINT(1 1)', 'POINT(5 5)', 'POINT(2 5)', 'POINT(25 5)', 'POINT(15 5)', 'POINT(0 0)', 'POINT(10 12)']) p;
SELECT g, ct_intersects(ct, g::geometry) AS intersects, ct_intersects(ct, g::geometry) = ST_Intersects(ct_decode(ct), g::geometry) AS as_postgis
  FROM holed, unnest(ARRAY['POLYGON((4 4,6 4,6 6,4 6,4 4))', 'POLYGON((1 1,9 1,9 9,1 9,1 1))', 'POLYGON((-1 -1,31 -1,31 11,-1 11,-1 -1),(-0.5 -0.5,30.5 -0.5,30.5 10.5,-0.5 10.5,-0.5 -0.5))',
                           'LINESTRING(3 3,7 7)', 'LINESTRING(12 5,18 5)', 'LINESTRING(10 5,20 5)', 'MULTILINESTRING((12 5,18 5),(3 3,2 5))',
                           'POLYGON EMPTY', 'LINESTRING EMPTY', 'MULTIPOLYGON(((4 4,6 4,6 6,4 6,4 4)),((24 4,26 4,26 6,24 6,24 4)))']) g;
SELECT ct_intersects(NULL::circletree, 'POINT(1 1)'::geometry) IS NULL AS null_ct,
       ct_intersects(ct, NULL::geometry) IS NULL AS null_geom,
       ct_intersects(ct, 'POINT EMPTY'::geometry) = ST_Intersects(ct_decode(ct), 'POINT EMPTY'::geometry) AS empty_point,
       ct_distance(ct, 'POINT EMPTY'::geometry) IS NULL AND ST_Distance(ct_decode(ct), 'POINT EMPTY'::geometry) IS NULL AS empty_distance
  FROM holed;
SELECT ct_intersects(e, 'POINT(1 1)'::geometry) AS intersects, ct_contains(e, 'POINT(1 1)'::geometry) AS contains,
       ct_dwithin(e, 'POINT(1 1)'::geometry, 1e9) AS dwithin, ct_distance(e, 'POINT(1 1)'::geometry) AS distance,
       ST_Intersects(ct_decode(e), 'POINT(1 1)'::geometry) AS postgis_intersects,
       ST_Distance(ct_decode(e), 'POINT(1 1)'::geometry) AS postgis_distance
  FROM (SELECT ct_encode_within('POLYGON EMPTY', 1) AS e) s;
-- mixed SRIDs and a negative distance: PostGIS's messages, as 22023 with a hint
SELECT outcome($$SELECT ct_intersects(ct, 'SRID=4326;POINT(1 1)'::geometry) FROM holed$$);
SELECT outcome($$SELECT ct_distance('SRID=4326;LINESTRING(1 1,2 2)'::geometry, ct) FROM holed$$);
SELECT outcome($$SELECT ct_dwithin(ct, 'POINT(1 1)'::geometry, -1) FROM holed$$);
-- the native index: ct_intersects and ct_dwithin use it with no && written, and find the rows a
-- sequential scan finds
-- (one SRID a pair: && compares boxes whatever their SRID, and PostGIS refuses mixed SRIDs)
ALTER TABLE ip ADD COLUMN srid int;
UPDATE ip SET srid = ct_srid(ct);
CREATE INDEX ip_ct ON ip USING gist (ct);
ANALYZE ip;
CREATE TABLE probe AS SELECT pt, ST_SRID(pt) AS srid FROM pts WHERE kind = 'random';
SET enable_seqscan = off;
EXPLAIN (COSTS OFF) SELECT count(*) FROM probe p JOIN ip ON ip.srid = p.srid AND ct_intersects(ip.ct, p.pt);
EXPLAIN (COSTS OFF) SELECT count(*) FROM probe p JOIN ip ON ip.srid = p.srid AND ct_dwithin(p.pt, ip.ct, 500);
CREATE TABLE by_index AS
SELECT (SELECT count(*) FROM probe p JOIN ip ON ip.srid = p.srid AND ct_intersects(ip.ct, p.pt)) AS intersects,
       (SELECT count(*) FROM probe p JOIN ip ON ip.srid = p.srid AND ct_dwithin(p.pt, ip.ct, 500)) AS dwithin,
       (SELECT count(*) FROM probe p JOIN ip ON ip.srid = p.srid AND ct_contains(ip.ct, ST_Expand(p.pt, 100))) AS contains,
       (SELECT count(*) FROM probe p JOIN ip ON ip.ct && p.pt) AS overlaps;
RESET enable_seqscan;
SET enable_indexscan = off;
SET enable_bitmapscan = off;
SELECT b.intersects = s.intersects AND b.dwithin = s.dwithin AND b.contains = s.contains AND b.overlaps = s.overlaps AS index_rows_equal_seqscan_rows,
       s.intersects = (SELECT count(*) FROM probe p JOIN ipd d ON ST_SRID(d.g) = p.srid AND d.g && p.pt AND ST_Intersects(d.g, p.pt)) AS as_postgis,
       s.intersects > 0 AND s.dwithin > s.intersects AS not_trivial
  FROM by_index b,
       (SELECT (SELECT count(*) FROM probe p JOIN ip ON ip.srid = p.srid AND ct_intersects(ip.ct, p.pt)) AS intersects,
               (SELECT count(*) FROM probe p JOIN ip ON ip.srid = p.srid AND ct_dwithin(p.pt, ip.ct, 500)) AS dwithin,
               (SELECT count(*) FROM probe p JOIN ip ON ip.srid = p.srid AND ip.ct && ST_Expand(p.pt, 100)
                                                  AND ct_contains(ip.ct, ST_Expand(p.pt, 100))) AS contains,
               (SELECT count(*) FROM probe p JOIN ip ON ip.ct && p.pt) AS overlaps) s;
RESET enable_indexscan;
RESET enable_bitmapscan;
-- && is the envelope's: the same rows as ct_envelope(ct) && geom, from either side
SELECT count(*) FILTER (WHERE (ip.ct && p.pt) IS DISTINCT FROM (ct_envelope(ip.ct) && p.pt)) AS differ,
       count(*) FILTER (WHERE (p.pt && ip.ct) IS DISTINCT FROM (ip.ct && p.pt)) AS commuted_differ,
       count(*) FILTER (WHERE ip.ct && p.pt) > 0 AS some
  FROM probe p, ip;
-- boxes are compared as PostGIS compares them, rounded outwards to floats: a point a millimetre
-- beyond the envelope at 500 km is within its float box (1/32 m there), 10 cm beyond is not
SELECT d AS beyond, ct && p AS overlaps, ct_envelope(ct) && p AS postgis, p && ct AS commuted
  FROM (SELECT ct_encode_within('SRID=32633;POLYGON((500000 6000000,500100 6000000,500100 6000100,500000 6000000))'::geometry, 1) AS ct) v,
       LATERAL (SELECT d, ST_SetSRID(ST_MakePoint(ST_XMax(ct_envelope(ct)) + d, 6000050), 32633) AS p FROM unnest(ARRAY[0, 0.001, 0.01, 0.1]) d) s;
-- equality the planner can use: DISTINCT, GROUP BY, UNION, a hash join, a hash index look-up
-- (byte order and PostgreSQL's hash of the bytes; a btree index, like bytea's, takes only values
-- under about 2.7 kB)
INSERT INTO ip SELECT name || ' again', ct, srid FROM ip WHERE name IN (SELECT name FROM ip ORDER BY name LIMIT 3);
SELECT count(*) AS rows, count(DISTINCT ct) AS distinct_values,
       (SELECT count(*) FROM (SELECT ct FROM ip GROUP BY ct) g) AS groups,
       (SELECT count(*) FROM (SELECT ct FROM ip UNION SELECT ct FROM ip) u) AS union_rows
  FROM ip;
SET enable_mergejoin = off;
SET enable_nestloop = off;
EXPLAIN (COSTS OFF) SELECT count(*) FROM ip a JOIN ip b ON a.ct = b.ct;
SELECT count(*) AS hash_join_pairs FROM ip a JOIN ip b ON a.ct = b.ct;
RESET enable_mergejoin;
RESET enable_nestloop;
CREATE INDEX ip_bytes ON ip USING hash (ct);
SET enable_seqscan = off;
EXPLAIN (COSTS OFF) SELECT count(*) FROM ip WHERE ct = (SELECT ct FROM ip ORDER BY name LIMIT 1);
SELECT count(*) AS found_by_hash_index FROM ip WHERE ct = (SELECT ct FROM ip ORDER BY name LIMIT 1);
RESET enable_seqscan;
SELECT count(*) FILTER (WHERE a.ct < b.ct) + count(*) FILTER (WHERE a.ct > b.ct) + count(*) FILTER (WHERE a.ct = b.ct) = count(*) AS total_order,
       count(*) FILTER (WHERE (a.ct <= b.ct) <> (circletree_cmp(a.ct, b.ct) <= 0)) AS cmp_differs
  FROM ip a, ip b;
-- the casts: ::geometry is ct_decode, ::geography is ct_decode_geography
SELECT count(*) FILTER (WHERE ST_AsEWKB(ct::geometry) = ST_AsEWKB(ct_decode(ct))) AS cast_is_decode,
       count(*) FILTER (WHERE ST_Area(ct::geometry) > 0) AS in_postgis_functions,
       count(*) FILTER (WHERE ST_AsEWKB((ct::geography)::geometry) = ST_AsEWKB(ct_decode_geography(ct)::geometry)) AS geography_cast,
       count(*) AS polygons
  FROM ip;
DROP VIEW pairs;
DROP TABLE ip, ipd, env, vtx, pts, wins, touch, holed, probe, by_index;
