#!/usr/bin/env bash
# Installs what is missing, builds, generates the demo species as glTF assets, bakes one for
# pruning with its PR report, renders the demo forest headless (shaded, λ view, occlusion,
# and the PR comparison of opt vs full detail), and says where the pictures and figures are.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh forest

out=build/demo
mkdir -p "$out"
for species in fig2_1 broadleaf conifer; do
  build/forest generate --species "scenes/species/$species.toml" --out "$out/$species.glb"
done
# Hull, priority order and PR-measured λ/scale tables, then their plots (Fig 7.2, 7.9, 7.10).
build/forest bake "$out/broadleaf.glb" --out "$out/broadleaf_baked.glb" --views 3 --resolution 128
build/forest report "$out/broadleaf_baked.glb" --out "$out/report"
# The demo forest: presets are generated and baked on first use into the species cache.
build/forest render scenes/demo.toml --out "$out/demo.png" --stats
# The λ and occlusion views show what is drawn, not the light: without the sun's shadows.
build/forest render scenes/demo.toml --out "$out/demo_lambda.png" --view lambda --mode opt --shadows off
build/forest render scenes/demo.toml --out "$out/demo_occlusion.png" --mode opt --occlusion on --shadows off --stats
# PR of the pruned forest against full detail (coverage masks, Fig 7.1 picture).
build/forest render scenes/demo.toml --out "$out/mask_full.png" --view mask --mode full
build/forest render scenes/demo.toml --out "$out/mask_opt.png" --view mask --mode opt
build/forest compare "$out/mask_full.png" "$out/mask_opt.png" --diff "$out/pr_opt_vs_full.png"

echo
echo "Demo done:"
echo "  pictures: $PWD/$out/demo.png (shaded), demo_lambda.png (λ view), demo_occlusion.png"
echo "  PR:       $PWD/$out/pr_opt_vs_full.png (tp light green, fp red, fn dark green)"
echo "  figures:  $PWD/$out/report/{pr_diagram,scale_vs_lambda,lambda_vs_distance}.png + CSV"
echo "  assets:   $PWD/$out/{fig2_1,broadleaf,conifer,broadleaf_baked}.glb (any glTF viewer or Blender)"
