#!/usr/bin/env python3
"""forest export's files in clients nobody here wrote: three.js's GLTFLoader in headless
Chromium, Blender's glTF importer in background mode, and the Khronos glTF-Validator.
Takes the baked asset in CACHE_DIR (a test-sized broadleaf with hull, impostor and bake data,
made by the client.bake fixture), exports it instanced and flattened, loads LOD0 and the
coarsest LOD in the client, and checks the leaf and triangle counts against the source asset
(read here from its glTF JSON, not from the exporter), that leaf colours arrive (instance or
vertex colours, more than one value) and textures arrive, and that nothing but bark and leaves
is in the scene. `validator`: every exported file, both forms, has 0 errors and 0 warnings.
Usage: client_import_test.py three|blender|validator FOREST SOURCE_DIR NPM_DIR CACHE_DIR
Exit 0 pass, 1 fail, 77 skipped (client not installed)."""
import json, os, shutil, struct, subprocess, sys, tempfile

client, forest, src, npm, cache = sys.argv[1:6]
tool = {"three": "chromium", "blender": "blender", "validator": "node"}[client]
if not shutil.which(tool):
    print(f"client_import_test: {tool} missing (scripts/install-deps.sh --test installs it)")
    sys.exit(77)
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def gltf_json(path):
    with open(path, "rb") as f:
        data = f.read()
    length = struct.unpack_from("<I", data, 12)[0]
    return json.loads(data[20:20 + length])


def triangles(doc, mesh_name):
    for m in doc["meshes"]:
        if m["name"] == mesh_name:
            return doc["accessors"][m["primitives"][0]["indices"]]["count"] // 3
    raise KeyError(mesh_name)


def load(path):
    if client == "three":
        page = os.path.join(npm, "three_import.html")
        shutil.copy(os.path.join(src, "tests/tools/three_import.html"), page)
        cmd = ["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--allow-file-access-from-files",
               "--virtual-time-budget=30000", "--dump-dom", f"file://{page}?file={path}"]
    else:
        cmd = ["blender", "-b", "--factory-startup", "--python-exit-code", "1", "-P",
               os.path.join(src, "tests/tools/blender_import.py"), "--", path]
    # Blender finds its Python home through PATH: a pyenv or venv python ahead of Debian's
    # would hide Debian's numpy, which its glTF importer needs.
    env = dict(os.environ, PATH="/usr/bin:/bin") if client == "blender" else None
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=300, env=env).stdout
    for line in out.splitlines():
        i = line.find("FOREST_IMPORT {")
        if i >= 0:
            return json.loads(line[i + len("FOREST_IMPORT "):].split("</pre>")[0])
    raise RuntimeError(f"{client} loaded nothing from {path}:\n{out[-2000:]}")


def meshes(result):
    """name -> (triangles, colours seen, texture arrived), whatever the client's format."""
    if client == "three":
        return {m["name"]: (m["triangles"], m["colors"], m["texture"] is not None) for m in result["meshes"]}
    images = result["images"]
    return {name: (o["triangles"], max(o["colors"].values(), default=0),
                   ("leaf" if name == "leaves" else "bark") in images)
            for name, o in result["objects"].items() if o["type"] == "MESH"}


tmp = tempfile.mkdtemp(prefix="forest-client-")
try:
    assets = [os.path.join(cache, f) for f in os.listdir(cache) if f.endswith(".glb")]
    if len(assets) != 1:
        raise RuntimeError(f"expected one baked asset in {cache}, found {assets}")
    asset = assets[0]
    source = gltf_json(asset)
    node_names = [n["name"] for n in source["nodes"]]
    lods = sorted(n for n in node_names if n.startswith("branches_lod"))
    leaves = next(source["accessors"][n["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["TRANSLATION"]]["count"]
                  for n in source["nodes"] if n["name"] == "leaves")
    card = triangles(source, "leaf_card")
    check("hull" in node_names and any(m["name"] == "impostor" for m in source["materials"]),
          "the source asset has a hull and an impostor to keep out")
    for flatten in ([True] if client == "blender" else [False, True]):
        out = os.path.join(tmp, "flat" if flatten else "instanced", "broadleaf.glb")
        os.makedirs(os.path.dirname(out))
        subprocess.run([forest, "export", asset, "--out", out] + (["--flatten"] if flatten else []), check=True,
                       stdout=subprocess.DEVNULL)
        files = sorted(os.path.join(os.path.dirname(out), f) for f in os.listdir(os.path.dirname(out)))
        check(len(files) == len(lods) + 1, f"{len(files)} files written for {len(lods) + 1} levels")
        if client == "validator":
            v = subprocess.run(["node", os.path.join(src, "tests/tools/validate_gltf.mjs")] + files,
                               capture_output=True, text=True, env=dict(os.environ, NODE_PATH=os.path.join(npm, "node_modules")))
            print(v.stdout.strip())
            check(v.returncode == 0, f"glTF-Validator: 0 errors, 0 warnings in every {'flattened' if flatten else 'instanced'} file")
            continue
        for level in (0, len(lods)):
            f = out if level == 0 else out.replace(".glb", f"_LOD{level}.glb")
            bark = triangles(source, "branches" if level == 0 else f"branches_lod{level}")
            got = meshes(load(f))
            what = f"{client}, {'flattened' if flatten else 'instanced'}, LOD{level}"
            check(sorted(got) == ["branches", "leaves"], f"{what}: meshes {sorted(got)} are bark and leaves only")
            check(got.get("branches", (0,))[0] == bark, f"{what}: {got.get('branches', (0,))[0]} bark triangles, source {bark}")
            check(got.get("leaves", (0,))[0] == leaves * card,
                  f"{what}: {got.get('leaves', (0,))[0]} leaf triangles, source {leaves} leaves x {card}")
            check(got.get("leaves", (0, 0))[1] > 1, f"{what}: leaf colours arrive ({got.get('leaves', (0, 0))[1]} distinct)")
            check(all(m[2] for m in got.values()), f"{what}: bark and leaf textures arrive")
finally:
    shutil.rmtree(tmp, ignore_errors=True)
print(f"client_import_test: {client}: {len(failures)} failure(s)")
sys.exit(1 if failures else 0)
