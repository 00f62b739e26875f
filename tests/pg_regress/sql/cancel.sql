-- Faults (issue 9 item 4): statement_timeout stops a long encode, sweep and each metric (57014,
-- "canceling statement"), and the backend is usable after. The input is a star-shaped ring of a
-- million vertices (valid by construction), on which each call takes seconds uncancelled; the time
-- each takes to stop is in docs/RELIABILITY.md (about 0.1 s past the timeout for ct_encode_within
-- and ct_hausdorff, 0.5 s for ct_sliver_error, 1.7 s for ct_encode, whose Delaunay triangulation
-- of a ring cannot be interrupted).
CREATE TEMP TABLE star AS
SELECT ST_MakePolygon(ST_MakeLine(array_agg(ST_MakePoint(r * cos(t), r * sin(t)) ORDER BY i) || ST_MakePoint(100000, 0))) AS geom
  FROM (SELECT i, 2 * pi() * i / 1000000 AS t,
               100000 + 1000 * sin(37 * 2 * pi() * i / 1000000) + 300 * sin(1013 * 2 * pi() * i / 1000000)
                 + 30 * sin(20011 * 2 * pi() * i / 1000000) AS r
          FROM generate_series(0, 999999) i) s;
SELECT ST_NPoints(geom), ST_IsValid(geom) FROM star;
CREATE TEMP TABLE small AS SELECT ct_encode_within(ST_Buffer('POINT(0 0)'::geometry, 100000, 64), 50) AS ct;
\set VERBOSITY terse
-- The encoders and the sweep run PostGIS's ST_IsValid (about 0.2 s on this ring; the encoders
-- beside their own work): a timeout well past it, so that it is circletree's own loop that is
-- cancelled, not GEOS (regress host_check cancels during the check).
SET statement_timeout = '1500ms';
SELECT ct_encode_within(geom, 50) IS NULL FROM star;
SELECT 1 AS usable;
SELECT ct_encode(geom, 25, 0.4, 50) IS NULL FROM star;
SELECT 1 AS usable;
SELECT count(*) FROM star, ct_sweep(geom, ARRAY[25], ARRAY[0.4], ARRAY[50]);
SELECT 1 AS usable;
SET statement_timeout = '200ms';
SELECT ct_hausdorff(ct, geom) FROM small, star;
SELECT ct_hausdorff(geom, geom) FROM star;
SELECT ct_sliver_error(ct, geom) FROM small, star;
SELECT 1 AS usable;
RESET statement_timeout;
\set VERBOSITY default
SELECT ct_hausdorff(ct, ct_decode(ct)) < 1e-6 AS still_works FROM small;
