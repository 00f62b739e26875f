-- In place: joins on a circletree column with its native GiST index against the GiST-indexed
-- geometry column of ST_Simplify(geom, 10, true) and against the original geometry, in EPSG:3857,
-- per dataset of table coast (scripts/load.sh). 22,000 random points in the polygons' envelopes,
-- 2,000 windows of 2 km, points within 500 m. Times in ms, one run each; the counts must agree
-- between circletree and ct_decode's PostGIS answers (checked in regress in_place), and the ratio
-- column is circletree's time over the simplified column's.
\set ON_ERROR_STOP on
SET client_min_messages = warning;
DROP TABLE IF EXISTS ip_g, ip_pts, ip_win, ip_times, ip_mem;
CREATE TABLE ip_g AS
SELECT dataset, name, g3857 AS orig, ST_Simplify(g3857, 10, true) AS g10, ct_encode_within(g3857, 10) AS c10
  FROM (SELECT dataset, name, ST_Transform(geom, 3857) AS g3857 FROM coast) s;
CREATE INDEX ON ip_g USING gist (orig);
CREATE INDEX ON ip_g USING gist (g10);
CREATE INDEX ON ip_g USING gist (c10);
ANALYZE ip_g;
SELECT setseed(0.5);
CREATE TABLE ip_pts AS
SELECT d.dataset, ST_SetSRID(ST_MakePoint(x0 + random() * (x1 - x0), y0 + random() * (y1 - y0)), 3857) AS pt
  FROM (SELECT dataset, ST_XMin(e) x0, ST_XMax(e) x1, ST_YMin(e) y0, ST_YMax(e) y1, row_number() OVER (PARTITION BY dataset) k,
               count(*) OVER (PARTITION BY dataset) n
          FROM (SELECT dataset, ST_Envelope(orig) e FROM ip_g) s) d,
       LATERAL generate_series(1, (22000 / d.n)::int) i;
CREATE TABLE ip_win AS SELECT dataset, ST_Expand(pt, 1000) AS w FROM (SELECT *, row_number() OVER (PARTITION BY dataset) r FROM ip_pts) s
 WHERE r % 11 = 0;
ANALYZE ip_pts; ANALYZE ip_win;
CREATE TABLE ip_times(dataset text, query text, column_ text, rows bigint, ms float8);
CREATE OR REPLACE FUNCTION pg_temp.timed(ds text, q text, col text, sql text) RETURNS void LANGUAGE plpgsql AS $$
DECLARE t0 timestamptz; n bigint;
BEGIN
  t0 := clock_timestamp();
  EXECUTE sql INTO n USING ds;
  INSERT INTO ip_times VALUES (ds, q, col, n, extract(epoch FROM clock_timestamp() - t0) * 1000);
END $$;
DO $$
DECLARE ds text;
BEGIN
  FOR ds IN SELECT DISTINCT dataset FROM ip_g ORDER BY 1 LOOP
    PERFORM pg_temp.timed(ds, 'points in polygons', 'orig', 'SELECT count(*) FROM ip_pts p JOIN ip_g g ON g.dataset = $1 AND ST_Intersects(g.orig, p.pt) WHERE p.dataset = $1');
    PERFORM pg_temp.timed(ds, 'points in polygons', 'g10', 'SELECT count(*) FROM ip_pts p JOIN ip_g g ON g.dataset = $1 AND ST_Intersects(g.g10, p.pt) WHERE p.dataset = $1');
    PERFORM pg_temp.timed(ds, 'points in polygons', 'c10', 'SELECT count(*) FROM ip_pts p JOIN ip_g g ON g.dataset = $1 AND ct_intersects(g.c10, p.pt) WHERE p.dataset = $1');
    PERFORM pg_temp.timed(ds, 'points within 500 m', 'orig', 'SELECT count(*) FROM ip_pts p JOIN ip_g g ON g.dataset = $1 AND ST_DWithin(g.orig, p.pt, 500) WHERE p.dataset = $1');
    PERFORM pg_temp.timed(ds, 'points within 500 m', 'g10', 'SELECT count(*) FROM ip_pts p JOIN ip_g g ON g.dataset = $1 AND ST_DWithin(g.g10, p.pt, 500) WHERE p.dataset = $1');
    PERFORM pg_temp.timed(ds, 'points within 500 m', 'c10', 'SELECT count(*) FROM ip_pts p JOIN ip_g g ON g.dataset = $1 AND ct_dwithin(g.c10, p.pt, 500) WHERE p.dataset = $1');
    PERFORM pg_temp.timed(ds, 'windows of 2 km', 'orig', 'SELECT count(*) FROM ip_win w JOIN ip_g g ON g.dataset = $1 AND ST_Intersects(g.orig, w.w) WHERE w.dataset = $1');
    PERFORM pg_temp.timed(ds, 'windows of 2 km', 'g10', 'SELECT count(*) FROM ip_win w JOIN ip_g g ON g.dataset = $1 AND ST_Intersects(g.g10, w.w) WHERE w.dataset = $1');
    PERFORM pg_temp.timed(ds, 'windows of 2 km', 'c10', 'SELECT count(*) FROM ip_win w JOIN ip_g g ON g.dataset = $1 AND ct_intersects(g.c10, w.w) WHERE w.dataset = $1');
  END LOOP;
