#!/usr/bin/env bash
# A real client reads circletree through a view (issue 40 item 6): GDAL's PostgreSQL driver
# (`ogr2ogr` from Debian's gdal-bin) copies a view `SELECT name, ct::geometry AS geom FROM ...` into a
# GeoPackage, and back into PostgreSQL from the GeoPackage; every feature must come back, with its
# geometry's bytes equal to ct_decode's. Run by scripts/test.sh after the extension is installed;
# expects scripts/setup.sh to have run. The database and the file are removed on exit.
set -euo pipefail
cd "$(dirname "$0")/.."
db=circletree_clients
gpkg=$(mktemp -d)/coast.gpkg
cleanup() { psql -X -q -d postgres -c "DROP DATABASE IF EXISTS $db" >/dev/null 2>&1 || true; rm -rf "$(dirname "$gpkg")"; }
trap cleanup EXIT
bash scripts/load.sh "$db" public=tests/data/polygons.tsv.gz holdout=tests/data/holdout.tsv.gz
psql -X -q -v ON_ERROR_STOP=1 -d "$db" <<'SQL'
CREATE TABLE coast_ct AS SELECT dataset, name, ct_encode_within(geom, 10) AS ct, ct_encode(geom, 5, 0.4, 10) AS paper FROM coast;
-- one layer in one SRID (New Zealand's polygons, EPSG:2193), and every polygon in one layer of
-- mixed UTM zones (a GeoPackage layer has one SRS: the coordinates must still come back)
CREATE VIEW nz_view AS SELECT dataset || '/' || name AS name, ct::geometry AS geom FROM coast_ct WHERE ct_srid(ct) = 2193
UNION ALL SELECT dataset || '/' || name || '/paper', paper::geometry FROM coast_ct WHERE ct_srid(ct) = 2193;
CREATE VIEW all_view AS SELECT dataset || '/' || name AS name, ct::geometry AS geom FROM coast_ct
UNION ALL SELECT dataset || '/' || name || '/paper', paper::geometry FROM coast_ct;
SQL
echo "== ogr2ogr: view -> GeoPackage -> table ($(ogr2ogr --version))"
for view in nz_view all_view; do
  ogr2ogr -f GPKG "$gpkg" "PG:dbname=$db" "$view" -nln "$view" $( [ -e "$gpkg" ] && echo -update )
  ogrinfo -so "$gpkg" "$view" | grep -E "^Feature Count|^Geometry:|^    ID\[\"EPSG\""  | sed "s/^/  $view: /" || true
  ogr2ogr -f PostgreSQL "PG:dbname=$db" "$gpkg" "$view" -nln "${view%_view}_back" -lco GEOMETRY_NAME=geom -lco FID=fid
done
psql -X -q -v ON_ERROR_STOP=1 -d "$db" <<'SQL'
\pset footer off
SELECT 'nz_view (EWKB, SRID included)' AS layer, count(v.*) AS in_view, count(b.*) AS came_back,
       count(*) FILTER (WHERE ST_AsEWKB(b.geom) = ST_AsEWKB(v.geom)) AS same_bytes
  FROM nz_view v FULL JOIN nz_back b USING (name)
UNION ALL
SELECT 'all_view (WKB, coordinates)', count(v.*), count(b.*), count(*) FILTER (WHERE ST_AsBinary(b.geom) = ST_AsBinary(v.geom))
  FROM all_view v FULL JOIN all_back b USING (name);
DO $$
BEGIN
  IF EXISTS (SELECT FROM nz_view v FULL JOIN nz_back b USING (name) WHERE ST_AsEWKB(b.geom) IS DISTINCT FROM ST_AsEWKB(v.geom))
     OR EXISTS (SELECT FROM all_view v FULL JOIN all_back b USING (name) WHERE ST_AsBinary(b.geom) IS DISTINCT FROM ST_AsBinary(v.geom))
     OR (SELECT count(*) FROM all_view) <> 2 * (SELECT count(*) FROM coast_ct)
     OR (SELECT count(*) FROM nz_view) < 2 THEN
    RAISE EXCEPTION 'a feature did not come back through ogr2ogr with ct_decode''s geometry';
  END IF;
END $$;
SQL
echo "every feature came back with ct_decode's geometry"
