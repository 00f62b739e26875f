#!/usr/bin/env bash
# The main job: build and install circletree (release) into the local PostgreSQL 15 (started if
# needed), load the sample polygons shipped in tests/data/samples.tsv, encode them and print, per
# polygon: vertices, WKB bytes, circletree bytes, circles by kind, validity and errors.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup.sh

echo "== building and installing circletree (release)"
cargo pgrx install --release --pg-config "$PG_CONFIG" </dev/null

db=circletree_demo
psql -X -q -d postgres -c "DROP DATABASE IF EXISTS $db" -c "CREATE DATABASE $db"
psql -X -q -v ON_ERROR_STOP=1 -d "$db" <<'SQL'
SET client_min_messages = warning;
CREATE EXTENSION circletree CASCADE;
CREATE TABLE poly(name text, source text, srid int, npoints int, wkt text);
\copy poly FROM 'tests/data/samples.tsv' WITH (FORMAT csv, DELIMITER E'\t', HEADER true, QUOTE E'\x01')
CREATE TABLE coast AS SELECT name, ST_GeomFromText(wkt, srid) AS geom FROM poly;
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
\echo The same polygons by PostGIS alone: ST_Simplify(geom, 10, true) as TWKB on a 1 m grid (smaller today, see README)
\echo
SELECT name, ST_NPoints(s) AS vertices, octet_length(ST_AsTWKB(s, 0)) AS twkb_bytes, ST_IsValid(s) AS valid,
       round(ST_HausdorffDistance(s, geom)::numeric, 2) AS hausdorff_m
  FROM (SELECT name, geom, ST_Simplify(geom, 10, true) AS s FROM coast) x ORDER BY 2;
SQL
