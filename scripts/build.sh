#!/usr/bin/env bash
# Configures and builds forest into build/ (Release with debug info, Ninja).
set -euo pipefail
cd "$(dirname "$0")/.."
# ccache across checkouts: paths below the source folder hash as relative ones, and the
# working folder is not hashed, so a fresh clone elsewhere reuses what another clone compiled.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}" CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-true}"
if [[ ! -f build/build.ninja ]]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
fi
ninja -C build "$@"
