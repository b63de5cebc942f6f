"""Builds a small scene in Blender 3.4 and exports it with Blender's own glTF
add-on (io_scene_gltf2), as a user's file would come to Kappa: run by
tools/blender_gltf.sh as

    blender -b --factory-startup --python tools/blender/gltf_export_scene.py -- OUT.glb

The scene (Blender's Z up; the exporter writes glTF's +Y up):
  floor     a 6 x 6 plane at z = 0, Principled base colour (0.8, 0.8, 0.8), roughness 0.9
  box       a 1 m cube resting on the floor at (-1, 0, 0.5), red (0.8, 0.1, 0.1), metallic 0
  metal     a 1 m cube at (1, 0.5, 0.5), gold-like base (1.0, 0.77, 0.34), metallic 1, roughness 0.25
  glass     a UV sphere of radius 0.4 at (0, -1, 0.4), transmission 1, IOR 1.5, roughness 0
  panel     a 1 x 1 plane at z = 2.5 facing down, emission (1, 1, 1) strength 5
  lights    a point light (1000 W) at (2, -2, 3), a spot light (500 W, size 60 deg, blend 0.2)
            at (-2, -2, 3) aimed at the origin, a sun (strength 2) tilted 30 deg
  camera    at (0, -6, 2.5) aimed at (0, 0, 0.5), 50 mm lens, 16:9 film (render size 320 x 180)
Materials are the Principled BSDF the add-on exports as pbrMetallicRoughness
(+ KHR_materials_transmission, KHR_materials_emissive_strength where needed).
"""
import math
import sys

import bpy
from mathutils import Vector


def principled(name, base, metallic=0.0, roughness=0.5, transmission=0.0, ior=1.45, emission=None, strength=1.0):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*base, 1.0)
    bsdf.inputs["Metallic"].default_value = metallic
    bsdf.inputs["Roughness"].default_value = roughness
    bsdf.inputs["Transmission"].default_value = transmission
    bsdf.inputs["IOR"].default_value = ior
    if emission is not None:
        bsdf.inputs["Emission"].default_value = (*emission, 1.0)
        bsdf.inputs["Emission Strength"].default_value = strength
    return mat


def with_material(obj, mat):
    obj.data.materials.clear()
    obj.data.materials.append(mat)
    return obj


def aim(obj, target):
    direction = Vector(target) - obj.location
    obj.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()


def main():
    out = sys.argv[sys.argv.index("--") + 1]
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene

    bpy.ops.mesh.primitive_plane_add(size=6, location=(0, 0, 0))
    with_material(bpy.context.object, principled("floor", (0.8, 0.8, 0.8), roughness=0.9)).name = "floor"
    bpy.ops.mesh.primitive_cube_add(size=1, location=(-1, 0, 0.5))
    with_material(bpy.context.object, principled("red", (0.8, 0.1, 0.1))).name = "box"
    bpy.ops.mesh.primitive_cube_add(size=1, location=(1, 0.5, 0.5))
    with_material(bpy.context.object, principled("gold", (1.0, 0.77, 0.34), metallic=1.0, roughness=0.25)).name = "metal"
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.4, location=(0, -1, 0.4), segments=32, ring_count=16)
    bpy.ops.object.shade_smooth()
    with_material(bpy.context.object, principled("glass", (1, 1, 1), roughness=0.0, transmission=1.0, ior=1.5)).name = "glass"
    bpy.ops.mesh.primitive_plane_add(size=1, location=(0, 0, 2.5), rotation=(math.pi, 0, 0))
    with_material(bpy.context.object, principled("panel", (0, 0, 0), emission=(1, 1, 1), strength=5.0)).name = "panel"

    point = bpy.data.lights.new("bulb", "POINT")
    point.energy = 1000.0
    obj = bpy.data.objects.new("bulb", point)
    obj.location = (2, -2, 3)
    scene.collection.objects.link(obj)
    spot = bpy.data.lights.new("spot", "SPOT")
    spot.energy = 500.0
    spot.spot_size = math.radians(60)
    spot.spot_blend = 0.2
    obj = bpy.data.objects.new("spot", spot)
    obj.location = (-2, -2, 3)
    scene.collection.objects.link(obj)
    aim(obj, (0, 0, 0))
    sun = bpy.data.lights.new("sun", "SUN")
    sun.energy = 2.0
    obj = bpy.data.objects.new("sun", sun)
    obj.rotation_euler = (math.radians(30), 0, math.radians(20))
    scene.collection.objects.link(obj)

    cam = bpy.data.cameras.new("view")
    cam.lens = 50
    obj = bpy.data.objects.new("view", cam)
    obj.location = (0, -6, 2.5)
    scene.collection.objects.link(obj)
    aim(obj, (0, 0, 0.5))
    scene.camera = obj
    scene.render.resolution_x = 320
    scene.render.resolution_y = 180

    bpy.ops.export_scene.gltf(filepath=out, export_format="GLB", export_cameras=True, export_lights=True,
                              export_yup=True, export_apply=True)


main()
