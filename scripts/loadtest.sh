#!/usr/bin/env bash
# Load test (issue 9 item 3): pgbench, CLIENTS clients (default 8) for SECONDS (default 60), each
# transaction one of: ct_encode_within + INSERT into a table with a circletree column, ct_encode +
# INSERT, ct_decode of a stored row, ct_hausdorff and ct_sliver_error of a stored row. Then: every
# stored row decodes to a valid polygon, the peak RSS of each pgbench backend (VmHWM, sampled just
# before the run ends), and a parallel scan that encodes the table gives the serial bytes. Needs the
# extension installed (scripts/demo.sh or scripts/test.sh did it).
#   bash scripts/loadtest.sh [SECONDS] [CLIENTS]
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup.sh
secs=${1:-60}
clients=${2:-8}
db=circletree_load
bash scripts/load.sh "$db" public=tests/data/polygons.tsv.gz
psql -X -q -v ON_ERROR_STOP=1 -d "$db" <<'SQL'
-- the polygons of at most 5,000 vertices (the rest are minutes of encoding a transaction)
CREATE TABLE src AS SELECT row_number() OVER (ORDER BY name) AS id, name, geom FROM coast WHERE npoints <= 5000;
CREATE TABLE store(id bigserial PRIMARY KEY, src int, ct circletree);
INSERT INTO store(src, ct) SELECT id, ct_encode_within(geom, 25) FROM src;
SQL
n=$(psql -X -At -d "$db" -c "SELECT count(*) FROM src")
dir=$(mktemp -d)
cat >"$dir/encode_within.sql" <<SQL
\set id random(1, $n)
INSERT INTO store(src, ct) SELECT id, ct_encode_within(geom, 10) FROM src WHERE id = :id;
SQL
cat >"$dir/encode.sql" <<SQL
\set id random(1, $n)
INSERT INTO store(src, ct) SELECT id, ct_encode(geom, 10, 0.4, 20) FROM src WHERE id = :id;
SQL
cat >"$dir/decode.sql" <<SQL
\set id random(1, $n)
SELECT ST_NPoints(ct_decode(ct)) FROM store WHERE src = :id LIMIT 1;
SQL
cat >"$dir/metrics.sql" <<SQL
\set id random(1, $n)
SELECT ct_hausdorff(s.ct, g.geom), ct_sliver_error(s.ct, g.geom) FROM store s JOIN src g ON g.id = s.src WHERE s.src = :id LIMIT 1;
SQL
chmod -R a+rX "$dir"
# sample each pgbench backend's peak RSS a few seconds before the end
(
  sleep $((secs > 10 ? secs - 5 : secs / 2))
  for pid in $(psql -X -At -d "$db" -c "SELECT pid FROM pg_stat_activity WHERE application_name = 'pgbench'"); do
    awk '/VmHWM/ {print $2}' "/proc/$pid/status" 2>/dev/null
  done >"$dir/hwm"
) &
sampler=$!
echo "== pgbench: $clients clients, ${secs}s"
pgbench -n -c "$clients" -j "$clients" -T "$secs" -d "$db" \
  -f "$dir/encode_within.sql@2" -f "$dir/encode.sql@1" -f "$dir/decode.sql@4" -f "$dir/metrics.sql@1" \
  2>&1 | grep -E "transaction type|number of (transactions|failed)|latency average|tps|SQL script|weight|- number" || true
wait "$sampler" || true
if [ -s "$dir/hwm" ]; then
  sort -n "$dir/hwm" | awk '{a[NR]=$1} END {printf "peak RSS per backend (VmHWM): min %d MB, median %d MB, max %d MB over %d backends\n", a[1]/1024, a[int((NR+1)/2)]/1024, a[NR]/1024, NR}'
fi
psql -X -q -v ON_ERROR_STOP=1 -d "$db" <<'SQL'
\echo == every stored row decodes to a valid polygon
SELECT count(*) AS rows, count(*) FILTER (WHERE ST_IsValid(ct_decode(ct))) AS valid FROM store;
\echo == a parallel scan that encodes gives the serial bytes
SET max_parallel_workers_per_gather = 0;
CREATE TEMP TABLE serial AS SELECT id, ct_encode_within(geom, 10)::bytea AS b FROM src;
SET max_parallel_workers_per_gather = 2;
SET parallel_setup_cost = 0;
SET parallel_tuple_cost = 0;
SET min_parallel_table_scan_size = 0;
EXPLAIN (COSTS off) SELECT id, ct_encode_within(geom, 10)::bytea FROM src;
CREATE TEMP TABLE parallel AS SELECT id, ct_encode_within(geom, 10)::bytea AS b FROM src;
SELECT count(*) AS rows, bool_and(s.b = p.b) AS same_bytes FROM serial s JOIN parallel p USING (id);
SQL
rm -rf "$dir"
