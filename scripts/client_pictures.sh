#!/usr/bin/env bash
# forest export's files as other clients show them: exports MODEL.glb (instanced and
# flattened), renders LOD0 in three.js (headless Chromium, WebGL 2 on SwiftShader; instanced
# leaves), in Blender (background mode, Cycles; flattened, since Blender 3.4 lacks
# EXT_mesh_gpu_instancing) and, for comparison, in forest itself (`forest preview`, one view).
# Needs scripts/install-deps.sh --test (Blender, Chromium) and build/npm (scripts/test.sh).
# Usage: scripts/client_pictures.sh MODEL.glb OUTDIR [SIZE]
#   writes OUTDIR/<name>_forest.png, <name>_three.png, <name>_blender.png and the exports.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
[[ $# -ge 2 ]] || { echo "usage: scripts/client_pictures.sh MODEL.glb OUTDIR [SIZE]" >&2; exit 2; }
model="$(realpath "$1")"
out="$(realpath -m "$2")"
size=${3:-480}
name="$(basename "$model" .glb)"
forest="$root/build/forest"
[[ -d "$root/build/npm/node_modules/three" ]] || { echo "client_pictures: build/npm/node_modules/three missing (run scripts/test.sh once)" >&2; exit 2; }
mkdir -p "$out/instanced" "$out/flat"
"$forest" export "$model" --out "$out/instanced/$name.glb" >/dev/null
"$forest" export "$model" --out "$out/flat/$name.glb" --flatten >/dev/null
"$forest" preview "$model" --views 1 --size "$size" --out "$out/${name}_forest.png" >/dev/null
"$root/scripts/three_picture.sh" "file=$out/instanced/$name.glb" "$out/${name}_three.png" "$size" >/dev/null
# Blender takes its Python home from PATH: Debian's, whose numpy its glTF importer needs.
PATH=/usr/bin:/bin blender -b --factory-startup --python-exit-code 1 -P "$root/tests/tools/blender_render.py" -- \
  "$out/flat/$name.glb" "$out/${name}_blender.png" "$size" 32 >/dev/null
echo "client_pictures: $out/${name}_forest.png, ${name}_three.png, ${name}_blender.png"
