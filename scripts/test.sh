#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test: fuzzing (clang, ASan + UBSan), the
# unit and CLI tests under ASan + UBSan (gcc), then GPU tests on lavapipe with the Khronos
# validation layer, glTF-Validator, the export clients (three.js, Blender) and the deploy
# tests in the ordinary build. Ends with ctest's summary line.
set -euo pipefail
cd "$(dirname "$0")/.."
# ccache across checkouts: paths below the source folder hash as relative ones, and the
# working folder is not hashed, so a fresh clone elsewhere reuses what another clone compiled.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}" CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-true}"


scripts/install-deps.sh --test

# Khronos glTF-Validator from npm, pinned by tests/tools/package-lock.json.
mkdir -p build/npm
if ! cmp -s tests/tools/package-lock.json build/npm/package-lock.json || [[ ! -d build/npm/node_modules/gltf-validator ]]; then
  cp tests/tools/package.json tests/tools/package-lock.json build/npm/
  (cd build/npm && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
fi

build_start=$(date +%s)
scripts/build.sh
echo "test.sh: build took $(( $(date +%s) - build_start )) s"

# Pin lavapipe where a machine has several drivers, unless the caller chose a device.
if [[ -z "${VK_DRIVER_FILES:-}${VK_ICD_FILENAMES:-}${FOREST_DEVICE:-}" && -f /usr/share/vulkan/icd.d/lvp_icd.x86_64.json ]]; then
  export VK_DRIVER_FILES=/usr/share/vulkan/icd.d/lvp_icd.x86_64.json
fi
export FOREST_VALIDATION=1

# CI-sized fuzzing of every loader of untrusted input (clang, ASan + UBSan, build-fuzz/):
# FOREST_FUZZ_SECONDS per target (default 35, ~4 min in all; 0 skips it).
fuzz_status=0
if [[ "${FOREST_FUZZ_SECONDS:-35}" != 0 ]]; then
  scripts/fuzz.sh "${FOREST_FUZZ_SECONDS:-35}" || fuzz_status=$?
fi

# The unit and CLI tests under ASan + UBSan (gcc -O1, build-asan/, the asan preset): every
# run. The CLI tests drive the instrumented `forest` through bakes, renders, the cache and
# export on lavapipe. FOREST_ASAN=0 skips; the whole suite under ASan (GPU tests too) is
# `cmake --workflow --preset asan` (README, Hardening).
asan_status=0
if [[ "${FOREST_ASAN:-1}" != 0 ]]; then
  asan_start=$(date +%s)
  [[ -f build-asan/build.ninja ]] || cmake --preset asan >/dev/null
  if ! cmake --build build-asan --target unit_tests cli_tests forest >build-asan/build.log 2>&1; then
    tail -n 40 build-asan/build.log
    asan_status=1
  elif ! ctest --preset asan -R '^(unit|cli)\.' -j"$(nproc)" >build-asan/ctest.log 2>&1; then
    tail -n 200 build-asan/ctest.log
    asan_status=1
  else
    echo "test.sh: ASan + UBSan: $(grep -E 'tests passed' build-asan/ctest.log)"
  fi
  echo "test.sh: ASan + UBSan unit and CLI tests took $(( $(date +%s) - asan_start )) s (log: build-asan/ctest.log)"
fi

# Everything else in the ordinary build (GPU, clients, validator, deploy). The unit and CLI
# tests ran above, from the same sources under the sanitizers (gcc at -O1 against -O2, no
# fast-math: the same arithmetic); with FOREST_ASAN=0 they run here instead.
cd build
skip=()
[[ "${FOREST_ASAN:-1}" == 0 ]] || skip=(-E '^(unit|cli)\.')
ctest_status=0
ctest --output-on-failure -j"$(nproc)" "${skip[@]}" "$@" || ctest_status=$?
[[ $fuzz_status -eq 0 ]] || echo "test.sh: fuzzing found a failure (see above; inputs in build-fuzz/artifacts/)"
[[ $asan_status -eq 0 ]] || echo "test.sh: the ASan + UBSan unit and CLI tests failed (above; build-asan/ctest.log)"
[[ $fuzz_status -eq 0 && $asan_status -eq 0 && $ctest_status -eq 0 ]]
