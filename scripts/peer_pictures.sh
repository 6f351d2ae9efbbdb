#!/usr/bin/env bash
# Our trees next to a peer's: ez-tree (npm @dgreenheck/ez-tree, Daniel Greenheck's procedural
# generator for three.js) against forest's presets, each drawn by the same three.js page
# (tests/tools/three_render.html: one sun with shadows, a hemisphere light, ACES, the camera
# framing the tree from the side; headless Chromium, WebGL 2 on SwiftShader), ours through
# `forest export`, and ours also in forest itself (`forest preview`, one view).
# Needs scripts/install-deps.sh --test (Chromium) and build/npm (scripts/test.sh installs it).
# Usage: scripts/peer_pictures.sh OUTDIR [SIZE]
#   writes OUTDIR/<pair>_eztree.png, <pair>_forest_three.png, <pair>_forest.png per pair and
#   OUTDIR/triangles.txt (each tree's triangles, instances counted, as three.js holds them).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
[[ $# -ge 1 ]] || { echo "usage: scripts/peer_pictures.sh OUTDIR [SIZE]" >&2; exit 2; }
out="$(realpath -m "$1")"
size=${2:-480}
forest="$root/build/forest"
[[ -d "$root/build/npm/node_modules/@dgreenheck/ez-tree" ]] ||
  { echo "peer_pictures: build/npm/node_modules/@dgreenheck/ez-tree missing (run scripts/test.sh once)" >&2; exit 2; }
mkdir -p "$out"
three() { "$root/scripts/three_picture.sh" "$1" "$2" "$size"; }
: >"$out/triangles.txt"
# Pairs: an ez-tree preset and the forest species of the same habit.
for pair in "oak:Oak Medium:quercus_robur" "pine:Pine Medium:pinus_sylvestris" "aspen:Aspen Medium:populus_trichocarpa"; do
  IFS=: read -r name preset species <<<"$pair"
  "$forest" generate --species "$root/scenes/species/$species.toml" --out "$out/$species.glb" >/dev/null
  "$forest" export "$out/$species.glb" --out "$out/${species}_export.glb" >/dev/null
  "$forest" preview "$out/$species.glb" --views 1 --size "$size" --out "$out/${name}_forest.png" >/dev/null
  ours=$(three "file=$out/${species}_export.glb" "$out/${name}_forest_three.png")
  peer=$(three "eztree=${preset// /%20}&seed=1" "$out/${name}_eztree.png")
  echo "$name: ez-tree '$preset' $peer triangles, forest $species $ours triangles (LOD0)" | tee -a "$out/triangles.txt"
done
echo "peer_pictures: $out/*_eztree.png, *_forest_three.png, *_forest.png, triangles.txt"
