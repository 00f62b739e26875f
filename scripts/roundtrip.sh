#!/usr/bin/env bash
# Nothing lost in a round trip (issue 9 item 5): values written by ct_encode, ct_encode_within and the
# text form (format versions 1 and 2) go through pg_dump/pg_restore (custom format) and through
# logical replication with binary = true (the initial COPY and streamed inserts) between two throwaway
# clusters on this machine; the bytes on the far side must equal the bytes sent. Run by scripts/test.sh
# after the extension is installed; the clusters are removed on exit.
set -euo pipefail
cd "$(dirname "$0")/.."
as_root() { if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi; }
pub=5441
sub=5442
cleanup() {
  for port in $pub $sub; do
    as_root pg_dropcluster --stop 15 "ct$port" >/dev/null 2>&1 || true
  done
}
trap cleanup EXIT
cleanup
for port in $pub $sub; do
  as_root pg_createcluster 15 "ct$port" --port "$port" -- --auth-local=trust >/dev/null 2>&1
  as_root pg_conftool 15 "ct$port" set wal_level logical
  as_root pg_ctlcluster 15 "ct$port" start
done
q() { as_root runuser -u postgres -- psql -X -q -v ON_ERROR_STOP=1 -h /var/run/postgresql -p "$1" -d "$2" "${@:3}"; }
for port in $pub $sub; do
  q "$port" postgres -c "CREATE DATABASE rt"
  q "$port" rt -c "SET client_min_messages = warning" -c "CREATE EXTENSION circletree CASCADE"
  q "$port" rt -c "CREATE TABLE v(id int PRIMARY KEY, ct circletree)"
done
gzip -dc tests/data/polygons.tsv.gz | awk -F'\t' 'NR > 1 && $4 <= 3000 {print $1 "\t" $3 "\t" $5}' >/tmp/circletree_rt.tsv
chmod a+r /tmp/circletree_rt.tsv
q $pub rt <<'SQL'
CREATE TEMP TABLE raw(name text, srid int, wkt text);
\copy raw FROM '/tmp/circletree_rt.tsv' WITH (FORMAT text)
INSERT INTO v SELECT row_number() OVER (ORDER BY name), ct_encode_within(ST_GeomFromText(wkt, srid), 10) FROM raw;
INSERT INTO v SELECT 1000 + row_number() OVER (ORDER BY name), ct_encode(ST_GeomFromText(wkt, srid), 5, 0.4, 10) FROM raw;
INSERT INTO v VALUES (2001, 'SRID=32760;CIRCLETREE(grid=0.5;min_radius=5;overlap=0.4;dp_tolerance=NULL;max_error=5;vertices=5;wkb_bytes=93;repaired=0;bbox=(0 0,10 10);POLYGON((5 5 5,8 5 0,8 8 -1)))'),
                     (2002, 'SRID=4326;CIRCLETREE(version=2;grid=1;min_radius=1;overlap=0.4;dp_tolerance=NULL;max_error=1;vertices=0;wkb_bytes=9;repaired=0;POLYGON EMPTY)');
CREATE PUBLICATION p FOR TABLE v;
SQL
sent=$(q $pub rt -At -c "SELECT count(*) || ' ' || md5(string_agg(ct::bytea::text, ',' ORDER BY id)) FROM v")
echo "sent: $sent (rows, md5 of the bytes)"

# pg_dump / pg_restore, custom format
q $pub postgres -c "CREATE DATABASE restored"
as_root runuser -u postgres -- pg_dump -h /var/run/postgresql -p $pub -Fc -d rt -f /tmp/circletree_rt.dump
as_root runuser -u postgres -- pg_restore -h /var/run/postgresql -p $pub -d restored /tmp/circletree_rt.dump
restored=$(q $pub restored -At -c "SELECT count(*) || ' ' || md5(string_agg(ct::bytea::text, ',' ORDER BY id)) FROM v")
echo "pg_dump/pg_restore: $restored"

# logical replication, binary = true: the initial table copy (PostgreSQL 15 copies it as text: the text
# form, circletree_out/in), then rows streamed after it (binary: circletree_send/recv)
q $sub rt -c "CREATE SUBSCRIPTION s CONNECTION 'host=/var/run/postgresql port=$pub dbname=rt user=postgres' PUBLICATION p WITH (binary = true)"
q $pub rt -c "INSERT INTO v SELECT id + 5000, ct FROM v WHERE id < 1000"
want=$(q $pub rt -At -c "SELECT count(*) || ' ' || md5(string_agg(ct::bytea::text, ',' ORDER BY id)) FROM v")
got=""
for _ in $(seq 1 60); do
  got=$(q $sub rt -At -c "SELECT count(*) || ' ' || md5(string_agg(ct::bytea::text, ',' ORDER BY id)) FROM v")
  [ "$got" = "$want" ] && break
  sleep 1
done
echo "logical replication (binary = true): $got"
valid=$(q $sub rt -At -c "SELECT count(*) FILTER (WHERE NOT ST_IsValid(ct_decode(ct))) FROM v")
fail=0
[ "$restored" = "$sent" ] || { echo "FAIL: pg_restore changed the values"; fail=1; }
[ "$got" = "$want" ] || { echo "FAIL: the subscriber has other values than the publisher ($want)"; fail=1; }
[ "$valid" = 0 ] || { echo "FAIL: $valid replicated values do not decode valid"; fail=1; }
[ $fail = 0 ] && echo "round trips: every value arrived byte for byte"
exit $fail
