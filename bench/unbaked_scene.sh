#!/usr/bin/env bash
# Writes OUTDIR/scene.toml: SCENE with each `[[species]] preset` generated once into
# OUTDIR/species<i>.glb (the given forest binary, the species' own seed or the scene's) and
# named by `model =`, and every other relative path made absolute. Such a scene needs no bake
# and no species cache, so two builds render the very same models (bench/ab_render.sh); mode
# cook works unbaked (mode opt would draw full detail, occlusion uses a crown ellipsoid).
# Usage: bench/unbaked_scene.sh FOREST_BINARY SCENE OUTDIR
set -euo pipefail
[[ $# -eq 3 ]] || { echo "usage: bench/unbaked_scene.sh FOREST_BINARY SCENE OUTDIR" >&2; exit 2; }
mkdir -p "$3"
python3 - "$1" "$2" "$3" <<'PY'
import os, re, subprocess, sys
forest, scene, out = sys.argv[1], sys.argv[2], os.path.abspath(sys.argv[3])
base = os.path.dirname(os.path.abspath(scene))
text, count = open(scene).read(), [0]
def model(match):
    block, i = match.group(0), count[0]
    count[0] += 1
    glb = os.path.join(out, f"species{i}.glb")
    preset = re.search(r'^preset = "([^"]+)"', block, flags=re.M).group(1)
    seed = re.search(r'^seed = (\d+)', block, flags=re.M)
    args = [forest, "generate", "--species", os.path.join(base, preset), "--out", glb]
    subprocess.run(args + (["--seed", seed.group(1)] if seed else []), check=True, stdout=subprocess.DEVNULL)
    return re.sub(r'^preset = "[^"]+"', f'model = "{glb}"', block, flags=re.M)
# Each [[species]] table up to the next table header.
text = re.sub(r'^\[\[species\]\]\n(?:(?!\[).*\n?)*', model, text, flags=re.M)
text = re.sub(r'^(heightmap|model) = "([^"/][^"]*)"', lambda m: f'{m.group(1)} = "{os.path.join(base, m.group(2))}"', text, flags=re.M)
open(os.path.join(out, "scene.toml"), "w").write(text)
print(f"{os.path.join(out, 'scene.toml')}: {count[0]} species generated")
PY
