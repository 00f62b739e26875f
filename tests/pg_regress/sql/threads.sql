-- circletree.encode_threads (issue 11): on a geometry of at least 5,000 vertices an encode may run
-- independent steps on a second thread. The stored bytes must not depend on it: every polygon of
-- the public set encoded with 1 and with 2 threads, by both encoders, at two bounds.
SELECT ct_srid(ct_encode('POLYGON((0 0,10 0,10 10,0 0))'::geometry, 1, 0.4, 1)) AS loads_the_library;
SHOW circletree.encode_threads;
SET circletree.encode_threads = 1;
CREATE TEMP TABLE one AS
SELECT name, t, ct_encode_within(geom, t)::bytea AS within, ct_encode(geom, t / 2, 0.4, t)::bytea AS paper
  FROM coast, (VALUES (10.0), (100.0)) b(t);
SET circletree.encode_threads = 2;
CREATE TEMP TABLE two AS
SELECT name, t, ct_encode_within(geom, t)::bytea AS within, ct_encode(geom, t / 2, 0.4, t)::bytea AS paper
  FROM coast, (VALUES (10.0), (100.0)) b(t);
SELECT count(*) AS pairs,
       count(*) FILTER (WHERE one.within = two.within) AS within_same,
       count(*) FILTER (WHERE one.paper = two.paper) AS paper_same,
       count(*) FILTER (WHERE c.npoints >= 5000) AS large_enough_for_a_thread
  FROM one JOIN two USING (name, t) JOIN coast c USING (name);
-- only 1 or 2
SELECT outcome('SET circletree.encode_threads = 0') AS zero, outcome('SET circletree.encode_threads = 3') AS three;
RESET circletree.encode_threads;
SHOW circletree.encode_threads;
