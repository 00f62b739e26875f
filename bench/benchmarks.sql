-- circletree against PostGIS on the public polygons and the held-out ones. Run by scripts/bench.sh,
-- which loads the polygons into table coast(dataset, family, name, source, npoints, geom) first
-- and exports the bench_* tables it leaves behind as CSV for scripts/bench_report.py. Each query's
-- result is stored, so every size below is pg_column_size of a stored column (what the table
-- costs on disk, TOAST compression included; circletree is STORAGE EXTERNAL, already dense).
\set ON_ERROR_STOP on
SET client_min_messages = warning;
SET max_parallel_workers_per_gather = 0;

DROP TABLE IF EXISTS bench_tol, bench_ct, bench_simp, bench_rows, bench_sweep, bench_speed;

CREATE TABLE bench_tol AS SELECT unnest('{5,10,25,50,100,250}'::float8[]) AS t;

-- circletree, three ways: ct_encode_within(geom, t) (the fewest bytes within t), ct_encode at the
-- same bound, ct_encode(geom, t/2, 0.4, t), and at the setting issue 4 used, ct_encode(geom, t,
-- 0.4, 2t) (bound 2t).
\echo == encoding: 3 encoders x 6 tolerances x every polygon (public and held-out)
CREATE TABLE bench_ct AS
SELECT c.name, x.t, s.method, s.bound,
       CASE WHEN s.method = 'ct_encode_within' THEN ct_encode_within(c.geom, x.t)
            ELSE ct_encode(c.geom, s.min_radius, 0.4, s.dp) END AS ct
  FROM coast c, bench_tol x,
       LATERAL (VALUES ('ct_encode_within', NULL, NULL, x.t),
                       ('ct_encode', x.t / 2, x.t, x.t),
                       ('ct_encode_2t', x.t, 2 * x.t, 2 * x.t)) AS s(method, min_radius, dp, bound);
ALTER TABLE bench_ct ADD COLUMN hausdorff float8, ADD COLUMN sliver float8, ADD COLUMN valid bool;
\echo == measuring circletree (continuous Hausdorff, sliver area, validity)
UPDATE bench_ct b SET hausdorff = ct_hausdorff(b.ct, c.geom), sliver = ct_sliver_error(b.ct, c.geom),
                      valid = ST_IsValid(ct_decode(b.ct))
  FROM coast c WHERE c.name = b.name;

-- PostGIS: ST_Simplify (Douglas-Peucker, keeping collapsed rings) and ST_SimplifyPreserveTopology
-- (its valid alternative), each stored as TWKB on a grid of at most t/10 (10^-p metres, p decimal
-- digits: ceil(-log(t/10))). Errors are measured on what TWKB gives back.
\echo == ST_Simplify and ST_SimplifyPreserveTopology + TWKB at 6 tolerances
CREATE TABLE bench_simp AS
SELECT name, t, method, twkb, ST_SetSRID(ST_GeomFromTWKB(twkb), srid) AS back
  FROM (SELECT c.name, x.t, m.method, ST_AsTWKB(m.s, q.p) AS twkb, ST_SRID(c.geom) AS srid
          FROM coast c, bench_tol x,
               LATERAL (SELECT ceil(-log(x.t / 10))::int AS p) q,
               LATERAL (VALUES ('dp_twkb', ST_Simplify(c.geom, x.t, true)),
                               ('topo_twkb', ST_SimplifyPreserveTopology(c.geom, x.t))) AS m(method, s)) y;
ALTER TABLE bench_simp ADD COLUMN hausdorff float8, ADD COLUMN sliver float8, ADD COLUMN valid bool;
\echo == measuring the PostGIS results (same continuous Hausdorff, ST_SymDifference, ST_IsValid)
UPDATE bench_simp b SET hausdorff = ct_hausdorff(b.back, c.geom),
                        sliver = ST_Area(ST_SymDifference(c.geom, ST_MakeValid(b.back))),
                        valid = ST_IsValid(b.back)
  FROM coast c WHERE c.name = b.name;

