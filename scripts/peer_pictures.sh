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
cp "$root/tests/tools/three_render.html" "$root/build/npm/three_render.html"
page="file://$root/build/npm/three_render.html"
# One three.js picture of QUERY (file=... or eztree=...) to PNG; prints its triangle count.
# One --dump-dom run gives both, from the same finished page (three_render.html ?dump=1); a
# run whose page had not finished (no title) is tried again, twice at most.
three() {
  local query="$1" png="$2" dom
  for attempt in 1 2 3; do
    dom=$(chromium --headless --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader \
      --allow-file-access-from-files --virtual-time-budget=60000 --window-size="$size,$size" \
      --dump-dom "$page?$query&size=$size&dump=1" 2>/dev/null || true)
    if [[ "$dom" == *"<title>rendered: "* && "$dom" == *'<pre id="png">data:image/png;base64,'* ]]; then
      sed -n 's/.*<pre id="png">data:image\/png;base64,\([^<]*\)<\/pre>.*/\1/p' <<<"$dom" | base64 -d >"$png"
      sed -n 's/.*<title>rendered: \([0-9]*\) triangles<\/title>.*/\1/p' <<<"$dom"
      return 0
    fi
  done
  echo "peer_pictures: three.js did not finish $query" >&2
  return 1
}
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
