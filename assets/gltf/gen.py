#!/usr/bin/env python3
"""The glTF 2.0 test scenes: small files, each made to exercise one part of
the glTF loader, with every number the tests compare written here. Standard
library only; the same bytes on every run.

    python3 assets/gltf/gen.py    # writes every file below into assets/gltf/

Conventions (glTF 2.0's own): +Y up, right-handed, metres; a triangle's front
is the side from which its vertices run counter-clockwise; "facing +Z" says
where that front points. Node transforms are column vectors, world = parent *
local, a node's local matrix T * R * S (translation, rotation quaternion
[x, y, z, w], scale) or its column-major `matrix`. S = 0.7071067811865476
(Python's math.sqrt(0.5)) below, so [0, S, 0, S] is 90 degrees about +Y (it
maps (x, y, z) to (z, y, -x): -Z to -X) and [-S, 0, 0, S] is -90 degrees about
+X (it maps -Z to -Y: straight down). Every vertex coordinate, texture
coordinate and factor a test compares bitwise is a binary fraction (0.25,
0.5, 0.75, 1.984375 ...), exact in a float. Buffers are little-endian; each
accessor has its own bufferView (offsets 4-byte aligned, `target` set; image
views have none); every buffer is padded with zeros to a multiple of 4 bytes
and its byteLength says so. extensionsUsed lists exactly the extensions
that appear in the file, sorted (none is in extensionsRequired). Unless a
scene says otherwise a primitive's `mode` is absent (TRIANGLES), a material
is single-sided (doubleSided absent) and there is one scene, `"scene": 0`.
Every POSITION accessor has min/max.

Material shorthand: "white" = pbrMetallicRoughness baseColorFactor
[0.75, 0.75, 0.75, 1], metallicFactor 0, roughnessFactor 1, extension
KHR_materials_specular {"specularFactor": 0} (a Lambertian reflector of
albedo 0.75). "matte" = the same with baseColorFactor [1, 1, 1, 1].

1. nested_cube.gltf + nested_cube.bin
   Mesh "cube": the cube [-0.5, 0.5]^3, 8 vertices, vertex i = (x, y, z) with
   x = +0.5 if i & 1, y = +0.5 if i & 2, z = +0.5 if i & 4, else -0.5 (vertex 0
   is (-0.5, -0.5, -0.5), vertex 7 (0.5, 0.5, 0.5)). 36 UNSIGNED_SHORT indices,
   12 triangles facing outwards, two per face in the order -X, +X, -Y, +Y,
   -Z, +Z; the face quad (a, b, c, d) gives triangles (a, b, c), (a, c, d):
       -X (0, 4, 6, 2)  +X (1, 3, 7, 5)  -Y (0, 1, 5, 4)
       +Y (2, 6, 7, 3)  -Z (0, 2, 3, 1)  +Z (4, 5, 7, 6)
   No material (glTF's default material: base colour 1, metallic 1,
   roughness 1), `mode` absent.
   Nodes: scene 0 = [node 0]. Node 0 "outer": translation [1, 2, 3], rotation
   [0, S, 0, S], scale [2, 2, 2], children [1]. Node 1 "inner": matrix
   (column-major) [0.5,0,0,0, 0,0.5,0,0, 0,0,0.5,0, 0.5,0,0,1] (translation
   [0.5, 0, 0], uniform scale 0.5), mesh 0.
   World position: (1, 2, 3) + R_y90(2 * ((0.5, 0, 0) + 0.5 p)) =
   (1 + p.z, 2 + p.y, 2 - p.x): the world box x in [0.5, 1.5], y in [1.5, 2.5],
   z in [1.5, 2.5] (up to the rounding of S).
   nested_cube_expected.json: "triangles": 12 triangles, each 3 [x, y, z], in
   index order, computed in double as outer * inner * p with outer = T * R * S
   (R from the quaternion by the usual formula, so entries like
   1 - 2 * S^2 = -2.2e-16 appear); "world_from_mesh": that 4 x 4 matrix,
   row-major. Compare within 1e-5.

2. The OBJ/glTF twin: twin.obj + twin.mtl, twin.gltf + twin.bin (external
   buffer), twin.glb (the same JSON with no buffer uri, the buffer as the BIN
   chunk: JSON chunk padded with spaces, BIN chunk with zeros, both to 4
   bytes), twin_embedded.gltf (the buffer as a
   data:application/octet-stream;base64 URI); twin_obj.json, twin_gltf.json:
   Kappa scene files, camera eye (0, 1, 3.5), look_at (0, 1, 0), up (0, 1, 0),
   vfov_deg 40, environment [0, 0, 0], film 32 x 32, meshes ["twin.obj"] and
   ["twin.gltf"]. The glTF has no cameras and no lights, no normals, no
   texture coordinates (neither has the OBJ: no vn, no vt).
   Eight objects, in this order in both files: the OBJ's `o` blocks (each its
   own `v` lines, then `usemtl` and triangle-only `f` lines with plain vertex
   indices) and the glTF's nodes 0-7 (name = the object's, mesh k = node k,
   no transform) in scene 0. Mesh k: one primitive, "mode": 4 written out,
   material as below. "indexed" = its own POSITION (the object's vertices, as
   listed) plus UNSIGNED_INT indices (the triangles below); "flat" = a
   POSITION of 3 vertices per triangle in the same order, no indices. Either
   way the triangles, their order and their vertices' order and values are
   the same in the OBJ and the glTF. A quad (a, b, c, d) is the triangles
   (a, b, c), (a, c, d).
     0 floor       white, indexed: (-1,0,1) (1,0,1) (1,0,-1) (-1,0,-1), facing +Y
     1 ceiling     white, flat:    (-1,2,-1) (1,2,-1) (1,2,1) (-1,2,1), facing -Y
     2 back_wall   white, indexed: (-1,0,-1) (1,0,-1) (1,2,-1) (-1,2,-1), facing +Z
     3 left_wall   red, flat:      (-1,0,1) (-1,0,-1) (-1,2,-1) (-1,2,1), facing +X
     4 right_wall  green, flat:    (1,0,-1) (1,0,1) (1,2,1) (1,2,-1), facing -X
     5 light       light, flat:    y = 1.984375 (2 - 1/64; exact), x, z in
                   [-0.25, 0.25]: (-0.25,y,-0.25) (0.25,y,-0.25) (0.25,y,0.25)
                   (-0.25,y,0.25), facing -Y; area 0.25 m^2
     6 box         glossy, indexed: the cube x in [0, 0.5], y in [0, 0.5], z in
                   [-0.25, 0.25] (centred on x = 0.25, z = 0, resting on the
                   floor), its 8 vertices and 12 outward triangles numbered as
                   in nested_cube (vertex i: x = 0.5 if i & 1 else 0, y = 0.5
                   if i & 2 else 0, z = 0.25 if i & 4 else -0.25)
     7 panel       metal, flat: (-0.75,0,-0.25) (-0.25,0,-0.75) (-0.25,1,-0.75)
                   (-0.75,1,-0.25), a vertical 0.5 sqrt 2 x 1 panel in the
                   back-left corner facing (1, 0, 1)/sqrt 2 (towards the camera)
   26 triangles in all. Materials (MTL, read as Blender 3.4's importer ->
   glTF, same parameters):
     white  Kd 0.75 0.75 0.75, Ks 0 0 0, illum 1  ->  white (above)
     red    Kd 0.75 0.25 0.25 ...                  ->  white with base [0.75, 0.25, 0.25, 1]
     green  Kd 0.25 0.75 0.25 ...                  ->  white with base [0.25, 0.75, 0.25, 1]
     light  Kd 0 0 0, Ks 0 0 0, Ke 8 8 8, illum 1  ->  base [0, 0, 0, 1], metallic 0,
            roughness 1, specularFactor 0, emissiveFactor [1, 1, 1],
            KHR_materials_emissive_strength {"emissiveStrength": 8}: radiance 8
     glossy Kd 0.5 0.5 0.5, Ks 0.5 0.5 0.5, Pr 0.25, Pm 0, illum 2  ->  base
            [0.5, 0.5, 0.5, 1], metallic 0, roughness 0.25, no specular
            extension (specularFactor 1: specular 0.5)
     metal  Kd 0.75 0.5 0.25, Ks 0.5 0.5 0.5, Pr 0.25, Pm 1, illum 3  ->  base
            [0.75, 0.5, 0.25, 1], metallic 1, roughness 0.25, no extension
   (glTF material index: white 0, red 1, green 2, light 3, glossy 4, metal 5.)
   extensionsUsed: KHR_materials_emissive_strength, KHR_materials_specular.
   doubleSided is absent (false) as everywhere: Kappa, like Blender's
   renderers, reflects alike on both sides of an opaque surface, and the MTL
   has no such flag; the light is to emit from its front (-Y) side only, as
   the MTL's Ke does in Kappa.

3. cameras.gltf (embedded buffer)
   Mesh 0 "quad": z = 0, x, y in [-0.5, 0.5], facing +Z, UNSIGNED_SHORT
   indices, material 0 "matte". Cameras, in this order:
     0 "ortho" orthographic xmag 1, ymag 1, znear 0.1, zfar 100
     1 "wide"  perspective yfov 1 (57.29577951308232 degrees), aspectRatio 2,
               znear 0.1, no zfar
     2 "tele"  perspective yfov 0.25 (14.32394487827058 degrees), znear 0.1,
               no aspectRatio, no zfar
   Nodes (scene 0 = [0, 1, 2, 3], in that order): 0 "ortho" camera 0,
   translation [0, 0, 10]; 1 "wide" camera 1, translation [0, 1, 5];
   2 "tele" camera 2, translation [2, 0, 0], rotation [0, S, 0, S]; 3 "quad"
   mesh 0. The first perspective camera, whether counted in `cameras` or in
   the scene's node order (the two agree), is camera 1 "wide" (the
   orthographic one before it is skipped): eye (0, 1, 5), looking down -Z
   (look_at (0, 1, 4)), up +Y, vertical field of view 1 radian; its
   aspectRatio 2 is the author's and does not change Kappa's film. "tele":
   eye (2, 0, 0), looking down -X, up +Y, 0.25 radian.

4. Lights: KHR_lights_punctual, each file with an embedded buffer
   (extensionsUsed: KHR_lights_punctual, KHR_materials_specular). Mesh 0
   "floor": y = 0, x, z in [-8, 8], vertices (-8,0,8) (8,0,8) (8,0,-8)
   (-8,0,-8), UNSIGNED_SHORT indices [0,1,2, 0,2,3] (facing +Y), material 0
   "matte"; node 0 "floor". Light 0 on node 1; no cameras.
     point_light.gltf        light "bulb": type point, color [1, 1, 1],
                             intensity 683 (candela), no range; node 1 "bulb"
                             translation [0, 2, 0]. At the floor's origin
                             (distance 2, normal incidence) the irradiance is
                             683 / 4 lx (0.25 W m^-2 at 683 lm/W).
     spot_light.gltf         light "spot": type spot, color [1, 1, 1], intensity
                             683, spot {innerConeAngle 0.25, outerConeAngle 0.5};
                             node 1 "spot" translation [0, 2, 0], rotation
                             [-S, 0, 0, S] (its -Z points straight down). On
                             the floor the full-intensity disc has radius
                             2 tan 0.25 = 0.5106838424420725 and nothing lies
                             beyond 2 tan 0.5 = 1.092604979687581.
     directional_light.gltf  light "sun": type directional, color [1, 1, 1],
                             intensity 683 (lux); node 1 "sun" rotation
                             [-S, 0, 0, S], no translation (light travels
                             straight down, -Y). Mesh 1 "blocker", node 2:
                             two quads at y = 1, x, z in [-0.5, 0.5], material
                             0: (-0.5,1,-0.5) (0.5,1,-0.5) (0.5,1,0.5) (-0.5,1,0.5)
                             facing -Y, then (-0.5,1,0.5) (0.5,1,0.5) (0.5,1,-0.5)
                             (-0.5,1,-0.5) facing +Y; UNSIGNED_SHORT indices
                             over those 8 vertices. 4 triangles + 2 floor = 6.
                             The floor's direct irradiance is 683 lx (1 W m^-2)
                             outside the square x, z in [-0.5, 0.5] and 0
                             inside: the blocker's shadow is exactly it.

5. Alpha.
   mask_alpha.png: 8 x 8 RGBA, RGB 255 everywhere, alpha 255 in columns 0-3
   (the left half) and 0 in columns 4-7.
   Quad (all three files): z = 0, x, y in [-1, 1], facing +Z: vertices
   (-1,-1,0) (1,-1,0) (1,1,0) (-1,1,0) with TEXCOORD_0 (0,1) (1,1) (1,0) (0,0)
   (glTF's v runs down the image: (0, 0) is the image's top-left corner, at
   the quad's top-left (-1, 1)), UNSIGNED_SHORT indices [0,1,2, 0,2,3]: u =
   (x + 1) / 2, v = (1 - y) / 2, so the image's left half covers x < 0.
   Texture 0 = image 0 with sampler 0 {magFilter NEAREST (9728), wrapS and
   wrapT CLAMP_TO_EDGE (33071)}. Material 0 ("mask" in the MASK files,
   "blend" in blend.gltf): metallicFactor 0,
   roughnessFactor 1, baseColorTexture {"index": 0}.
     mask.glb          the image in the BIN chunk through a bufferView,
                       mimeType image/png (mask_alpha.png's bytes); alphaMode
                       MASK, alphaCutoff 0.5, baseColorFactor [1, 1, 1, 1]:
                       the quad is opaque where x < 0 and cut out where x > 0.
     mask_cutoff.gltf  + mask_cutoff.bin, image uri "mask_alpha.png"; alphaMode
                       MASK, alphaCutoff 0.75, baseColorFactor [1, 1, 1, 0.5]:
                       alpha is at most 1 * 0.5 < 0.75 everywhere, the whole
                       quad is cut out.
     blend.gltf        embedded buffer, image uri "mask_alpha.png"; alphaMode
                       BLEND (no alphaCutoff), baseColorFactor [1, 1, 1, 1].

6. textured.gltf + textured.bin, textured_checker.png, textured_metal_rough.png
   textured_checker.png: 4 x 4 RGB grey checks, texel (column i, row j from
   the top) = 255 where i + j is even (the top-left texel is 255), else 64
   (sRGB: linear 1 and 0.05126945837404324).
   textured_metal_rough.png: 4 x 4 RGB, R = 0, G (roughness) = 128 (128/255 =
   0.5019607843137255, linear data), B (metallic) = 255 in columns 0-1 and 0
   in columns 2-3.
   Quad: the alpha scenes' vertices and indices, TEXCOORD_0 (0,2) (2,2) (2,0)
   (0,0): u = x + 1, v = 1 - y, both in [0, 2]. Sampler 0: wrapS REPEAT
   (10497), wrapT MIRRORED_REPEAT (33648), no filters. Texture 0 = checker,
   texture 1 = metal_rough, both sampler 0. Material 0 "textured":
   baseColorFactor [1, 1, 1, 1], baseColorTexture 0, metallicFactor 1,
   roughnessFactor 1, metallicRoughnessTexture 1; no emissiveTexture. With
   REPEAT the image repeats twice across x (metallic where x in [-1, -0.5) or
   [0, 0.5)); with MIRRORED_REPEAT the quad's lower half (v in (1, 2]) shows
   the image flipped upside down (v -> 2 - v).
   textured_data_uri.gltf: the same JSON and textured.bin, but image 0's uri is
   the checker PNG as data:image/png;base64.

7. primitives.gltf (embedded buffer), all in z = 0, all triangles facing +Z,
   material 0 "matte" on every primitive. Mesh and node k share the name.
     mesh 0 "strip"  mode 5 TRIANGLE_STRIP, 5 vertices, no indices:
                     v0 (0,1,0) v1 (0,0,0) v2 (1,1,0) v3 (1,0,0) v4 (2,1,0)
     mesh 1 "fan"    mode 6 TRIANGLE_FAN, 5 vertices, no indices:
                     v0 (-3,0,0) (hub) v1 (-2,0,0) v2 (-2,1,0) v3 (-3,1,0) v4 (-4,1,0)
     mesh 2 "mixed"  three primitives: [0] mode 4 written out, vertices
                     (0,2,0) (1,2,0) (1,3,0) (0,3,0), UNSIGNED_BYTE indices
                     [0,1,2, 0,2,3]; [1] mode 0 POINTS, 3 vertices (4,0,0)
                     (5,0,0) (6,0,0); [2] mode 1 LINES, 4 vertices (4,1,0)
                     (5,1,0) (4,2,0) (5,2,0) (2 segments). [1] and [2] are
                     to be warned about and skipped; [0] kept.
     mesh 3 "shared" one triangle (0,-2,0) (1,-2,0) (0,-1,0), no indices,
                     used by node 3 "shared_a" (translation [0, 0, 0]) and
                     node 4 "shared_b" (translation [3, 0, 0]).
   Nodes 0-2 carry meshes 0-2, no transform; scene 0 = [0, 1, 2, 3, 4].
   The spec's topology (glTF 2.0, 3.7.2.1): strip triangle i =
   {v_i, v_(i+(1+i%2)), v_(i+(2-i%2))}, i.e. (i, i+1, i+2) for even i and
   (i, i+2, i+1) for odd i (the same triangle and winding as OpenGL's
   (i+1, i, i+2), first vertex differs); fan triangle i = {v_(i+1), v_(i+2), v_0}.
   Expected triangles, 10, in this order:
     strip (v0,v1,v2) (v1,v3,v2) (v2,v3,v4)
     fan   (v1,v2,v0) (v2,v3,v0) (v3,v4,v0)
     mixed (0,2,0)(1,2,0)(1,3,0)  (0,2,0)(1,3,0)(0,3,0)
     shared_a (0,-2,0)(1,-2,0)(0,-1,0);  shared_b (3,-2,0)(4,-2,0)(3,-1,0)

8. extensions.gltf (embedded buffer; the image, textured_checker.png's bytes,
   through a bufferView, mimeType image/png; texture 0 = image 0, no sampler)
   Mesh k (k = 0..7) "quad_k": one quad x, y in [0, 1], z = 0, facing +Z,
   vertices (0,0,0) (1,0,0) (1,1,0) (0,1,0), UNSIGNED_SHORT indices
   [0,1,2, 0,2,3] (the accessors are shared by all eight meshes), material k.
   Meshes 0, 1, 4 and 6 (those whose material has a texture) also have
   TEXCOORD_0 (0,1) (1,1) (1,0) (0,0); mesh 6 has TEXCOORD_1 as well: (0,0.5)
   (0.5,0.5) (0.5,0) (0,0). Every material: base [0.75, 0.75, 0.75, 1],
   metallic 0, roughness 1, plus:
     0 "normal_texture"     normalTexture {"index": 0}
     1 "occlusion_texture"  occlusionTexture {"index": 0}
     2 "clearcoat"          KHR_materials_clearcoat {clearcoatFactor 1,
                            clearcoatRoughnessFactor 0.25}
     3 "sheen"              KHR_materials_sheen {sheenColorFactor [1, 1, 1],
                            sheenRoughnessFactor 0.5}
     4 "texture_transform"  baseColorTexture {"index": 0, extensions:
                            KHR_texture_transform {offset [0.5, 0], scale [2, 2]}}
     5 "volume"             KHR_materials_volume {thicknessFactor 0.25} (no
                            transmission extension: the validator warns)
     6 "texcoord_1"         baseColorTexture {"index": 0, "texCoord": 1}
     7 "plain"              nothing more
   Nodes 0-6 "quad_0".."quad_6": mesh k, translation [2k, 0, 0]; node 7
   "other_scene_quad": mesh 7, translation [0, 2, 0]. Scenes: 0 "main" =
   [0..6] (the default, "scene": 0), 1 "other" = [7]. extensionsUsed:
   KHR_materials_clearcoat, KHR_materials_sheen, KHR_materials_volume,
   KHR_texture_transform (none required).
   Expected: scene 0 only, 7 quads = 14 triangles (node 7 not loaded); one
   warning for each of: normalTexture (material 0), occlusionTexture (1),
   KHR_materials_clearcoat (2), KHR_materials_sheen (3), KHR_texture_transform
   (4), KHR_materials_volume (5), texCoord 1 (6); and, as the loader chooses,
   that scene 1 of 2 is not loaded.
"""
import base64
import json
import math
import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True  # leave no __pycache__ beside png_writer.py
sys.path.insert(0, os.path.join(HERE, ".."))
from png_writer import write_png  # noqa: E402

