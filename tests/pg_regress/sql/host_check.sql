-- The encoders ask PostGIS's ST_IsValid themselves (release 0.6.0): ct_encode and ct_encode_within
-- pass the geometry and the two PostGIS functions to _ct_encode_geom / _ct_encode_within_geom, which
-- call them on the backend's thread, beside the encoder's own work on an input of at least 5,000
-- vertices (before it on a smaller one). What is stored and what is refused are as if PostGIS had
-- checked first.
--
-- 1. The same bytes as 0.5.0's path (PostGIS's verdict computed first, in SQL) on every public
--    polygon, both encoders; 14 of them are large enough for the check to run beside the encoder.
SELECT count(*) AS polygons, count(*) FILTER (WHERE npoints >= 5000) AS checked_beside,
       count(*) FILTER (WHERE ct_encode_within(geom, 10)::bytea
                              = _ct_encode_within_wkb(ST_AsBinary(geom), ST_SRID(geom), _ct_invalid_reason(geom), 10)::bytea) AS same_within,
       count(*) FILTER (WHERE ct_encode(geom, 5, 0.4, 10)::bytea
                              = _ct_encode_wkb(ST_AsBinary(geom), ST_SRID(geom), _ct_invalid_reason(geom), 5, 0.4, 10, NULL)::bytea) AS same_encode
  FROM coast;
-- 2. Invalid inputs, small and large (a large one is refused while the encoder is stopped), with
--    M values too (0.5.0 did not ask PostGIS about a POLYGONM: GeometryType names it so).
CREATE TEMP TABLE bad(name text, geom geometry);
INSERT INTO bad VALUES
 ('bow-tie', 'POLYGON((0 0,10 10,10 0,0 10,0 0))'),
 ('bow-tie, M', 'POLYGONM((0 0 1,10 10 1,10 0 1,0 10 1,0 0 1))'),
 ('hole outside the shell, ZM', 'POLYGON ZM((0 0 1 1,10 0 1 1,10 10 1 1,0 10 1 1,0 0 1 1),(20 20 1 1,30 20 1 1,30 30 1 1,20 20 1 1))'),
 ('overlapping parts, M', 'MULTIPOLYGONM(((0 0 1,10 0 1,10 10 1,0 10 1,0 0 1)),((5 5 1,15 5 1,15 15 1,5 15 1,5 5 1)))'),
 ('bow-tie, segmentized', ST_Segmentize('POLYGON((0 0,1000 1000,1000 0,0 1000,0 0))'::geometry, 0.5)),
 ('star with a hole outside', ST_MakePolygon(
    (SELECT ST_MakeLine(array_agg(ST_MakePoint((1000 + 10 * sin(37 * t)) * cos(t), (1000 + 10 * sin(37 * t)) * sin(t)) ORDER BY i)
                        || ST_MakePoint(1000, 0))
       FROM (SELECT i, 2 * pi() * i / 100000 AS t FROM generate_series(0, 99999) i) s),
    ARRAY['LINESTRING(5000 5000,5100 5000,5100 5100,5000 5000)'::geometry]));
SELECT name, ST_NPoints(geom) AS npoints,
       outcome(format('SELECT ct_encode_within(%L::geometry, 1)', geom::text)) AS ct_encode_within,
       outcome(format('SELECT ct_encode(%L::geometry, 1, 0.4, 1)', geom::text)) AS ct_encode
  FROM bad ORDER BY npoints, name;
SELECT name, outcome(format('SELECT ct_sliver_error(%L::circletree, %L::geometry)', ct::text, geom::text)) AS ct_sliver_error
  FROM bad, (SELECT ct_encode('POLYGON((0 0,100 0,100 100,0 100,0 0))'::geometry, 5, 0.4, 10) AS ct) good
 WHERE ST_NPoints(geom) < 100 ORDER BY name;
-- 3. A direct call runs only functions of one geometry returning what PostGIS's return (so nothing
--    a caller could not run in SQL on the same geometry), that the caller may execute.
SELECT outcome($$SELECT _ct_encode_within_geom('POLYGON((0 0,10 0,10 10,0 0))'::geometry, '\x00'::bytea, 0,
                 'pg_sleep(float8)', 'st_isvalidreason(geometry)', 1)$$) AS not_of_a_geometry;
SELECT outcome($$SELECT _ct_encode_geom('POLYGON((0 0,10 0,10 10,0 0))'::geometry, '\x00'::bytea, 0,
                 'st_isvalid(geometry)', 'st_area(geometry)', 5, 0.4, 10, NULL)$$) AS not_text;
SELECT outcome($$SELECT _ct_encode_geom('POLYGON((0 0,10 0,10 10,0 0))'::geometry, '\x00'::bytea, 0,
                 'st_dump(geometry)', 'st_isvalidreason(geometry)', 5, 0.4, 10, NULL)$$) AS a_set;
