#!/usr/bin/env bash
# Print the regress file tests/pg_regress/sql/readme.sql from README.md: every ```sql block that follows
# a `<!-- tested -->` line, verbatim, in order. scripts/test.sh fails when the committed file differs, so the
# README's SQL is what the regress test `readme` runs (and its output is compared).
#   bash scripts/readme_sql.sh > tests/pg_regress/sql/readme.sql
set -euo pipefail
cd "$(dirname "$0")/.."
echo "-- Generated from README.md by scripts/readme_sql.sh (the README's tested SQL blocks); do not edit."
awk '
  /^<!-- tested -->$/ { armed = 1; next }
  armed && /^```sql$/ { inblock = 1; armed = 0; next }
  inblock && /^```$/ { inblock = 0; next }
  inblock { print }
  !/^[[:space:]]*$/ { armed = 0 }
' README.md
