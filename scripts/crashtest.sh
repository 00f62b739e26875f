#!/usr/bin/env bash
# Crash recovery (issue 9 item 4): a throwaway cluster is killed (`pg_ctl stop -m immediate`, no
# checkpoint, no clean shutdown) while one session inserts encoded rows one committed transaction at
# a time and another holds a large uncommitted INSERT. After WAL recovery: every insert the server
# acknowledged is there, none of the uncommitted rows is, every stored value has exactly the bytes a
# fresh encode of its source gives and decodes to a valid polygon, and the indexes pass amcheck.
# Needs the extension installed; the cluster is removed on exit.
#   bash scripts/crashtest.sh [SECONDS_BEFORE_THE_KILL]
set -euo pipefail
cd "$(dirname "$0")/.."
as_root() { if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi; }
secs=${1:-10}
port=5443
cluster="ct$port"
work=$(mktemp -d)
chmod a+rwx "$work"
cleanup() {
  as_root pg_dropcluster --stop 15 "$cluster" >/dev/null 2>&1 || true
  rm -rf "$work"
}
trap cleanup EXIT
as_root pg_dropcluster --stop 15 "$cluster" >/dev/null 2>&1 || true
as_root pg_createcluster 15 "$cluster" --port "$port" -- --auth-local=trust >/dev/null 2>&1
as_root pg_ctlcluster 15 "$cluster" start
q() { as_root runuser -u postgres -- psql -X -q -v ON_ERROR_STOP=1 -h /var/run/postgresql -p "$port" -d crash "$@"; }
as_root runuser -u postgres -- createdb -h /var/run/postgresql -p "$port" crash
gzip -dc tests/data/polygons.tsv.gz | awk -F'\t' 'NR > 1 && $4 <= 5000 {print $1 "\t" $3 "\t" $5}' >"$work/src.tsv"
chmod a+r "$work/src.tsv"
q <<SQL
SET client_min_messages = warning;
CREATE EXTENSION circletree CASCADE;
CREATE EXTENSION amcheck;
CREATE TEMP TABLE raw(name text, srid int, wkt text);
\copy raw FROM '$work/src.tsv' WITH (FORMAT text)
CREATE TABLE src AS SELECT row_number() OVER (ORDER BY name)::int AS id, ST_GeomFromText(wkt, srid) AS geom FROM raw;
CREATE TABLE store(id int PRIMARY KEY, src int NOT NULL, ct circletree NOT NULL);
CREATE INDEX ON store (src);
SQL
n=$(q -At -c "SELECT count(*) FROM src")
# one committed row per statement (autocommit); RETURNING prints the id once the commit is acknowledged
for i in $(seq 1 100000); do
  echo "INSERT INTO store SELECT $i, id, ct_encode_within(geom, 10) FROM src WHERE id = $(( i % n + 1 )) RETURNING id;"
done >"$work/inserts.sql"
chmod a+r "$work/inserts.sql"
as_root runuser -u postgres -- stdbuf -oL psql -X -q -At -h /var/run/postgresql -p "$port" -d crash \
  -f "$work/inserts.sql" >"$work/acked" 2>"$work/inserts.err" &
writer=$!
# a bulk insert that never commits: none of its rows may survive
as_root runuser -u postgres -- psql -X -q -h /var/run/postgresql -p "$port" -d crash \
  -c "BEGIN" \
  -c "INSERT INTO store SELECT 1000000 + g * 100 + id, id, ct_encode(geom, 5, 0.4, 10) FROM src, generate_series(1, 50) g" \
  -c "SELECT pg_sleep(3600)" >/dev/null 2>&1 &
bulk=$!
sleep "$secs"
echo "== killing the server (pg_ctl stop -m immediate) after ${secs}s"
as_root pg_ctlcluster 15 "$cluster" stop -m immediate
wait "$writer" 2>/dev/null || true
wait "$bulk" 2>/dev/null || true
acked=$(grep -c '^[0-9]' "$work/acked" || true)
echo "acknowledged commits before the kill: $acked"
as_root pg_ctlcluster 15 "$cluster" start
grep -c '^[0-9]' "$work/acked" >/dev/null || { echo "no insert was acknowledged: nothing was tested"; exit 1; }
grep '^[0-9]' "$work/acked" | awk '{print $1}' >"$work/acked_ids"
chmod a+r "$work/acked_ids"
result=$(q -At <<SQL
CREATE TEMP TABLE acked(id int);
\copy acked FROM '$work/acked_ids'
SELECT (SELECT count(*) FROM acked) || ' ' ||
       (SELECT count(*) FROM acked a WHERE NOT EXISTS (SELECT FROM store s WHERE s.id = a.id)) || ' ' ||
       (SELECT count(*) FROM store) || ' ' ||
       (SELECT count(*) FROM store WHERE id >= 1000000) || ' ' ||
       (SELECT count(*) FROM store s JOIN src g ON g.id = s.src
         WHERE s.ct::bytea = ct_encode_within(g.geom, 10)::bytea AND ST_IsValid(ct_decode(s.ct))) || ' ' ||
       (SELECT count(*) FROM store WHERE pg_column_size(ct) > 2000);
SELECT bt_index_check(c.oid, true) FROM pg_index i JOIN pg_class c ON c.oid = i.indexrelid
 WHERE i.indrelid = 'store'::regclass;
SQL
)
read -r nacked missing stored uncommitted good toasted <<<"$(echo "$result" | head -1)"
echo "after recovery: $stored rows stored, $missing of $nacked acknowledged missing, $uncommitted uncommitted rows present, $good rows with the bytes of a fresh encode and a valid decode, $toasted of them over 2 kB (TOASTed), indexes pass bt_index_check"
[ "$missing" = 0 ] && [ "$uncommitted" = 0 ] && [ "$good" = "$stored" ] && [ "$stored" -ge "$nacked" ] || {
  echo "crash recovery lost or changed data"
  exit 1
}
echo "crash recovery: nothing committed lost"
