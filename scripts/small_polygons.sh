#!/usr/bin/env bash
# Extract a table of many small real polygons from GSHHG 2.3.7 full resolution (Debian's
# gmt-gshhg-full, through GMT's `gmt coast`): every island, lake, island in a lake and pond of at
# least 1 km² that lies whole inside one of GMT's bins, in the regions below. Each is transformed to
# the WGS 84 / UTM zone of its centroid, snapped to 1 cm and kept if ST_IsValid. Writes the polygon-file
# format of tests/data (name, source, srid, npoints, wkt), gzipped.
#   bash scripts/small_polygons.sh public tests/data/small.tsv.gz    (the committed set)
#   bash scripts/small_polygons.sh holdout /tmp/small_holdout.tsv.gz (other regions, not committed)
# Needs gmt and gmt-gshhg-full (apt-get install gmt gmt-gshhg-full), PostGIS in a running cluster.
set -euo pipefail
cd "$(dirname "$0")/.."
set_=$1
out=$2
case "$set_" in
  public) regions="21/30/60/64 12/21/56/60 5/15/60/66 -80/-70/48/52 -100/-90/55/60 140/150/-44/-40 -8/-4/55/59
                   -76/-70/-50/-44 25/35/64/68 -90/-80/45/50 100/110/50/56 -62/-52/46/52 -130/-120/50/56
                   -160/-150/56/62 60/70/60/66 -70/-60/58/64" ;;
  holdout) regions="-100/-90/60/66 30/40/60/64 -75/-68/40/45 115/125/-35/-30 -50/-40/60/66 170/180/60/66" ;;
  *) echo "usage: $0 public|holdout OUT.tsv.gz" >&2; exit 2 ;;
esac
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for r in $regions; do
  (cd "$tmp" && gmt coast -R"$r" -Df -W -M -A1) | python3 -c '
import sys
region = sys.argv[1].replace("/", "_")
segs = []
for line in sys.stdin:
    if line.startswith(">"):
        segs.append([line.split("Level")[1].strip(), []])
    elif line.strip():
        x, y = line.split()[:2]
        segs[-1][1].append((x, y))
i = 0
for level, pts in segs:
    # a polygon whole inside one bin comes back closed; one cut by a bin edge does not
    if len(pts) >= 4 and pts[0] == pts[-1]:
        ring = ",".join(f"{x} {y}" for x, y in pts)
        print(f"gshhg_{region}_{i}\t{level}\tPOLYGON(({ring}))")
        i += 1
' "$r"
done >"$tmp/raw.tsv"
chmod 755 "$tmp"
chmod 644 "$tmp/raw.tsv"
db=circletree_small_extract
psql -X -q -d postgres -c "DROP DATABASE IF EXISTS $db" -c "CREATE DATABASE $db"
psql -X -q -v ON_ERROR_STOP=1 -d "$db" <<SQL
SET client_min_messages = warning;
CREATE EXTENSION postgis;
CREATE TABLE raw(name text, level int, wkt text);
\\copy raw FROM '$tmp/raw.tsv' WITH (FORMAT text)
CREATE TABLE small AS
SELECT name, 'GSHHG 2.3.7 full (gmt-gshhg-full), level ' || level || ' (' ||
             CASE level WHEN 1 THEN 'island' WHEN 2 THEN 'lake' WHEN 3 THEN 'island in a lake' ELSE 'pond' END || ')' AS source,
       srid, ST_NPoints(g) AS npoints, g
  FROM (SELECT name, level, srid, ST_SnapToGrid(ST_Transform(ST_SetSRID(ST_GeomFromText(wkt), 4326), srid), 0.01) AS g
          FROM (SELECT *, CASE WHEN ST_Y(c) >= 0 THEN 32600 ELSE 32700 END + least(60, floor((ST_X(c) + 180) / 6)::int + 1) AS srid
                  FROM (SELECT *, ST_Centroid(ST_GeomFromText(wkt)) AS c FROM raw) r) s) t
 WHERE ST_IsValid(g) AND NOT ST_IsEmpty(g);
SQL
psql -X -q -d "$db" -At -c "SELECT count(*) || ' polygons, ' || (SELECT count(*) FROM raw) - count(*) || ' dropped (invalid after the 1 cm grid), median ' ||
  percentile_disc(0.5) WITHIN GROUP (ORDER BY npoints) || ' vertices, 90th percentile ' || percentile_disc(0.9) WITHIN GROUP (ORDER BY npoints) FROM small"
{
  printf 'name\tsource\tsrid\tnpoints\twkt\n'
  psql -X -q -d "$db" -At -F $'\t' -c "SELECT name, source, srid, npoints, ST_AsText(g) FROM small ORDER BY name"
} | gzip -9n >"$out"
psql -X -q -d postgres -c "DROP DATABASE $db"
echo "wrote $out"
