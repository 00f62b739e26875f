#!/usr/bin/env bash
# Create database $1 afresh with circletree (CASCADE: PostGIS too) and load polygon files of
# tests/data into it, as table coast(dataset, family, name, source, npoints, geom). Each further
# argument is dataset=file, e.g. `public=tests/data/polygons.tsv.gz holdout=tests/data/holdout.tsv.gz`
# (gzip or plain TSV: name, source, srid, npoints, wkt). Used by scripts/demo.sh and scripts/bench.sh;
# expects scripts/setup.sh to have run (a cluster on PGHOST, a superuser role).
set -euo pipefail
db=$1
shift
psql -X -q -d postgres -c "DROP DATABASE IF EXISTS $db" -c "CREATE DATABASE $db"
{
  echo "SET client_min_messages = warning;"
  echo "CREATE EXTENSION circletree CASCADE;"
  echo "CREATE TABLE poly(dataset text, name text, source text, srid int, npoints int, wkt text);"
  echo "CREATE TEMP TABLE raw(name text, source text, srid int, npoints int, wkt text);"
  for arg in "$@"; do
    dataset=${arg%%=*}
    file=${arg#*=}
    case "$file" in
      *.gz) src="PROGRAM 'gzip -dc $file'" ;;
      *) src="'$file'" ;;
    esac
    echo "\\copy raw FROM $src WITH (FORMAT csv, DELIMITER E'\\t', HEADER true, QUOTE E'\\x01')"
    echo "INSERT INTO poly SELECT '$dataset', * FROM raw; TRUNCATE raw;"
  done
  cat <<'SQL'
CREATE TABLE coast AS
SELECT dataset, CASE WHEN source LIKE 'GSHHG%' THEN 'GSHHG' WHEN source LIKE 'LINZ%' THEN 'LINZ' ELSE 'Stats NZ' END AS family,
       name, source, npoints, ST_GeomFromText(wkt, srid) AS geom
  FROM poly;
DROP TABLE poly;
SQL
} | psql -X -q -v ON_ERROR_STOP=1 -d "$db"
