-- Many small polygons beside the large ones: bytes per value (the distribution, not only sums)
-- and the time of a call, per dataset of table coast (scripts/load.sh; `small` is
-- tests/data/small.tsv.gz). ct_encode_within(geom, t) against ST_AsTWKB(ST_Simplify(geom, t, true), p)
-- on TWKB's grid of at most t/10 (p = ceil(-log(t/10)), as bench/benchmarks.sql), both as stored
-- (pg_column_size). Times in ms, best of three runs each, one run of the script.
\set ON_ERROR_STOP on
SET client_min_messages = warning;
DROP TABLE IF EXISTS sm_rows, sm_speed;
CREATE TABLE sm_rows AS
SELECT c.dataset, c.name, c.npoints, x.t, pg_column_size(ct_encode_within(c.geom, x.t)) AS ct_bytes,
       pg_column_size(ST_AsTWKB(ST_Simplify(c.geom, x.t, true), ceil(-log(x.t / 10))::int)) AS twkb_bytes
  FROM coast c, (VALUES (10.0), (25.0), (100.0)) x(t);
CREATE OR REPLACE FUNCTION pg_temp.best_ms(q text, ds text) RETURNS float8 LANGUAGE plpgsql AS $$
DECLARE t0 timestamptz; best float8 := 'infinity';
BEGIN
  FOR i IN 1..3 LOOP
    t0 := clock_timestamp();
    EXECUTE q USING ds;
    best := least(best, extract(epoch FROM clock_timestamp() - t0) * 1000);
  END LOOP;
  RETURN best;
END $$;
CREATE TEMP TABLE enc AS
SELECT dataset, geom, ct_encode_within(geom, 10) AS ct, ST_AsTWKB(ST_Simplify(geom, 10, true), 0) AS twkb FROM coast;
CREATE TABLE sm_speed AS
SELECT d.dataset, q.step, q.ours, pg_temp.best_ms(q.ours_q, d.dataset) AS ours_ms, q.postgis, pg_temp.best_ms(q.postgis_q, d.dataset) AS postgis_ms,
       (SELECT count(*) FROM coast c WHERE c.dataset = d.dataset) AS values_
  FROM (SELECT DISTINCT dataset FROM coast) d,
       (VALUES
         ('encode within 10 m', 'ct_encode_within(geom, 10)', 'SELECT sum(pg_column_size(ct_encode_within(geom, 10))) FROM enc WHERE dataset = $1',
          'ST_AsTWKB(ST_Simplify(geom, 10, true), 0)', 'SELECT sum(octet_length(ST_AsTWKB(ST_Simplify(geom, 10, true), 0))) FROM enc WHERE dataset = $1'),
         ('decode', 'ct_decode(ct)', 'SELECT sum(ST_NPoints(ct_decode(ct))) FROM enc WHERE dataset = $1',
          'ST_GeomFromTWKB(twkb)', 'SELECT sum(ST_NPoints(ST_GeomFromTWKB(twkb))) FROM enc WHERE dataset = $1'),
         ('validity check alone', '', 'SELECT 1',
          'ST_IsValid(geom)', 'SELECT count(*) FILTER (WHERE ST_IsValid(geom)) FROM enc WHERE dataset = $1')
       ) q(step, ours, ours_q, postgis, postgis_q)
 ORDER BY 1, 2;
SELECT dataset, t, count(*) AS values_, percentile_disc(0.5) WITHIN GROUP (ORDER BY npoints) AS median_vertices,
       sum(ct_bytes) AS ct_bytes, sum(twkb_bytes) AS twkb_bytes, round(sum(ct_bytes)::numeric / sum(twkb_bytes), 3) AS total_ratio,
       round(percentile_cont(0.5) WITHIN GROUP (ORDER BY ct_bytes::float8 / twkb_bytes)::numeric, 3) AS median_ratio,
       round(percentile_cont(0.9) WITHIN GROUP (ORDER BY ct_bytes::float8 / twkb_bytes)::numeric, 3) AS p90_ratio,
       round(100.0 * count(*) FILTER (WHERE ct_bytes > twkb_bytes) / count(*), 1) AS pct_larger
  FROM sm_rows GROUP BY 1, 2 ORDER BY 1, 2;
SELECT dataset, step, round(ours_ms::numeric) AS ours_ms, round(postgis_ms::numeric) AS postgis_ms,
       round((ours_ms / postgis_ms)::numeric, 2) AS ratio FROM sm_speed ORDER BY 1, 2;