END $$;
SELECT t.dataset, t.query, o.ms::int AS orig_ms, g.ms::int AS g10_ms, t.ms::int AS c10_ms,
       round((t.ms / g.ms)::numeric, 2) AS c10_over_g10, t.rows AS c10_rows, g.rows AS g10_rows
  FROM ip_times t JOIN ip_times g USING (dataset, query) JOIN ip_times o USING (dataset, query)
 WHERE t.column_ = 'c10' AND g.column_ = 'g10' AND o.column_ = 'orig' ORDER BY 1, 2;
SELECT dataset, pg_size_pretty(sum(pg_column_size(orig))) AS orig, pg_size_pretty(sum(pg_column_size(g10))) AS g10,
       pg_size_pretty(sum(pg_column_size(c10))) AS c10 FROM ip_g GROUP BY 1 ORDER BY 1;
-- Peak backend memory: each join alone in a new backend, then the backend's peak resident set
-- (VmHWM, which counts the shared buffers it touched) and a new backend's peak after SELECT 1.
CREATE TABLE ip_mem(dataset text, query text, column_ text, peak_kb bigint);
\set peak 'INSERT INTO ip_mem SELECT :''ds'', :''q'', :''col'', (regexp_match(pg_read_file(''/proc/'' || pg_backend_pid() || ''/status''), ''VmHWM:\\s+(\\d+)''))[1]::bigint;'
\c
\set ds '' \set q 'new backend' \set col ''
SELECT 1 \g /dev/null
:peak
\c
\set ds public \set q 'points in polygons' \set col g10
SELECT count(*) FROM ip_pts p JOIN ip_g g ON g.dataset = :'ds' AND ST_Intersects(g.g10, p.pt) WHERE p.dataset = :'ds' \g /dev/null
:peak
\c
\set ds public \set q 'points in polygons' \set col c10
SELECT count(*) FROM ip_pts p JOIN ip_g g ON g.dataset = :'ds' AND ct_intersects(g.c10, p.pt) WHERE p.dataset = :'ds' \g /dev/null
:peak
\c
\set ds public \set q 'windows of 2 km' \set col g10
SELECT count(*) FROM ip_win w JOIN ip_g g ON g.dataset = :'ds' AND ST_Intersects(g.g10, w.w) WHERE w.dataset = :'ds' \g /dev/null
:peak
\c
\set ds public \set q 'windows of 2 km' \set col c10
SELECT count(*) FROM ip_win w JOIN ip_g g ON g.dataset = :'ds' AND ct_intersects(g.c10, w.w) WHERE w.dataset = :'ds' \g /dev/null
:peak
\c
\set ds holdout \set q 'points in polygons' \set col g10
SELECT count(*) FROM ip_pts p JOIN ip_g g ON g.dataset = :'ds' AND ST_Intersects(g.g10, p.pt) WHERE p.dataset = :'ds' \g /dev/null
:peak
\c
\set ds holdout \set q 'points in polygons' \set col c10
SELECT count(*) FROM ip_pts p JOIN ip_g g ON g.dataset = :'ds' AND ct_intersects(g.c10, p.pt) WHERE p.dataset = :'ds' \g /dev/null
:peak
\c
\set ds holdout \set q 'windows of 2 km' \set col g10
SELECT count(*) FROM ip_win w JOIN ip_g g ON g.dataset = :'ds' AND ST_Intersects(g.g10, w.w) WHERE w.dataset = :'ds' \g /dev/null
:peak
\c
\set ds holdout \set q 'windows of 2 km' \set col c10
SELECT count(*) FROM ip_win w JOIN ip_g g ON g.dataset = :'ds' AND ct_intersects(g.c10, w.w) WHERE w.dataset = :'ds' \g /dev/null
:peak