-- One row per polygon, tolerance and method; scripts/bench_report.py sums them (and compresses
-- each TWKB value with LZMA2, the entropy reference, from its hex).
CREATE TABLE bench_rows AS
SELECT c.dataset, c.family, c.name, c.npoints, pg_column_size(c.geom) AS geom_bytes,
       octet_length(ST_AsBinary(c.geom)) AS wkb_bytes, ST_Area(c.geom) AS area,
       b.t, b.method, b.bound, pg_column_size(b.ct) AS bytes, ct_ncircles(b.ct) AS points,
       b.hausdorff, b.sliver, b.valid, NULL::text AS twkb_hex, NULL::int AS varlena_header
  FROM bench_ct b JOIN coast c USING (name)
UNION ALL
SELECT c.dataset, c.family, c.name, c.npoints, pg_column_size(c.geom), octet_length(ST_AsBinary(c.geom)),
       ST_Area(c.geom), s.t, s.method, s.t, pg_column_size(s.twkb), ST_NPoints(s.back),
       s.hausdorff, s.sliver, s.valid, encode(s.twkb, 'hex'), pg_column_size(s.twkb) - octet_length(s.twkb)
  FROM bench_simp s JOIN coast c USING (name);

-- The paper's experiment (figures 11 to 14) on Kapiti Island: all 150 combinations.
\echo == the experiment of the paper on kapiti_island_linz (150 encodings)
CREATE TABLE bench_sweep AS
SELECT * FROM ct_sweep((SELECT geom FROM coast WHERE name = 'kapiti_island_linz'));

-- Speed: best of three runs of each query over the public set, in milliseconds.
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

CREATE TEMP TABLE enc10 AS
SELECT c.name, c.geom, c.npoints, ct_encode(c.geom, 5, 0.4, 10) AS ct, ct_encode_within(c.geom, 10) AS ctw,
       (SELECT s.twkb FROM bench_simp s WHERE s.name = c.name AND s.t = 10 AND s.method = 'dp_twkb') AS twkb
  FROM coast c WHERE c.dataset = 'public';
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
    ('encode within 10 m', 'ct_encode_within(geom, 10)', 'SELECT sum(pg_column_size(ct_encode_within(geom, 10))) FROM enc10',
               'ST_AsTWKB(ST_Simplify(geom, 10, true), 0)', 'SELECT sum(octet_length(ST_AsTWKB(ST_Simplify(geom, 10, true), 0))) FROM enc10',
               (SELECT sum(npoints) FROM enc10)),
    ('decode', 'ct_decode(ct)', 'SELECT sum(ST_NPoints(ct_decode(ct))) FROM enc10',
               'ST_AsTWKB(geom, 0)', 'SELECT sum(octet_length(ST_AsTWKB(geom, 0))) FROM enc10',
               (SELECT sum(npoints) FROM enc10)),
    ('decode, simplified', 'ct_decode(ct)', 'SELECT sum(ST_NPoints(ct_decode(ct))) FROM enc10',
               'ST_GeomFromTWKB(twkb of ST_Simplify(geom, 10))', 'SELECT sum(ST_NPoints(ST_GeomFromTWKB(twkb))) FROM enc10',
               (SELECT sum(npoints) FROM enc10)),
    ('decode, within 10 m', 'ct_decode(ct_encode_within(geom, 10))', 'SELECT sum(ST_NPoints(ct_decode(ctw))) FROM enc10',
               'ST_GeomFromTWKB(twkb of ST_Simplify(geom, 10))', 'SELECT sum(ST_NPoints(ST_GeomFromTWKB(twkb))) FROM enc10',
               (SELECT sum(npoints) FROM enc10)),
    ('sliver area', 'ct_sliver_error(ct, geom)', 'SELECT sum(ct_sliver_error(ct, geom)) FROM enc10',
               'ST_Area(ST_SymDifference(geom, ct_decode(ct)))', 'SELECT sum(ST_Area(ST_SymDifference(geom, ct_decode(ct)))) FROM enc10',
               (SELECT sum(npoints) FROM enc10)),
    ('Hausdorff (polygons of at most 5,000 vertices)', 'ct_hausdorff(ct, geom)', 'SELECT sum(ct_hausdorff(ct, geom)) FROM small',
               'ST_HausdorffDistance(ct_decode(ct), geom)', 'SELECT sum(ST_HausdorffDistance(ct_decode(ct), geom)) FROM small',
               (SELECT sum(npoints) FROM small))
  ) AS q(step, ours, ours_q, postgis, postgis_q, v);