GENERATOR = "Kappa assets/gltf/gen.py"

# glTF's enumerations.
FLOAT, UNSIGNED_BYTE, UNSIGNED_SHORT, UNSIGNED_INT = 5126, 5121, 5123, 5125
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963
POINTS, LINES, TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN = 0, 1, 4, 5, 6
NEAREST, REPEAT, MIRRORED_REPEAT, CLAMP_TO_EDGE = 9728, 10497, 33648, 33071

S = math.sqrt(0.5)  # 0.7071067811865476
ROT_Y_90 = [0.0, S, 0.0, S]          # 90 degrees about +Y: -Z -> -X
ROT_X_MINUS_90 = [-S, 0.0, 0.0, S]   # -90 degrees about +X: -Z -> -Y (down)

LIGHT_Y = 1.984375  # the twin's light, 1/64 m under the ceiling (exact in binary)


# ---------------------------------------------------------------- geometry

def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def facing(a, b, c):
    """The (unnormalised) normal of the counter-clockwise triangle a, b, c."""
    return cross(sub(b, a), sub(c, a))


def quad(corners, normal):
    """A quad's corners (counter-clockwise seen from `normal`) and its two
    triangles (0, 1, 2), (0, 2, 3), checked to face `normal`."""
    tris = [(0, 1, 2), (0, 2, 3)]
    for t in tris:
        n = facing(*(corners[i] for i in t))
        assert dot(n, normal) > 0 and all(abs(x) < 1e-12 for x in cross(n, normal)), (corners, normal)
    return list(corners), tris


