#!/usr/bin/env bash
# Scale-out check, by hand, not in CI: circletree in a Citus distributed table, and joins on it.
# Needs Citus built and installed into the system PostgreSQL 15 (it is not in Debian's packages;
# docs/RELIABILITY.md says how it was built here) and circletree installed. Three throwaway clusters on
# this machine: a coordinator and two workers. The sample polygons go into a distributed table; a
# distributed INSERT ... SELECT encodes them on the workers into a colocated table with a circletree
# column; the bytes must equal a local encode's, and the distributed decode, metrics and round trips
# through the workers must agree. The clusters are removed on exit.
#   bash scripts/citus.sh
set -euo pipefail
cd "$(dirname "$0")/.."
as_root() { if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi; }
ports=(5451 5452 5453)
cleanup() {
  for port in "${ports[@]}"; do
    as_root pg_dropcluster --stop 15 "ct$port" >/dev/null 2>&1 || true
  done
}
trap cleanup EXIT
cleanup
for port in "${ports[@]}"; do
  as_root pg_createcluster 15 "ct$port" --port "$port" -- --auth-local=trust --auth-host=trust >/dev/null 2>&1
  as_root pg_conftool 15 "ct$port" set shared_preload_libraries citus
  as_root pg_conftool 15 "ct$port" set listen_addresses localhost
  as_root pg_ctlcluster 15 "ct$port" start
done
q() { as_root runuser -u postgres -- psql -X -q -v ON_ERROR_STOP=1 -h /var/run/postgresql -p "$1" -d "$2" "${@:3}"; }
for port in "${ports[@]}"; do
  q "$port" postgres -c "CREATE DATABASE ct"
  q "$port" ct -c "SET client_min_messages = warning" -c "CREATE EXTENSION citus"
done
q 5451 ct -c "SELECT citus_set_coordinator_host('localhost', 5451)" \
  -c "SELECT citus_add_node('localhost', 5452)" -c "SELECT citus_add_node('localhost', 5453)" >/dev/null
echo "== nodes"
q 5451 ct -c "SELECT nodename, nodeport, noderole FROM pg_dist_node ORDER BY nodeport"
# CREATE EXTENSION on the coordinator is propagated to the workers by Citus
q 5451 ct -c "SET client_min_messages = warning" -c "CREATE EXTENSION circletree CASCADE"
q 5451 ct -At -c "SELECT extversion FROM pg_extension WHERE extname = 'circletree'" | sed 's/^/coordinator circletree /'
for port in 5452 5453; do
  q "$port" ct -At -c "SELECT extversion FROM pg_extension WHERE extname = 'circletree'" | sed "s/^/worker $port circletree /"
done
gzip -dc tests/data/polygons.tsv.gz | awk -F'\t' 'NR > 1 {print $1 "\t" $3 "\t" $5}' >/tmp/circletree_citus.tsv
chmod a+r /tmp/circletree_citus.tsv
q 5451 ct <<'SQL'
CREATE TABLE coast(name text PRIMARY KEY, geom geometry);
SELECT create_distributed_table('coast', 'name', shard_count := 8);
CREATE TEMP TABLE raw(name text, srid int, wkt text);
\copy raw FROM '/tmp/circletree_citus.tsv' WITH (FORMAT text)
INSERT INTO coast SELECT name, ST_GeomFromText(wkt, srid) FROM raw;
CREATE TABLE coast_ct(name text PRIMARY KEY, ct circletree, paper circletree);
SELECT create_distributed_table('coast_ct', 'name', colocate_with := 'coast');
\echo == the distributed encode (pushed down to the workers)
EXPLAIN (COSTS off) INSERT INTO coast_ct SELECT name, ct_encode_within(geom, 10), ct_encode(geom, 5, 0.4, 10) FROM coast;
\timing on
INSERT INTO coast_ct SELECT name, ct_encode_within(geom, 10), ct_encode(geom, 5, 0.4, 10) FROM coast;
\timing off
\echo == rows per worker
SELECT nodeport, count(*) AS shards, sum(result::int) AS rows
  FROM run_command_on_shards('coast_ct', 'SELECT count(*) FROM %s') r
  JOIN pg_dist_shard_placement p USING (shardid) GROUP BY nodeport ORDER BY nodeport;
\echo == the same encode on the coordinator alone (a local table)
CREATE TABLE local_src AS SELECT * FROM coast;
\timing on
CREATE TABLE local_ct AS SELECT name, ct_encode_within(geom, 10) AS ct, ct_encode(geom, 5, 0.4, 10) AS paper FROM local_src;
\timing off
SELECT count(*) AS rows,
       count(*) FILTER (WHERE d.ct::bytea = l.ct::bytea AND d.paper::bytea = l.paper::bytea) AS same_bytes
  FROM coast_ct d JOIN local_ct l USING (name);
\echo == distributed decode and metrics (on the workers) against the local ones
SELECT count(*) AS rows,
       count(*) FILTER (WHERE ST_IsValid(ct_decode(ct)) AND ct_hausdorff(ct, geom) <= 10) AS valid_within_10
  FROM coast_ct JOIN coast USING (name);
