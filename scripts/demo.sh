#!/usr/bin/env bash
# The main job: build and install circletree (release) into the local PostgreSQL 15 (started if
# needed), load the sample polygons shipped in tests/data/samples.tsv, encode them and print, per
# polygon: vertices, WKB bytes, circletree bytes, circles by kind, validity and errors; then
# ct_encode_within(geom, 10) next to ST_Simplify + TWKB at the same 10 m (bytes, validity, Hausdorff).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup.sh

echo "== building and installing circletree (release)"
cargo pgrx install --release --pg-config "$PG_CONFIG" </dev/null

db=circletree_demo
bash scripts/load.sh "$db" samples=tests/data/samples.tsv
psql -X -q -v ON_ERROR_STOP=1 -d "$db" <<'SQL'
SET client_min_messages = warning;
\echo
\echo ct_encode(geom, 5, 0.4, 10): minimum radius 5 m, 40% overlap, Douglas-Peucker 10 m (max_error 10 m)
\echo
SELECT name, ST_NPoints(geom) AS vertices, octet_length(ST_AsBinary(geom)) AS wkb_bytes,
       pg_column_size(geom) AS geom_bytes, pg_column_size(ct) AS ct_bytes,
       round(ct_storage_ratio(ct)::numeric, 3) AS ratio,
       s->>'internal' AS internal, s->>'external' AS external, s->>'zero' AS zero, s->>'added_by_repair' AS repaired,
       ST_IsValid(ct_decode(ct)) AS valid,
       round(ct_hausdorff(ct, geom)::numeric, 2) AS hausdorff_m,
       round((100 * ct_sliver_ratio(ct, geom))::numeric, 4) AS sliver_pct
  FROM (SELECT name, geom, ct_encode(geom, 5, 0.4, 10) AS ct FROM coast) e, LATERAL ct_summary(ct) s
 ORDER BY vertices;
\echo
\echo The fewest bytes within 10 m, ct_encode_within(geom, 10), next to what PostGIS alone stores at the
\echo same tolerance: ST_AsTWKB(ST_Simplify(geom, 10, true), 0) (TWKB on a 1 m grid, measured as it decodes)
\echo
SELECT name, pg_column_size(ct) AS within_bytes, pg_column_size(twkb) AS twkb_bytes,
       round(pg_column_size(ct)::numeric / pg_column_size(twkb), 2) AS within_over_twkb,
       ST_IsValid(ct_decode(ct)) AS within_valid, ST_IsValid(back) AS twkb_valid,
       round(ct_hausdorff(ct, geom)::numeric, 2) AS within_hausdorff_m,
       round(ct_hausdorff(back, geom)::numeric, 2) AS twkb_hausdorff_m
  FROM (SELECT name, geom, ct_encode_within(geom, 10) AS ct, t.twkb,
               ST_SetSRID(ST_GeomFromTWKB(t.twkb), ST_SRID(geom)) AS back
          FROM coast, LATERAL (SELECT ST_AsTWKB(ST_Simplify(geom, 10, true), 0) AS twkb) t) x
 ORDER BY name;
SQL
