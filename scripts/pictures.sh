#!/usr/bin/env bash
# Regenerate the pictures in docs/pictures with ct_svg (README and docs/ALGORITHM.md show them):
# Kapiti Island (LINZ 1:50k, the paper's test island) encoded by the paper's method at (5, 0.4, 10)
# and by ct_encode_within at 10 m, each over the original. Needs the extension installed and the
# sample polygons loaded (scripts/load.sh), as scripts/demo.sh leaves them.
#   bash scripts/pictures.sh [DATABASE]
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup.sh
db=${1:-circletree_pictures}
if [ $# -eq 0 ]; then
  bash scripts/load.sh "$db" samples=tests/data/samples.tsv
fi
mkdir -p docs/pictures
pic() {
  psql -X -At -v ON_ERROR_STOP=1 -d "$db" -c "$2" >"docs/pictures/$1.svg"
  echo "docs/pictures/$1.svg: $(wc -c <"docs/pictures/$1.svg") bytes"
}
pic kapiti_paper "SELECT ct_svg(ct_encode(geom, 5, 0.4, 10), geom, 800) FROM coast WHERE name = 'kapiti_island_linz'"
pic kapiti_within "SELECT ct_svg(ct_encode_within(geom, 10), geom, 800) FROM coast WHERE name = 'kapiti_island_linz'"
pic kapiti_paper_coarse "SELECT ct_svg(ct_encode(geom, 50, 0.4, 100), geom, 800) FROM coast WHERE name = 'kapiti_island_linz'"
# the tangent cases: inside to inside, inside to outside, outside to outside, outside to a point,
# a point to inside (a value written in the text form)
pic tangent_cases "SELECT ct_svg('CIRCLETREE(version=2;grid=1;min_radius=1;overlap=0.4;dp_tolerance=NULL;max_error=1;vertices=5;wkb_bytes=93;repaired=0;bbox=(-100 -50,430 310);POLYGON((0 0 40,300 0 40,380 160 -40,150 260 -40,-60 200 0)))'::circletree, NULL, 500)"