def box(lo, hi):
    """The box [lo, hi]: vertex i takes hi in x if i & 1, in y if i & 2, in z
    if i & 4; 12 outward triangles, faces -X, +X, -Y, +Y, -Z, +Z."""
    verts = [tuple(hi[k] if i >> k & 1 else lo[k] for k in range(3)) for i in range(8)]
    faces = [(0, 4, 6, 2), (1, 3, 7, 5), (0, 1, 5, 4), (2, 6, 7, 3), (0, 2, 3, 1), (4, 5, 7, 6)]
    centre = tuple((a + b) / 2 for a, b in zip(lo, hi))
    tris = []
    for a, b, c, d in faces:
        for t in ((a, b, c), (a, c, d)):
            n = facing(*(verts[i] for i in t))
            assert dot(n, sub(verts[t[0]], centre)) > 0  # outwards
            tris.append(t)
    return verts, tris


def f32_exact(x):
    """x, asserted to be a float32 value (so the file holds it exactly)."""
    assert struct.unpack("<f", struct.pack("<f", x))[0] == x, x
    return x


# ---------------------------------------------------------------- matrices (row-major, double)

def trs(t, q, s):
    """T * R * S, as glTF composes a node's TRS."""
    x, y, z, w = q
    r = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
         [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
         [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    return [[r[i][0] * s[0], r[i][1] * s[1], r[i][2] * s[2], t[i]] for i in range(3)] + [[0.0, 0.0, 0.0, 1.0]]


def from_column_major(m):
    return [[float(m[c * 4 + r]) for c in range(4)] for r in range(4)]


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def transform(m, p):
    return [sum(m[i][k] * p[k] for k in range(3)) + m[i][3] for i in range(3)]


# ---------------------------------------------------------------- JSON

def number(x):
    if isinstance(x, bool):
        return "true" if x else "false"
    if isinstance(x, float):
        assert math.isfinite(x)
        return str(int(x)) if x == int(x) and abs(x) < 2 ** 53 else repr(x)  # 1.0 -> "1", -0.0 -> "0"
    return json.dumps(x)


def to_json(v, depth=0):
    """Indented JSON, with lists of plain values on one line."""
    pad = "  " * depth
    if isinstance(v, dict):
        if not v:
            return "{}"
        items = ["%s  %s: %s" % (pad, json.dumps(k), to_json(x, depth + 1)) for k, x in v.items()]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(v, list):
        if all(not isinstance(x, (dict, list)) for x in v):
            return "[" + ", ".join(number(x) for x in v) + "]"
        return "[\n" + ",\n".join(pad + "  " + to_json(x, depth + 1) for x in v) + "\n" + pad + "]"
    return number(v)


def write_text(name, text):
    with open(os.path.join(HERE, name), "w", newline="\n") as f:
        f.write(text)


def write_bytes(name, data):
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data)


def read_bytes(name):
    with open(os.path.join(HERE, name), "rb") as f:
        return f.read()


# ---------------------------------------------------------------- the document builder

KEY_ORDER = ["asset", "extensionsUsed", "extensions", "scene", "scenes", "nodes", "cameras", "meshes",
             "materials", "textures", "samplers", "images", "accessors", "bufferViews", "buffers"]


class Doc:
    """A glTF document with one buffer, built up in order."""

    def __init__(self):
        self.j = {"asset": {"generator": GENERATOR, "version": "2.0"}}
        self.bin = bytearray()

    def add(self, key, obj):
        items = self.j.setdefault(key, [])
        items.append(obj)
        return len(items) - 1

    def view(self, data, target=None):
        self.bin += b"\0" * (-len(self.bin) % 4)
        v = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if target is not None:
            v["target"] = target
        self.bin += data
        return self.add("bufferViews", v)

    def floats(self, rows, kind, min_max=False):
        n = len(rows[0])
        assert all(len(r) == n for r in rows)
        data = b"".join(struct.pack("<%df" % n, *(f32_exact(float(x)) for x in r)) for r in rows)
        a = {"bufferView": self.view(data, ARRAY_BUFFER), "componentType": FLOAT, "count": len(rows), "type": kind}
        if min_max:
            a["min"] = [float(min(r[i] for r in rows)) for i in range(n)]
            a["max"] = [float(max(r[i] for r in rows)) for i in range(n)]
        return self.add("accessors", a)

    def positions(self, points):
        return self.floats(points, "VEC3", min_max=True)

    def texcoords(self, uvs):
        return self.floats(uvs, "VEC2")

    def indices(self, values, component):
        code = {UNSIGNED_BYTE: "B", UNSIGNED_SHORT: "H", UNSIGNED_INT: "I"}[component]
        data = struct.pack("<%d%s" % (len(values), code), *values)
        return self.add("accessors", {"bufferView": self.view(data, ELEMENT_ARRAY_BUFFER), "componentType": component,
                                      "count": len(values), "type": "SCALAR"})

    def png_view(self, png):
        return self.add("images", {"bufferView": self.view(png), "mimeType": "image/png"})

    def padded_bin(self):
        return bytes(self.bin) + b"\0" * (-len(self.bin) % 4)

    def json_text(self, buffer):
        j = dict(self.j)
        j["buffers"] = [buffer]
        used = sorted(extension_names(j))
        if used:
            j["extensionsUsed"] = used  # every extension that appears, and no other
        assert set(j) <= set(KEY_ORDER), set(j) - set(KEY_ORDER)
        return to_json({k: j[k] for k in KEY_ORDER if k in j}) + "\n"

    def write_gltf(self, name, bin_name=None):
        """name.gltf with the buffer in bin_name beside it, or embedded as a data URI."""
        data = self.padded_bin()
        if bin_name:
            write_bytes(bin_name, data)
            uri = bin_name
        else:
            uri = "data:application/octet-stream;base64," + base64.b64encode(data).decode("ascii")
        write_text(name, self.json_text({"byteLength": len(data), "uri": uri}))

    def write_glb(self, name):
        data = self.padded_bin()
        j = self.json_text({"byteLength": len(data)}).encode("utf-8")
        j += b" " * (-len(j) % 4)
        total = 12 + 8 + len(j) + 8 + len(data)
        write_bytes(name, struct.pack("<4sII", b"glTF", 2, total) + struct.pack("<I4s", len(j), b"JSON") + j +
                    struct.pack("<I4s", len(data), b"BIN\0") + data)


def extension_names(v):
    """The names of the extensions a JSON value uses (the keys of every
    `extensions` object in it)."""
    names = set()
    if isinstance(v, dict):
        for k, x in v.items():
            if k == "extensions":
                names |= set(x)
            names |= extension_names(x)
    elif isinstance(v, list):
        for x in v:
            names |= extension_names(x)
    return names


def pbr(base, metallic, roughness, **more):
    m = {"pbrMetallicRoughness": {"baseColorFactor": [float(x) for x in base], "metallicFactor": float(metallic),
                                  "roughnessFactor": float(roughness)}}
    m.update(more)
    return m


def lambertian(name, base):
    """Base colour only: metallic 0, roughness 1, no specular reflection."""
    return dict({"name": name}, **pbr(base, 0, 1, extensions={"KHR_materials_specular": {"specularFactor": 0.0}}))


WHITE = [0.75, 0.75, 0.75, 1]
MATTE = [1, 1, 1, 1]


def flatten(tris):
    return [i for t in tris for i in t]


# ---------------------------------------------------------------- 1. nested_cube

def nested_cube():
    verts, tris = box((-0.5, -0.5, -0.5), (0.5, 0.5, 0.5))
    doc = Doc()
    pos = doc.positions(verts)
    idx = doc.indices(flatten(tris), UNSIGNED_SHORT)
    doc.add("meshes", {"name": "cube", "primitives": [{"attributes": {"POSITION": pos}, "indices": idx}]})
    outer_t, outer_r, outer_s = [1.0, 2.0, 3.0], ROT_Y_90, [2.0, 2.0, 2.0]
    inner = [0.5, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 0.5, 0, 0.5, 0, 0, 1]
    doc.add("nodes", {"name": "outer", "children": [1], "translation": outer_t, "rotation": outer_r,
                      "scale": outer_s})
    doc.add("nodes", {"name": "inner", "matrix": [float(x) for x in inner], "mesh": 0})
    doc.j["scene"] = 0
    doc.add("scenes", {"name": "nested_cube", "nodes": [0]})
    doc.write_gltf("nested_cube.gltf", "nested_cube.bin")

    world = matmul(trs(outer_t, outer_r, outer_s), from_column_major(inner))
    triangles = [[transform(world, verts[i]) for i in t] for t in tris]
    # The closed form (1 + z, 2 + y, 2 - x) agrees to rounding.
    for t, w in zip(tris, triangles):
        for i, p in zip(t, w):
            x, y, z = verts[i]
            assert all(abs(a - b) < 1e-12 for a, b in zip(p, (1 + z, 2 + y, 2 - x)))
    expected = {"generator": GENERATOR,
                "what": "nested_cube.gltf's 12 triangles in world space, index order, outer * inner * p in double",
                "world_from_mesh": world, "triangles": triangles}
    write_text("nested_cube_expected.json", to_json(expected) + "\n")


# ---------------------------------------------------------------- 2. the OBJ/glTF twin

TWIN_MTL = """# Written by gen.py: the OBJ half of the OBJ/glTF twin (see gen.py's docstring).
newmtl white
Kd 0.75 0.75 0.75
Ks 0 0 0
illum 1

newmtl red
Kd 0.75 0.25 0.25
Ks 0 0 0
illum 1

newmtl green
Kd 0.25 0.75 0.25
Ks 0 0 0
illum 1

newmtl light
Kd 0 0 0
Ks 0 0 0
Ke 8 8 8
illum 1

newmtl glossy
Kd 0.5 0.5 0.5
Ks 0.5 0.5 0.5
Pr 0.25
Pm 0
illum 2

newmtl metal
Kd 0.75 0.5 0.25
Ks 0.5 0.5 0.5
Pr 0.25
Pm 1
illum 3
"""

TWIN_MATERIALS = [
    lambertian("white", WHITE),
    lambertian("red", [0.75, 0.25, 0.25, 1]),
    lambertian("green", [0.25, 0.75, 0.25, 1]),
    dict({"name": "light"}, **pbr([0, 0, 0, 1], 0, 1, emissiveFactor=[1.0, 1.0, 1.0],
                                  extensions={"KHR_materials_emissive_strength": {"emissiveStrength": 8.0},
                                              "KHR_materials_specular": {"specularFactor": 0.0}})),
    dict({"name": "glossy"}, **pbr([0.5, 0.5, 0.5, 1], 0, 0.25)),
    dict({"name": "metal"}, **pbr([0.75, 0.5, 0.25, 1], 1, 0.25)),
]


def twin_objects():
    """(name, material, vertices, triangles, indexed), in file order."""
    y = LIGHT_Y
    objects = [
        ("floor", "white", quad([(-1, 0, 1), (1, 0, 1), (1, 0, -1), (-1, 0, -1)], (0, 1, 0)), True),
        ("ceiling", "white", quad([(-1, 2, -1), (1, 2, -1), (1, 2, 1), (-1, 2, 1)], (0, -1, 0)), False),
        ("back_wall", "white", quad([(-1, 0, -1), (1, 0, -1), (1, 2, -1), (-1, 2, -1)], (0, 0, 1)), True),
        ("left_wall", "red", quad([(-1, 0, 1), (-1, 0, -1), (-1, 2, -1), (-1, 2, 1)], (1, 0, 0)), False),
        ("right_wall", "green", quad([(1, 0, -1), (1, 0, 1), (1, 2, 1), (1, 2, -1)], (-1, 0, 0)), False),
        ("light", "light", quad([(-0.25, y, -0.25), (0.25, y, -0.25), (0.25, y, 0.25), (-0.25, y, 0.25)],
                                (0, -1, 0)), False),
        ("box", "glossy", box((0, 0, -0.25), (0.5, 0.5, 0.25)), True),
        ("panel", "metal", quad([(-0.75, 0, -0.25), (-0.25, 0, -0.75), (-0.25, 1, -0.75), (-0.75, 1, -0.25)],
                                (1, 0, 1)), False),
    ]
    return [(name, mat, [tuple(float(c) for c in v) for v in verts], tris, indexed)
            for name, mat, (verts, tris), indexed in objects]


def obj_number(x):
    f32_exact(x)
    s = str(int(x)) if x == int(x) else repr(x)
    assert float(s) == x
    return s


def twin():
    objects = twin_objects()
    obj = ["# Written by gen.py: the OBJ half of the OBJ/glTF twin; twin.gltf holds the same",
           "# triangles in the same order (see gen.py's docstring).", "mtllib twin.mtl", ""]
    base = 1
    for name, mat, verts, tris, _ in objects:
        obj.append("o " + name)
        obj += ["v " + " ".join(obj_number(c) for c in v) for v in verts]
        obj.append("usemtl " + mat)
        obj += ["f %d %d %d" % tuple(base + i for i in t) for t in tris]
        obj.append("")
        base += len(verts)
    write_text("twin.obj", "\n".join(obj))
    write_text("twin.mtl", TWIN_MTL)

    doc = Doc()
    material_index = {}
    for m in TWIN_MATERIALS:
        material_index[m["name"]] = doc.add("materials", m)
    for name, mat, verts, tris, indexed in objects:
        prim = {}
        if indexed:
            prim["attributes"] = {"POSITION": doc.positions(verts)}
            prim["indices"] = doc.indices(flatten(tris), UNSIGNED_INT)
        else:
            prim["attributes"] = {"POSITION": doc.positions([verts[i] for i in flatten(tris)])}
        prim["material"] = material_index[mat]
        prim["mode"] = TRIANGLES
        k = doc.add("meshes", {"name": name, "primitives": [prim]})
        doc.add("nodes", {"name": name, "mesh": k})
    doc.j["scene"] = 0
    doc.add("scenes", {"name": "twin", "nodes": list(range(len(objects)))})
    doc.write_gltf("twin.gltf", "twin.bin")
    doc.write_glb("twin.glb")
    doc.write_gltf("twin_embedded.gltf")

    for scene_name, mesh in (("twin_obj.json", "twin.obj"), ("twin_gltf.json", "twin.gltf")):
        scene = {"meshes": [mesh],
                 "camera": {"eye": [0, 1, 3.5], "look_at": [0, 1, 0], "up": [0, 1, 0], "vfov_deg": 40},
                 "environment": [0, 0, 0],
                 "film": {"width": 32, "height": 32}}
        write_text(scene_name, "{\n" + ",\n".join("  %s: %s" % (json.dumps(k), json.dumps(v))
                                                   for k, v in scene.items()) + "\n}\n")


# ---------------------------------------------------------------- 3. cameras

def quad_mesh(doc, name, corners, normal, material, uvs=None):
    verts, tris = quad(corners, normal)
    attributes = {"POSITION": doc.positions(verts)}
    if uvs is not None:
        attributes["TEXCOORD_0"] = doc.texcoords(uvs)
    prim = {"attributes": attributes, "indices": doc.indices(flatten(tris), UNSIGNED_SHORT), "material": material}
    return doc.add("meshes", {"name": name, "primitives": [prim]})


def cameras():
    doc = Doc()
    doc.add("materials", lambertian("matte", MATTE))
    quad_mesh(doc, "quad", [(-0.5, -0.5, 0), (0.5, -0.5, 0), (0.5, 0.5, 0), (-0.5, 0.5, 0)], (0, 0, 1), 0)
    doc.add("cameras", {"name": "ortho", "type": "orthographic",
                        "orthographic": {"xmag": 1.0, "ymag": 1.0, "zfar": 100.0, "znear": 0.1}})
    doc.add("cameras", {"name": "wide", "type": "perspective",
                        "perspective": {"aspectRatio": 2.0, "yfov": 1.0, "znear": 0.1}})
    doc.add("cameras", {"name": "tele", "type": "perspective", "perspective": {"yfov": 0.25, "znear": 0.1}})
    doc.add("nodes", {"name": "ortho", "camera": 0, "translation": [0.0, 0.0, 10.0]})
    doc.add("nodes", {"name": "wide", "camera": 1, "translation": [0.0, 1.0, 5.0]})
    doc.add("nodes", {"name": "tele", "camera": 2, "translation": [2.0, 0.0, 0.0], "rotation": ROT_Y_90})
    doc.add("nodes", {"name": "quad", "mesh": 0})
    doc.j["scene"] = 0
    doc.add("scenes", {"name": "cameras", "nodes": [0, 1, 2, 3]})
    doc.write_gltf("cameras.gltf")


# ---------------------------------------------------------------- 4. lights

def light_scene(file, light, light_node, blocker=False):
    doc = Doc()
    doc.j["extensions"] = {"KHR_lights_punctual": {"lights": [light]}}
    doc.add("materials", lambertian("matte", MATTE))
    quad_mesh(doc, "floor", [(-8, 0, 8), (8, 0, 8), (8, 0, -8), (-8, 0, -8)], (0, 1, 0), 0)
    doc.add("nodes", {"name": "floor", "mesh": 0})
    doc.add("nodes", dict({"name": light["name"]}, **light_node,
                          extensions={"KHR_lights_punctual": {"light": 0}}))
    nodes = [0, 1]
    if blocker:
        down, down_tris = quad([(-0.5, 1, -0.5), (0.5, 1, -0.5), (0.5, 1, 0.5), (-0.5, 1, 0.5)], (0, -1, 0))
        up, up_tris = quad([(-0.5, 1, 0.5), (0.5, 1, 0.5), (0.5, 1, -0.5), (-0.5, 1, -0.5)], (0, 1, 0))
        prim = {"attributes": {"POSITION": doc.positions(down + up)},
                "indices": doc.indices(flatten(down_tris) + [i + 4 for i in flatten(up_tris)], UNSIGNED_SHORT),
                "material": 0}
        doc.add("meshes", {"name": "blocker", "primitives": [prim]})
        nodes.append(doc.add("nodes", {"name": "blocker", "mesh": 1}))
    doc.j["scene"] = 0
    doc.add("scenes", {"name": os.path.splitext(file)[0], "nodes": nodes})
    doc.write_gltf(file)


def lights():
    white = [1.0, 1.0, 1.0]
    light_scene("point_light.gltf", {"name": "bulb", "type": "point", "color": white, "intensity": 683.0},
                {"translation": [0.0, 2.0, 0.0]})
    light_scene("spot_light.gltf", {"name": "spot", "type": "spot", "color": white, "intensity": 683.0,
                                    "spot": {"innerConeAngle": 0.25, "outerConeAngle": 0.5}},
                {"translation": [0.0, 2.0, 0.0], "rotation": ROT_X_MINUS_90})
    light_scene("directional_light.gltf", {"name": "sun", "type": "directional", "color": white,
                                           "intensity": 683.0},
                {"rotation": ROT_X_MINUS_90}, blocker=True)


# ---------------------------------------------------------------- 5. alpha

SQUARE = [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)]  # facing +Z
SQUARE_UV = [(0, 1), (1, 1), (1, 0), (0, 0)]               # v runs down the image