SELECT round(sum(pg_column_size(ct))::numeric / 1024, 1) AS ct_kb, round(sum(pg_column_size(paper))::numeric / 1024, 1) AS paper_kb,
       round(sum(ct_sliver_error(ct, geom))::numeric) AS sliver_m2 FROM coast_ct JOIN coast USING (name);
SELECT round(sum(pg_column_size(ct))::numeric / 1024, 1) AS ct_kb, round(sum(pg_column_size(paper))::numeric / 1024, 1) AS paper_kb,
       round(sum(ct_sliver_error(ct, geom))::numeric) AS sliver_m2 FROM local_ct JOIN local_src USING (name);
\echo == a shard moved between workers: the same bytes after the move
SELECT md5(string_agg(ct::bytea::text || paper::bytea::text, ',' ORDER BY name)) AS before FROM coast_ct \gset
SELECT citus_move_shard_placement(s.shardid, 'localhost', p.nodeport, 'localhost', CASE p.nodeport WHEN 5452 THEN 5453 ELSE 5452 END, shard_transfer_mode := 'block_writes')
  FROM pg_dist_shard s JOIN pg_dist_shard_placement p USING (shardid)
 WHERE s.logicalrelid = 'coast'::regclass ORDER BY s.shardid LIMIT 1;
SELECT md5(string_agg(ct::bytea::text || paper::bytea::text, ',' ORDER BY name)) = :'before' AS same_after_move FROM coast_ct;
\echo == joins on the workers with the native GiST index (EPSG:3857, as bench/in_place.sql), against the local answers
CREATE TABLE ip_ct(name text PRIMARY KEY, ct circletree);
SELECT create_distributed_table('ip_ct', 'name', colocate_with := 'coast');
INSERT INTO ip_ct SELECT name, ct_encode_within(ST_Transform(geom, 3857), 10) FROM coast;
CREATE INDEX ip_ct_gist ON ip_ct USING gist (ct);
SELECT setseed(0.5);
CREATE TABLE ip_pts(id int PRIMARY KEY, pt geometry);
INSERT INTO ip_pts
SELECT row_number() OVER (), ST_SetSRID(ST_MakePoint(ST_XMin(e) + random() * (ST_XMax(e) - ST_XMin(e)),
                                                     ST_YMin(e) + random() * (ST_YMax(e) - ST_YMin(e))), 3857)
  FROM (SELECT ct_envelope(ct) AS e FROM ip_ct ORDER BY name) s, generate_series(1, 200);
SELECT create_reference_table('ip_pts');
CREATE TABLE ip_win(id int PRIMARY KEY, w geometry);
INSERT INTO ip_win SELECT id, ST_Expand(pt, 1000) FROM ip_pts WHERE id % 5 = 0;
SELECT create_reference_table('ip_win');
-- the same tables on the coordinator alone
CREATE TABLE l_ct AS SELECT * FROM ip_ct;
CREATE INDEX ON l_ct USING gist (ct);
CREATE TABLE l_pts AS SELECT * FROM ip_pts;
CREATE TABLE l_win AS SELECT * FROM ip_win;
ANALYZE l_ct; ANALYZE l_pts; ANALYZE l_win;
EXPLAIN (COSTS off) SELECT g.name, p.id FROM ip_pts p JOIN ip_ct g ON ct_intersects(g.ct, p.pt);
SELECT 'points in polygons' AS join_, d.n AS distributed_rows, l.n AS local_rows, d.h = l.h AS same_pairs
  FROM (SELECT count(*) n, md5(string_agg(g.name || '/' || p.id, ',' ORDER BY g.name, p.id)) h FROM ip_pts p JOIN ip_ct g ON ct_intersects(g.ct, p.pt)) d,
       (SELECT count(*) n, md5(string_agg(g.name || '/' || p.id, ',' ORDER BY g.name, p.id)) h FROM l_pts p JOIN l_ct g ON ct_intersects(g.ct, p.pt)) l
UNION ALL
SELECT 'points within 500 m', d.n, l.n, d.h = l.h
  FROM (SELECT count(*) n, md5(string_agg(g.name || '/' || p.id, ',' ORDER BY g.name, p.id)) h FROM ip_pts p JOIN ip_ct g ON ct_dwithin(g.ct, p.pt, 500)) d,
       (SELECT count(*) n, md5(string_agg(g.name || '/' || p.id, ',' ORDER BY g.name, p.id)) h FROM l_pts p JOIN l_ct g ON ct_dwithin(g.ct, p.pt, 500)) l
UNION ALL
SELECT 'windows of 2 km', d.n, l.n, d.h = l.h
  FROM (SELECT count(*) n, md5(string_agg(g.name || '/' || w.id, ',' ORDER BY g.name, w.id)) h FROM ip_win w JOIN ip_ct g ON ct_intersects(g.ct, w.w)) d,
       (SELECT count(*) n, md5(string_agg(g.name || '/' || w.id, ',' ORDER BY g.name, w.id)) h FROM l_win w JOIN l_ct g ON ct_intersects(g.ct, w.w)) l;
SQL
