#!/usr/bin/env bash
# Coverage-guided fuzzing of the core (issue 9): every cargo-fuzz target of
# crates/circletree-core/fuzz for SECONDS each (default 600), starting from the seeds in the repo
# (fuzz/seeds/<target>, read only) and a working corpus (fuzz/corpus/<target>, not committed).
# Prints, per target, libFuzzer's last status line: executions, coverage (cov: edges, ft: features),
# corpus size. A crash stops the script and leaves the input in fuzz/artifacts/<target>/.
#   bash scripts/fuzz.sh [SECONDS] [TARGET...]
set -euo pipefail
secs=${1:-600}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(decode text encode)
cd "$(dirname "$0")/../crates/circletree-core"
if ! cargo +nightly --version >/dev/null 2>&1; then
  rustup toolchain install nightly --profile minimal </dev/null
fi
if ! cargo fuzz --version >/dev/null 2>&1; then
  cargo install cargo-fuzz --locked </dev/null
fi
for t in "${targets[@]}"; do
  mkdir -p "fuzz/corpus/$t"
  log=$(mktemp)
  echo "== fuzz $t for ${secs}s"
  if ! cargo +nightly fuzz run "$t" "fuzz/corpus/$t" "fuzz/seeds/$t" -- \
      -max_total_time="$secs" -rss_limit_mb=2048 -max_len=4096 -timeout=20 -print_final_stats=1 \
      >"$log" 2>&1 </dev/null; then
    tail -40 "$log"
    echo "fuzz $t FAILED (input in crates/circletree-core/fuzz/artifacts/$t/)"
    exit 1
  fi
  grep -E '^#[0-9]+' "$log" | tail -1
  grep -E '^stat::(number_of_executed_units|average_exec_per_sec|peak_rss_mb)' "$log" || true
  rm -f "$log"
done
