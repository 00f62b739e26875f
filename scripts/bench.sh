#!/usr/bin/env bash
# Regenerates BENCHMARKS.md (and docs/paper_experiment.svg) from this commit: release build and
# install into the local PostgreSQL 15, load the 55 public polygons and the 27 held-out ones, run
# bench/benchmarks.sql and bench/in_place.sql (sizes and errors of ct_encode_within and ct_encode against ST_Simplify and
# ST_SimplifyPreserveTopology + TWKB, the paper's experiment, speed against PostGIS's functions, joins in place),
# the core's bytes_breakdown (format v1 against v2, where the bytes go) and decode_speed (v1
# against v2) examples, time both encoders alone on one synthetic coastline of 1e3 .. 1e6 vertices
# (time, the best of three runs, and peak memory), then write the report with scripts/bench_report.py (LZMA2 of every TWKB
# value computed there). About 5 minutes after the build.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup.sh

echo "== building and installing circletree (release)"
cargo pgrx install --release --pg-config "$PG_CONFIG" </dev/null
cargo build --release -q -p circletree-core --example scaling --example bytes_breakdown \
  --example decode_speed </dev/null

out=$(mktemp -d)
db=circletree_bench
bash scripts/load.sh "$db" public=tests/data/polygons.tsv.gz holdout=tests/data/holdout.tsv.gz
start=$(date +%s)
psql -X -q -v ON_ERROR_STOP=1 -d "$db" -f bench/benchmarks.sql
for t in bench_rows bench_sweep bench_speed; do
  psql -X -q -v ON_ERROR_STOP=1 -d "$db" -c "\\copy $t TO STDOUT WITH (FORMAT csv, HEADER true)" >"$out/$t.csv"
done
psql -X -q -v ON_ERROR_STOP=1 -d "$db" -f bench/in_place.sql
psql -X -q -v ON_ERROR_STOP=1 -d "$db" -c "\\copy ip_times TO STDOUT WITH (FORMAT csv, HEADER true)" >"$out/in_place.csv"
psql -X -q -v ON_ERROR_STOP=1 -d "$db" -c "\\copy ip_mem TO STDOUT WITH (FORMAT csv, HEADER true)" >"$out/in_place_mem.csv"
echo "== many small polygons beside the large ones (bench/small.sql)"
bash scripts/load.sh circletree_bench_small public=tests/data/polygons.tsv.gz holdout=tests/data/holdout.tsv.gz small=tests/data/small.tsv.gz
psql -X -q -v ON_ERROR_STOP=1 -d circletree_bench_small -f bench/small.sql | tee "$out/small.txt"
echo "== SQL benchmarks took $(($(date +%s) - start)) s"

echo "== format v1 against v2, where the bytes go (core example bytes_breakdown)"
target/release/examples/bytes_breakdown 10 25 100 >"$out/breakdown.csv"
echo "== decode speed, v1 against v2 (core example decode_speed)"
target/release/examples/decode_speed 10 25 100 | tee "$out/decode_speed.md"

echo "== scaling: encode one synthetic coastline (time and peak memory), both encoders, best of 3"
echo "encoder,n,seconds,peak_kb,circles,bytes,wkb" >"$out/scaling.csv"
for encoder in ct_encode ct_encode_within; do
  for n in 1000 10000 100000 1000000; do
    lines=""
    for run in 1 2 3; do
      if [ "$encoder" = ct_encode_within ]; then
        line=$(CT_WITHIN=1 /usr/bin/time -f "TIME %e %M" target/release/examples/scaling "$n" 2>&1)
      else
        line=$(/usr/bin/time -f "TIME %e %M" target/release/examples/scaling "$n" 2>&1)
      fi
      echo "$encoder $line"
      lines+="$line"$'\n'
    done
    python3 - "$encoder" "$lines" >>"$out/scaling.csv" <<'PY'
import re, sys
# the fastest of the runs (this machine's speed drifts); the largest peak of them
found = re.findall(r"n=\s*(\d+) time=([\d.]+)s circles=(\d+) .*?bytes=(\d+) wkb=(\d+).*?\nTIME [\d.]+ (\d+)",
                   sys.argv[2], re.S)
assert len(found) == 3, sys.argv[2]
n, _, circles, size, wkb, _ = found[0]
secs = min(float(f[1]) for f in found)
peak = max(int(f[5]) for f in found)
print(f"{sys.argv[1]},{n},{secs:.3f},{peak},{circles},{size},{wkb}")
PY
  done
done

{
  echo "commit=$(git rev-parse --short HEAD)$(git diff --quiet HEAD -- . ':!BENCHMARKS.md' ':!docs/paper_experiment.svg' || echo '+changes')"
  echo "cpu=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
  echo "cores=$(nproc)"
  echo "postgres=$(psql -X -At -d "$db" -c 'SHOW server_version')"
  echo "postgis=$(psql -X -At -d "$db" -c 'SELECT postgis_lib_version()')"
  echo "geos=$(psql -X -At -d "$db" -c 'SELECT postgis_geos_version()')"
  echo "rustc=$(rustc --version)"
  echo "date=$(date -u +%Y-%m-%d)"
} >"$out/machine.txt"
python3 scripts/bench_report.py "$out"
echo "== wrote BENCHMARKS.md and docs/paper_experiment.svg (raw CSV in $out)"
