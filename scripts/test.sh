#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test (unit, GPU on lavapipe with the
# Khronos validation layer, CLI, glTF-Validator). Ends with ctest's summary line.
set -euo pipefail
cd "$(dirname "$0")/.."


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

cd build
ctest --output-on-failure -j"$(nproc)" "$@"
[[ $fuzz_status -eq 0 ]] || { echo "test.sh: fuzzing found a failure (see above; inputs in build-fuzz/artifacts/)"; exit 1; }
