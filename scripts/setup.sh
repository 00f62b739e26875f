#!/usr/bin/env bash
# Idempotent set-up of a fresh Debian 12 machine for circletree: Debian packages, cargo-pgrx 0.18.1, cargo-deny,
# pgrx registered against the system PostgreSQL 15, a running cluster with a superuser role for the
# current user. Sourced by scripts/demo.sh and scripts/test.sh; safe to run again.
set -euo pipefail

PG_CONFIG=/usr/lib/postgresql/15/bin/pg_config
PGRX_VERSION=0.18.1
DENY_VERSION=0.20.2
export PG_CONFIG

as_root() { if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi; }

# rust-toolchain.toml names the tested toolchain; where stable is that version under another name,
# link it (nothing can be downloaded here).
RUST_TOOLCHAIN=$(sed -n 's/^channel = "\(.*\)"/\1/p' "$(dirname "${BASH_SOURCE[0]}")/../rust-toolchain.toml")
if ! rustup toolchain list | grep -q "^$RUST_TOOLCHAIN"; then
  if rustc +stable --version | grep -q "^rustc $RUST_TOOLCHAIN "; then
    # (`rustup toolchain link` refuses a name that looks like a release: link the folder itself)
    host=$(rustc +stable -vV | sed -n 's/^host: //p')
    ln -s "stable-$host" "${RUSTUP_HOME:-$HOME/.rustup}/toolchains/$RUST_TOOLCHAIN-$host"
  else
    echo "rust-toolchain.toml asks for $RUST_TOOLCHAIN; this machine's stable is $(rustc +stable --version)" >&2
    exit 1
  fi
fi

need_pkgs=()
for p in postgresql-15 postgresql-server-dev-15 postgresql-15-postgis-3 libclang-dev clang \
         build-essential pkg-config libssl-dev sudo gdal-bin; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || need_pkgs+=("$p")
done
if [ ${#need_pkgs[@]} -gt 0 ]; then
  echo "== installing Debian packages: ${need_pkgs[*]}"
  as_root env DEBIAN_FRONTEND=noninteractive apt-get update -q
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${need_pkgs[@]}" </dev/null
fi

if ! cargo pgrx --version 2>/dev/null | grep -q "$PGRX_VERSION"; then
  echo "== installing cargo-pgrx $PGRX_VERSION (several minutes on 2 cores)"
  cargo install cargo-pgrx --version "$PGRX_VERSION" --locked </dev/null
fi

if ! cargo deny --version 2>/dev/null | grep -q "$DENY_VERSION"; then
  echo "== installing cargo-deny $DENY_VERSION (several minutes on 2 cores)"
  cargo install cargo-deny --version "$DENY_VERSION" --locked </dev/null
fi

if ! grep -qs "pg15" "${PGRX_HOME:-$HOME/.pgrx}/config.toml"; then
  echo "== registering the system PostgreSQL 15 with pgrx"
  cargo pgrx init --pg15 "$PG_CONFIG" </dev/null
fi

# A running cluster on port 5432 with a superuser role for whoever runs this (Debian uses peer auth).
if ! pg_lsclusters -h 2>/dev/null | grep -q '^15 \+main'; then
  as_root pg_createcluster 15 main
fi
if ! pg_lsclusters -h | grep -q '^15 \+main .* online'; then
  as_root pg_ctlcluster 15 main start
fi
me=$(id -un)
as_root runuser -u postgres -- psql -Xq -v ON_ERROR_STOP=1 -c "DO \$\$BEGIN IF NOT EXISTS (SELECT FROM pg_roles WHERE rolname='$me') THEN CREATE ROLE \"$me\" SUPERUSER LOGIN; END IF; END\$\$" </dev/null
export PGHOST=/var/run/postgresql PGPORT=5432