def alpha_doc(image, mode, cutoff, alpha):
    doc = Doc()
    m = pbr([1, 1, 1, alpha], 0, 1)
    m["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
    material = dict({"name": mode.lower()}, **m, alphaMode=mode)
    if cutoff is not None:
        material["alphaCutoff"] = cutoff
    doc.add("materials", material)
    quad_mesh(doc, "quad", SQUARE, (0, 0, 1), 0, SQUARE_UV)
    doc.add("nodes", {"name": "quad", "mesh": 0})
    doc.j["scene"] = 0
    doc.add("scenes", {"name": "alpha", "nodes": [0]})
    doc.add("samplers", {"magFilter": NEAREST, "wrapS": CLAMP_TO_EDGE, "wrapT": CLAMP_TO_EDGE})
    doc.add("textures", {"sampler": 0, "source": 0})
    if image == "bufferView":
        doc.png_view(read_bytes("mask_alpha.png"))
    else:
        doc.add("images", {"uri": image})
    return doc


def alpha():
    write_png(os.path.join(HERE, "mask_alpha.png"), 8, 8,
              [[c for x in range(8) for c in (255, 255, 255, 255 if x < 4 else 0)] for _ in range(8)], 4)
    alpha_doc("bufferView", "MASK", 0.5, 1.0).write_glb("mask.glb")
    alpha_doc("mask_alpha.png", "MASK", 0.75, 0.5).write_gltf("mask_cutoff.gltf", "mask_cutoff.bin")
    alpha_doc("mask_alpha.png", "BLEND", None, 1.0).write_gltf("blend.gltf")


# ---------------------------------------------------------------- 6. textured

def textured():
    write_png(os.path.join(HERE, "textured_checker.png"), 4, 4,
              [[c for i in range(4) for c in (3 * (255 if (i + j) % 2 == 0 else 64,))] for j in range(4)], 3)
    write_png(os.path.join(HERE, "textured_metal_rough.png"), 4, 4,
              [[c for i in range(4) for c in (0, 128, 255 if i < 2 else 0)] for _ in range(4)], 3)
    doc = Doc()
    m = pbr([1, 1, 1, 1], 1, 1)
    m["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
    m["pbrMetallicRoughness"]["metallicRoughnessTexture"] = {"index": 1}
    doc.add("materials", dict({"name": "textured"}, **m))
    quad_mesh(doc, "quad", SQUARE, (0, 0, 1), 0, [(2 * u, 2 * v) for u, v in SQUARE_UV])
    doc.add("nodes", {"name": "quad", "mesh": 0})
    doc.j["scene"] = 0
    doc.add("scenes", {"name": "textured", "nodes": [0]})
    doc.add("samplers", {"wrapS": REPEAT, "wrapT": MIRRORED_REPEAT})
    doc.add("textures", {"sampler": 0, "source": 0})
    doc.add("textures", {"sampler": 0, "source": 1})
    doc.add("images", {"uri": "textured_checker.png"})
    doc.add("images", {"uri": "textured_metal_rough.png"})
    doc.write_gltf("textured.gltf", "textured.bin")
    doc.j["images"][0] = {"uri": "data:image/png;base64," +
                          base64.b64encode(read_bytes("textured_checker.png")).decode("ascii")}
    doc.write_gltf("textured_data_uri.gltf", "textured.bin")  # the same bytes again


# ---------------------------------------------------------------- 7. primitives

def primitives():
    doc = Doc()
    doc.add("materials", lambertian("matte", MATTE))

    def mesh(name, prims):
        return doc.add("meshes", {"name": name, "primitives": [dict(p, material=0) for p in prims]})

    strip = [(0, 1, 0), (0, 0, 0), (1, 1, 0), (1, 0, 0), (2, 1, 0)]
    fan = [(-3, 0, 0), (-2, 0, 0), (-2, 1, 0), (-3, 1, 0), (-4, 1, 0)]
    # Every triangle the spec's rules make faces +Z.
    for i in range(3):
        a, b, c = i, i + 1 + i % 2, i + 2 - i % 2
        assert facing(strip[a], strip[b], strip[c])[2] > 0
        assert facing(fan[i + 1], fan[i + 2], fan[0])[2] > 0
    mesh("strip", [{"attributes": {"POSITION": doc.positions(strip)}, "mode": TRIANGLE_STRIP}])
    mesh("fan", [{"attributes": {"POSITION": doc.positions(fan)}, "mode": TRIANGLE_FAN}])
    square, square_tris = quad([(0, 2, 0), (1, 2, 0), (1, 3, 0), (0, 3, 0)], (0, 0, 1))
    mesh("mixed", [
        {"attributes": {"POSITION": doc.positions(square)},
         "indices": doc.indices(flatten(square_tris), UNSIGNED_BYTE), "mode": TRIANGLES},
        {"attributes": {"POSITION": doc.positions([(4, 0, 0), (5, 0, 0), (6, 0, 0)])}, "mode": POINTS},
        {"attributes": {"POSITION": doc.positions([(4, 1, 0), (5, 1, 0), (4, 2, 0), (5, 2, 0)])}, "mode": LINES},
    ])
    shared = [(0, -2, 0), (1, -2, 0), (0, -1, 0)]
    assert facing(*shared)[2] > 0
    mesh("shared", [{"attributes": {"POSITION": doc.positions(shared)}}])
    for k, name in enumerate(["strip", "fan", "mixed"]):
        doc.add("nodes", {"name": name, "mesh": k})
    doc.add("nodes", {"name": "shared_a", "mesh": 3, "translation": [0.0, 0.0, 0.0]})
    doc.add("nodes", {"name": "shared_b", "mesh": 3, "translation": [3.0, 0.0, 0.0]})
    doc.j["scene"] = 0
    doc.add("scenes", {"name": "primitives", "nodes": [0, 1, 2, 3, 4]})
    doc.write_gltf("primitives.gltf")


# ---------------------------------------------------------------- 8. extensions

def extensions():
    doc = Doc()

    def material(name, **more):
        m = dict({"name": name}, **pbr(WHITE, 0, 1))
        m.update(more)
        return doc.add("materials", m)

    material("normal_texture", normalTexture={"index": 0})
    material("occlusion_texture", occlusionTexture={"index": 0})
    material("clearcoat", extensions={"KHR_materials_clearcoat": {"clearcoatFactor": 1.0,
                                                                  "clearcoatRoughnessFactor": 0.25}})
    material("sheen", extensions={"KHR_materials_sheen": {"sheenColorFactor": [1.0, 1.0, 1.0],
                                                          "sheenRoughnessFactor": 0.5}})
    k = material("texture_transform")
    doc.j["materials"][k]["pbrMetallicRoughness"]["baseColorTexture"] = {
        "index": 0, "extensions": {"KHR_texture_transform": {"offset": [0.5, 0.0], "scale": [2.0, 2.0]}}}
    material("volume", extensions={"KHR_materials_volume": {"thicknessFactor": 0.25}})
    k = material("texcoord_1")
    doc.j["materials"][k]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0, "texCoord": 1}
    material("plain")

    verts, tris = quad([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], (0, 0, 1))
    pos = doc.positions(verts)
    uv0 = doc.texcoords([(0, 1), (1, 1), (1, 0), (0, 0)])
    uv1 = doc.texcoords([(0, 0.5), (0.5, 0.5), (0.5, 0), (0, 0)])
    idx = doc.indices(flatten(tris), UNSIGNED_SHORT)
    for k in range(8):
        attributes = {"POSITION": pos}
        if k in (0, 1, 4, 6):  # the materials with a texture
            attributes["TEXCOORD_0"] = uv0
        if k == 6:
            attributes["TEXCOORD_1"] = uv1
        doc.add("meshes", {"name": "quad_%d" % k, "primitives": [{"attributes": attributes, "indices": idx,
                                                                    "material": k}]})
    for k in range(7):
        doc.add("nodes", {"name": "quad_%d" % k, "mesh": k, "translation": [2.0 * k, 0.0, 0.0]})
    doc.add("nodes", {"name": "other_scene_quad", "mesh": 7, "translation": [0.0, 2.0, 0.0]})
    doc.j["scene"] = 0
    doc.add("scenes", {"name": "main", "nodes": list(range(7))})
    doc.add("scenes", {"name": "other", "nodes": [7]})
    doc.add("textures", {"source": 0})
    doc.png_view(read_bytes("textured_checker.png"))
    doc.write_gltf("extensions.gltf")


def main():
    nested_cube()
    twin()
    cameras()
    lights()
    alpha()
    textured()  # before extensions(), which embeds textured_checker.png
    primitives()
    extensions()


if __name__ == "__main__":
    main()
