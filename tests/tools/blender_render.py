# Renders a .glb in Blender (background mode, Cycles on the CPU) as an artist would see it
# after File > Import > glTF: a sun, a sky colour, a ground disc, the camera framing the
# imported objects from the side. For pictures of `forest export`'s files
# (scripts/client_pictures.sh).
# Usage: blender -b --factory-startup --python-exit-code 1 -P blender_render.py -- IN.glb OUT.png [SIZE] [SAMPLES]
import math
import sys

import bpy
import numpy
from mathutils import Vector

# Debian 12's Blender 3.4 glTF importer calls numpy.bool, gone from Debian 12's NumPy 1.24.
if not hasattr(numpy, "bool"):
    numpy.bool = bool

args = sys.argv[sys.argv.index("--") + 1:]
path, out = args[0], args[1]
size = int(args[2]) if len(args) > 2 else 480
samples = int(args[3]) if len(args) > 3 else 24
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=path)
scene = bpy.context.scene
meshes = [o for o in scene.objects if o.type == "MESH"]
corners = [o.matrix_world @ Vector(c) for o in meshes for c in o.bound_box]
lo = Vector((min(c.x for c in corners), min(c.y for c in corners), min(c.z for c in corners)))
hi = Vector((max(c.x for c in corners), max(c.y for c in corners), max(c.z for c in corners)))
center, extent = (lo + hi) / 2, hi - lo  # Blender is Z-up: the importer turned glTF's +Y up into +Z

bpy.ops.mesh.primitive_circle_add(vertices=64, radius=extent.length, fill_type="NGON", location=(center.x, center.y, lo.z))
ground = bpy.context.object
ground_material = bpy.data.materials.new("ground")
ground_material.diffuse_color = (0.14, 0.13, 0.05, 1)
ground_material.use_nodes = True
ground_material.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.14, 0.13, 0.05, 1)
ground.data.materials.append(ground_material)

sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", type="SUN"))
sun.data.energy = 4.0
sun.data.angle = math.radians(1.0)
sun.rotation_euler = (math.radians(50), 0, math.radians(35))
scene.collection.objects.link(sun)
world = bpy.data.worlds.new("sky")
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.45, 0.58, 0.8, 1)
world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.8
scene.world = world

camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
camera.data.angle = math.radians(35)
distance = extent.z * 0.62 / math.tan(math.radians(35) / 2)
camera.location = (center.x + 0.25 * distance, center.y - distance, center.z + 0.05 * extent.z)
camera.rotation_euler = (center - camera.location).to_track_quat("-Z", "Y").to_euler()
scene.collection.objects.link(camera)
scene.camera = camera

scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = samples
scene.cycles.use_denoising = False
scene.view_settings.view_transform = "Filmic"
scene.render.resolution_x = scene.render.resolution_y = size
scene.render.filepath = out
bpy.ops.render.render(write_still=True)
print("FOREST_RENDER " + out)