CREATE FUNCTION private_check(geometry) RETURNS bool LANGUAGE sql AS 'SELECT true';
REVOKE EXECUTE ON FUNCTION private_check(geometry) FROM PUBLIC;
SET client_min_messages = warning;
DROP ROLE IF EXISTS circletree_checker;  -- left by an interrupted run (roles outlive the database)
RESET client_min_messages;
CREATE ROLE circletree_checker NOLOGIN NOSUPERUSER;
SET ROLE circletree_checker;
SELECT outcome($$SELECT _ct_encode_within_geom('POLYGON((0 0,10 0,10 10,0 0))'::geometry,
                 ST_AsBinary('POLYGON((0 0,10 0,10 10,0 0))'::geometry), 0,
                 'private_check(geometry)', 'st_isvalidreason(geometry)', 1)$$) AS not_executable;
SELECT length(ct_encode_within('POLYGON((0 0,10 0,10 10,0 0))'::geometry, 1)::bytea) > 0 AS the_wrapper_works;
RESET ROLE;
DROP ROLE circletree_checker;
DROP FUNCTION private_check(geometry);
-- 4. A cancel while PostGIS checks a large input stops the encoder beside it, and the backend is
--    usable after (ST_IsValid of this ring of a million vertices takes about 0.2 s). Its first point
--    is given twice, so that the core's own proof (section 5) leaves it to PostGIS.
CREATE TEMP TABLE star AS
SELECT ST_MakePolygon(ST_MakeLine(ST_MakePoint(100000, 0) || array_agg(ST_MakePoint(r * cos(t), r * sin(t)) ORDER BY i) || ST_MakePoint(100000, 0))) AS geom
  FROM (SELECT i, 2 * pi() * i / 1000000 AS t,
               100000 + 1000 * sin(37 * 2 * pi() * i / 1000000) + 300 * sin(1013 * 2 * pi() * i / 1000000) AS r
          FROM generate_series(0, 999999) i) s;
\set VERBOSITY terse
SET statement_timeout = '50ms';
SELECT ct_encode_within(geom, 50) IS NULL FROM star;
SELECT ct_encode(geom, 25, 0.4, 50) IS NULL FROM star;
-- A cancel that reaches GEOS makes PostGIS raise "GEOS isvalid() threw an error!" (XX000: so does
-- SELECT ST_IsValid(geom) under the same timeout); the encoders raise the pending cancel instead
-- (57014). Newfoundland is proved valid by the core (about 5 ms), so the cancel comes from the
-- encoder.
SET statement_timeout = '10ms';
SELECT ct_encode_within(geom, 10) IS NULL FROM coast WHERE name = 'newfoundland';
SELECT ct_encode(geom, 5, 0.4, 10) IS NULL FROM coast WHERE name = 'newfoundland';
RESET statement_timeout;
SELECT 1 AS usable;
-- 5. The core's own proof of validity spares PostGIS's check only where it proves the
--    input valid beyond doubt. Random rings of 4 to 9 points on a 6 x 6 grid (so crossings, touches,
--    spikes, repeated points and collinear runs are common), alone, with a random hole, or beside a
--    random second part: every input PostGIS calls invalid is refused with PostGIS's reason, every
--    valid one is encoded, by both encoders.
SELECT setseed(0.17);
CREATE TEMP TABLE rings AS
SELECT k, ST_AddPoint(line, ST_StartPoint(line)) AS ring
  FROM (SELECT k, ST_MakeLine(ST_MakePoint(floor(random() * 6), floor(random() * 6)) ORDER BY j) AS line
          FROM generate_series(1, 1800) k, generate_series(1, 4 + k % 6) j GROUP BY k) s;
CREATE TEMP TABLE rnd AS
SELECT a.k, CASE a.k % 3 WHEN 0 THEN ST_MakePolygon(a.ring)
                         WHEN 1 THEN ST_MakePolygon(a.ring, ARRAY[b.ring])
                         ELSE ST_Collect(ST_MakePolygon(a.ring), ST_MakePolygon(b.ring)) END AS geom
  FROM rings a JOIN rings b ON b.k = a.k % 1800 + 1;
-- PostGIS's ST_IsValid says each reason as a NOTICE (the encoders' check does too): not printed here.
SET client_min_messages = warning;
CREATE TEMP TABLE rnd_out AS
SELECT k, ST_IsValid(geom) AS valid, ST_IsValidReason(geom) AS reason,
       outcome(format('SELECT ct_encode_within(%L::geometry, 0.1)', geom::text)) AS within,
       outcome(format('SELECT ct_encode(%L::geometry, 0.05, 0.4, 0.1)', geom::text)) AS encode
  FROM rnd;
RESET client_min_messages;
SELECT count(*) AS inputs, count(*) FILTER (WHERE valid) AS valid,
       count(*) FILTER (WHERE valid AND within = 'ok' AND encode = 'ok') AS valid_encoded,
       count(*) FILTER (WHERE NOT valid AND within LIKE '22023%' AND position(reason IN within) > 0
                              AND encode LIKE '22023%' AND position(reason IN encode) > 0) AS invalid_refused_with_reason
  FROM rnd_out;
SELECT k, valid, reason, within, encode FROM rnd_out
 WHERE valid <> (within = 'ok') OR valid <> (encode = 'ok') ORDER BY k LIMIT 10;
