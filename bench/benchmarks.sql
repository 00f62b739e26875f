-- circletree against PostGIS on the public polygons. Run by scripts/bench.sh, which loads the
-- polygons into table coast(name, source, npoints, geom) first and exports the bench_* tables it
-- leaves behind as CSV for scripts/bench_report.py. Each query's result is stored, so every size
-- below is pg_column_size of a stored column (what the table costs on disk, TOAST compression
-- included; circletree is STORAGE EXTERNAL, already dense).
\set ON_ERROR_STOP on
SET client_min_messages = warning;
SET max_parallel_workers_per_gather = 0;

DROP TABLE IF EXISTS bench_tol, bench_ct, bench_simp, bench_sizes, bench_sweep, bench_speed;

CREATE TABLE bench_tol AS SELECT unnest('{5,10,25,50,100,250}'::float8[]) AS t;

-- circletree at the issue's setting, ct_encode(geom, t, 0.4, 2t) (its bound is max(t, 2t) = 2t),
-- and at the same bound as ST_Simplify(geom, t): ct_encode(geom, t/2, 0.4, t).
\echo == encoding: 2 settings x 6 tolerances x every polygon
CREATE TABLE bench_ct AS
SELECT c.name, x.t, s.setting, s.bound, ct_encode(c.geom, s.min_radius, 0.4, s.dp) AS ct
  FROM coast c, bench_tol x,
       LATERAL (VALUES ('issue', x.t, 2 * x.t, 2 * x.t), ('same_bound', x.t / 2, x.t, x.t))
               AS s(setting, min_radius, dp, bound);
ALTER TABLE bench_ct ADD COLUMN hausdorff float8, ADD COLUMN sliver float8, ADD COLUMN valid bool;
\echo == measuring circletree (continuous Hausdorff, sliver area, validity)
UPDATE bench_ct b SET hausdorff = ct_hausdorff(b.ct, c.geom), sliver = ct_sliver_error(b.ct, c.geom),
                      valid = ST_IsValid(ct_decode(b.ct))
  FROM coast c WHERE c.name = b.name;

-- PostGIS's best: ST_Simplify (Douglas-Peucker, keeping collapsed rings) stored as TWKB on a grid
-- of at most t/10 (10^-p metres, p decimal digits). Errors are measured on what TWKB gives back.
\echo == ST_Simplify + TWKB at 6 tolerances
CREATE TABLE bench_simp AS
SELECT name, t, simplified, twkb, twkb_digits, ST_SetSRID(ST_GeomFromTWKB(twkb), srid) AS back
  FROM (SELECT c.name, x.t, s AS simplified, ST_AsTWKB(s, p) AS twkb, p AS twkb_digits, ST_SRID(c.geom) AS srid
          FROM coast c, bench_tol x,
               LATERAL (SELECT ST_Simplify(c.geom, x.t, true) AS s, ceil(-log(x.t / 10))::int AS p) q) y;
ALTER TABLE bench_simp ADD COLUMN hausdorff float8, ADD COLUMN sliver float8, ADD COLUMN valid bool;
\echo == measuring ST_Simplify + TWKB (same continuous Hausdorff, ST_SymDifference, ST_IsValid)
UPDATE bench_simp b SET hausdorff = ct_hausdorff(b.back, c.geom),
                        sliver = ST_Area(ST_SymDifference(c.geom, ST_MakeValid(b.back))),
                        valid = ST_IsValid(b.back)
  FROM coast c WHERE c.name = b.name;

CREATE TABLE bench_sizes AS
SELECT x.t,
       (SELECT count(*) FROM coast) AS polygons,
       (SELECT sum(npoints) FROM coast) AS vertices,
       (SELECT sum(pg_column_size(geom)) FROM coast) AS geom_bytes,
       (SELECT sum(octet_length(ST_AsBinary(geom))) FROM coast) AS wkb_bytes,
       ci.bytes AS ct_bytes, ci.hmax / (2 * x.t) AS ct_hausdorff_over_bound, ci.sliver AS ct_sliver_ratio, ci.valid AS ct_valid,
       cs.bytes AS ct1_bytes, cs.hmax / x.t AS ct1_hausdorff_over_bound, cs.sliver AS ct1_sliver_ratio, cs.valid AS ct1_valid,
       cs.smaller AS ct1_smaller_than_twkb,
       sp.wkb AS simp_wkb_bytes, sp.twkb AS simp_twkb_bytes, sp.digits AS twkb_digits,
       sp.hmax / x.t AS simp_hausdorff_over_bound, sp.sliver AS simp_sliver_ratio, sp.valid AS simp_valid
  FROM bench_tol x,
       LATERAL (SELECT sum(pg_column_size(b.ct)) AS bytes, max(b.hausdorff) AS hmax,
                       sum(b.sliver) / (SELECT sum(ST_Area(geom)) FROM coast) AS sliver,
                       avg(b.valid::int) AS valid
                  FROM bench_ct b WHERE b.t = x.t AND b.setting = 'issue') ci,
       LATERAL (SELECT sum(pg_column_size(b.ct)) AS bytes, max(b.hausdorff) AS hmax,
                       sum(b.sliver) / (SELECT sum(ST_Area(geom)) FROM coast) AS sliver,
                       avg(b.valid::int) AS valid,
                       count(*) FILTER (WHERE pg_column_size(b.ct) < pg_column_size(s.twkb)) AS smaller
                  FROM bench_ct b JOIN bench_simp s ON s.name = b.name AND s.t = b.t
                 WHERE b.t = x.t AND b.setting = 'same_bound') cs,
       LATERAL (SELECT sum(octet_length(ST_AsBinary(s.simplified))) AS wkb, sum(pg_column_size(s.twkb)) AS twkb,
                       max(s.twkb_digits) AS digits, max(s.hausdorff) AS hmax,
                       sum(s.sliver) / (SELECT sum(ST_Area(geom)) FROM coast) AS sliver,
                       avg(s.valid::int) AS valid
                  FROM bench_simp s WHERE s.t = x.t) sp
 ORDER BY x.t;

