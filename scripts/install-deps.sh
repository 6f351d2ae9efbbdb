#!/usr/bin/env bash
# Installs the Debian 12 packages forest needs, only those that are missing.
# Idempotent and quiet when everything is present. --test: also what only the tests use
# (a single-node Slurm for deploy/slurm's test; Blender and Chromium, the clients that
# `forest export`'s files are loaded in; scripts/test.sh passes it).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git ccache
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  glslang-tools spirv-tools spirv-cross
  libglfw3-dev libglm-dev libeigen3-dev libopenimageio-dev libmeshoptimizer-dev
  libgtest-dev libgmock-dev libexpat1-dev
  libtinygltf-dev libstb-dev libtomlplusplus-dev libcli11-dev nlohmann-json3-dev libtbb-dev
  fonts-dejavu-core
  xvfb xauth
  clang libclang-rt-14-dev
  nodejs npm
)
if [[ "${1:-}" == --test ]]; then
  packages+=(slurm-wlm munge blender python3-numpy chromium python3)
fi

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done
# node/npm may come from outside Debian (e.g. NodeSource); accept any working npm.
if command -v npm >/dev/null 2>&1 && command -v node >/dev/null 2>&1; then
  filtered=()
  for p in "${missing[@]}"; do [[ "$p" == nodejs || "$p" == npm ]] || filtered+=("$p"); done
  missing=("${filtered[@]}")
fi

[[ ${#missing[@]} -eq 0 ]] && exit 0

echo "install-deps: installing ${missing[*]}"
sudo=""
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null 2>&1 || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
