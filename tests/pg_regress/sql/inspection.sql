-- Inspection functions on a hand-written value and on a real polygon.
CREATE TABLE w AS SELECT 'SRID=0;CIRCLETREE(grid=0.01;min_radius=1;overlap=0;dp_tolerance=2.5;max_error=2.5;vertices=12;wkb_bytes=200;repaired=1;bbox=(-1.5 0,3 4.25);MULTIPOLYGON(((0 0 0,3 0 0,3 4.25 -0.5)),((-1.5 1 0,-1 1 0,-1 2 1.25),(1 1 0,1.5 1 0,1 1.5 0))))'::circletree AS ct;
SELECT * FROM ct_circles((SELECT ct FROM w));
SELECT ct_ncircles(ct), ct_srid(ct), ct_memsize(ct), pg_column_size(ct) FROM w;
SELECT jsonb_pretty(ct_summary(ct)) FROM w;
-- on Kapiti Island (LINZ 1:50k, 2029 vertices): circles of all three kinds, far fewer than vertices
CREATE TABLE k AS SELECT geom, ct_encode(geom, 5, 0.4, 10) AS ct FROM coast WHERE name = 'kapiti_island_linz';
SELECT ct_srid(ct) = ST_SRID(geom) AS same_srid, ct_ncircles(ct) < ST_NPoints(geom) / 2 AS fewer_circles,
       ct_memsize(ct) = octet_length(ct::bytea) + 4 AS memsize_is_varlena
  FROM k;
SELECT (s->>'internal')::int > 50 AS internal, (s->>'external')::int > 50 AS external, (s->>'zero')::int > 0 AS zero,
       (s->>'circles')::int = (s->>'internal')::int + (s->>'external')::int + (s->>'zero')::int AS kinds_add_up,
       s->>'original_vertices' AS vertices, s->>'original_wkb_bytes' AS wkb_bytes, s->'params' AS params, s->>'grid' AS grid
  FROM k, LATERAL ct_summary(ct) s;
SELECT count(*) = ct_ncircles((SELECT ct FROM k)) AS rows_match, min(seq) AS first_seq, bool_and(part = 1 AND ring = 1) AS one_ring
  FROM ct_circles((SELECT ct FROM k));
-- NULL in, NULL out
SELECT ct_ncircles(NULL), ct_srid(NULL), ct_summary(NULL) IS NULL AS summary_null, count(*) FROM ct_circles(NULL);
-- every function, the type and the operators of the extension are documented in the catalog
-- (\df+ ct_* and \dT+ circletree explain themselves)
SELECT count(*) AS undocumented
  FROM pg_depend d
 WHERE d.refobjid = (SELECT oid FROM pg_extension WHERE extname = 'circletree') AND d.deptype = 'e'
   AND d.classid IN ('pg_proc'::regclass, 'pg_type'::regclass, 'pg_operator'::regclass)
   AND obj_description(d.objid, d.classid::regclass::name) IS NULL
   AND NOT (d.classid = 'pg_type'::regclass AND d.objid = (SELECT typarray FROM pg_type WHERE typname = 'circletree'));
SELECT obj_description('ct_encode_within(geometry, float8)'::regprocedure, 'pg_proc') AS ct_encode_within;