-- The paper's experiment (figures 11 to 14) on Kapiti Island: all 150 combinations.
\echo == the paper's experiment on kapiti_island_linz (150 encodings)
CREATE TABLE bench_sweep AS
SELECT * FROM ct_sweep((SELECT geom FROM coast WHERE name = 'kapiti_island_linz'));

-- Speed: best of three runs of each query over the whole set, in milliseconds.
CREATE OR REPLACE FUNCTION pg_temp.best_ms(q text, reps int DEFAULT 3) RETURNS float8
LANGUAGE plpgsql AS $$
DECLARE
  t0 timestamptz;
  best float8 := 'infinity';
BEGIN
  FOR i IN 1..reps LOOP
    t0 := clock_timestamp();
    EXECUTE q;
    best := least(best, extract(epoch FROM clock_timestamp() - t0) * 1000);
  END LOOP;
  RETURN best;
END $$;

CREATE TEMP TABLE enc10 AS SELECT c.name, c.geom, c.npoints, ct_encode(c.geom, 5, 0.4, 10) AS ct FROM coast c;
CREATE TEMP TABLE small AS SELECT * FROM enc10 WHERE npoints <= 5000;

\echo == speed (best of 3 runs)
CREATE TABLE bench_speed(step text, ours text, ours_ms float8, postgis text, postgis_ms float8, vertices bigint);
INSERT INTO bench_speed
SELECT step, ours, pg_temp.best_ms(ours_q), postgis, pg_temp.best_ms(postgis_q), v
  FROM (VALUES
    ('encode', 'ct_encode(geom, 5, 0.4, 10)', 'SELECT sum(pg_column_size(ct_encode(geom, 5, 0.4, 10))) FROM enc10',
               'ST_Simplify(geom, 10, true)', 'SELECT sum(pg_column_size(ST_Simplify(geom, 10, true))) FROM enc10',
               (SELECT sum(npoints) FROM enc10)),
    ('encode, stored form', 'ct_encode(geom, 5, 0.4, 10)', 'SELECT sum(pg_column_size(ct_encode(geom, 5, 0.4, 10))) FROM enc10',
               'ST_AsTWKB(ST_Simplify(geom, 10, true), 0)', 'SELECT sum(octet_length(ST_AsTWKB(ST_Simplify(geom, 10, true), 0))) FROM enc10',
               (SELECT sum(npoints) FROM enc10)),
    ('decode', 'ct_decode(ct)', 'SELECT sum(ST_NPoints(ct_decode(ct))) FROM enc10',
               'ST_AsTWKB(geom, 0)', 'SELECT sum(octet_length(ST_AsTWKB(geom, 0))) FROM enc10',
               (SELECT sum(npoints) FROM enc10)),
    ('decode, simplified', 'ct_decode(ct)', 'SELECT sum(ST_NPoints(ct_decode(ct))) FROM enc10',
               'ST_GeomFromTWKB(twkb of ST_Simplify(geom, 10))', 'SELECT sum(ST_NPoints(ST_GeomFromTWKB(twkb))) FROM bench_simp WHERE t = 10',
               (SELECT sum(npoints) FROM enc10)),
    ('sliver area', 'ct_sliver_error(ct, geom)', 'SELECT sum(ct_sliver_error(ct, geom)) FROM enc10',
               'ST_Area(ST_SymDifference(geom, ct_decode(ct)))', 'SELECT sum(ST_Area(ST_SymDifference(geom, ct_decode(ct)))) FROM enc10',
               (SELECT sum(npoints) FROM enc10)),
    ('Hausdorff (polygons of at most 5,000 vertices)', 'ct_hausdorff(ct, geom)', 'SELECT sum(ct_hausdorff(ct, geom)) FROM small',
               'ST_HausdorffDistance(ct_decode(ct), geom)', 'SELECT sum(ST_HausdorffDistance(ct_decode(ct), geom)) FROM small',
               (SELECT sum(npoints) FROM small))
  ) AS q(step, ours, ours_q, postgis, postgis_q, v);
