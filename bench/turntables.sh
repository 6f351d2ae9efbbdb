#!/usr/bin/env bash
# Close turntables of the species and demo presets for the README (issue [2/6] item 9):
# scenes/gallery/turntable_<preset>.png, 4 views of 256² each. Usage: bench/turntables.sh [build dir]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
for n in picea_abies pinus_sylvestris larix_decidua betula_pendula fagus_sylvatica salix_alba \
         ulmus_laevis populus_trichocarpa acer_campestre quercus_robur broadleaf conifer; do
  "$build/forest" generate --species "$root/scenes/species/$n.toml" --out "$tmp/$n.glb" > /dev/null
  "$build/forest" preview "$tmp/$n.glb" --out "$root/scenes/gallery/turntable_$n.png" --views 4 --size 256
done
