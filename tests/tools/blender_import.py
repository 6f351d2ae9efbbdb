# Imports a .glb in Blender (background mode) and prints what arrived as one JSON line:
# objects by name and type, triangles per mesh object, colour attributes, images, materials.
# Usage: blender -b --factory-startup --python-exit-code 1 -P blender_import.py -- FILE.glb
import json
import sys

import bpy
import numpy

# Debian 12's Blender 3.4 glTF importer calls numpy.bool, which Debian 12's NumPy 1.24 no
# longer has (removed in 1.24): every mesh import fails without this alias, whatever the file.
if not hasattr(numpy, "bool"):
    numpy.bool = bool

path = sys.argv[sys.argv.index("--") + 1]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=path)
out = {"objects": {}, "images": sorted(i.name for i in bpy.data.images if i.size[0] > 0),
       "materials": sorted(m.name for m in bpy.data.materials)}
for o in bpy.context.scene.objects:
    entry = {"type": o.type, "parent": o.parent.name if o.parent else None, "visible": not o.hide_get()}
    if o.type == "MESH":
        mesh = o.data
        mesh.calc_loop_triangles()
        entry["triangles"] = len(mesh.loop_triangles)
        colors = {}
        for attr in mesh.color_attributes:
            values = set()
            for d in attr.data:
                values.add(tuple(round(c, 3) for c in d.color[:3]))
                if len(values) > 64:
                    break
            colors[attr.name] = len(values)
        entry["colors"] = colors  # attribute -> distinct values seen (up to 65)
    out["objects"][o.name] = entry
print("FOREST_IMPORT " + json.dumps(out, sort_keys=True))
