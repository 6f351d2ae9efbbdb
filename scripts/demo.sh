#!/usr/bin/env bash
# Installs what is missing, builds, generates the demo species as glTF assets, renders the
# demo forest headless, and says where the pictures are.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh forest

out=build/demo
mkdir -p "$out"
for species in fig2_1 broadleaf conifer; do
  build/forest generate --species "scenes/species/$species.toml" --out "$out/$species.glb"
done
build/forest render scenes/demo.toml --out "$out/demo.png" --stats

echo
echo "Demo done:"
echo "  picture:  $PWD/$out/demo.png   (scenes/demo.toml rendered headless)"
echo "  assets:   $PWD/$out/{fig2_1,broadleaf,conifer}.glb   (open in any glTF viewer or Blender)"
