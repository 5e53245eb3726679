"""Writes the USD Cornell box fixtures with Pixar's own USD library (usd-core), and the same
scene as glTF, so that raygine's USD reader is checked against files it did not write.

    python3 -m venv /tmp/usd && /tmp/usd/bin/pip install usd-core
    /tmp/usd/bin/python scripts/usd/make_cornell.py assets/usd

Writes cornell.usda (text, authored with the Usd API), cornell.usdc (the same layer exported
by Sdf as crate binary), cornell.usdz (a package of the .usdc made by UsdUtils) and
cornell.gltf (the same triangles, materials, emitter and camera in glTF 2.0, written here as
JSON). Every number is exactly representable in float32 and every transform is exact (0, +-1,
dyadic translations), so both readers get bit-identical vertices.

The room: metres, Y up, x and z in -1..1, y in 0..2, open towards +z. A RectLight of 0.5 m x
0.5 m at y = 1.984375 faces down (its -Z turned to -Y), 3000 cd/m^2 x 2^exposure 1 = 6000 cd/m^2
white. The camera stands at (0, 1, 3.5) looking down -Z, focal length 30, apertures 24 x 24.
"""

import base64
import json
import math
import os
import struct
import sys

from pxr import Gf, Sdf, Usd, UsdGeom, UsdLux, UsdShade, UsdUtils

OUT = sys.argv[1] if len(sys.argv) > 1 else "assets/usd"

WHITE = (0.75, 0.75, 0.75)
RED = (0.625, 0.0625, 0.0625)
GREEN = (0.125, 0.5, 0.125)

# (name, colour, polygons as lists of corners) in world coordinates, each face wound so that its
# (v1 - v0) x (v2 - v0) faces the room's inside.
ROOM = [
    ("Floor", "White", [[(-1, 0, -1), (-1, 0, 1), (1, 0, 1), (1, 0, -1)]]),
    ("Ceiling", "White", [[(-1, 2, -1), (1, 2, -1), (1, 2, 1), (-1, 2, 1)]]),
    ("Back", "White", [[(-1, 0, -1), (1, 0, -1), (1, 2, -1), (-1, 2, -1)]]),
    ("Left", "Red", [[(-1, 0, -1), (-1, 2, -1), (-1, 2, 1), (-1, 0, 1)]]),
    ("Right", "Green", [[(1, 0, -1), (1, 0, 1), (1, 2, 1), (1, 2, -1)]]),
]


def f32(x):
    return struct.unpack("f", struct.pack("f", x))[0]


def block(cx, cz, half, height, turn_deg):
    """A box on the floor turned about y, as 5 quads (no bottom); corners rounded to float32."""
    c, s = math.cos(math.radians(turn_deg)), math.sin(math.radians(turn_deg))
    foot = [(-half, -half), (half, -half), (half, half), (-half, half)]
    ring = [(f32(cx + x * c - z * s), f32(cz + x * s + z * c)) for x, z in foot]
    low = [(x, 0.0, z) for x, z in ring]
    high = [(x, f32(height), z) for x, z in ring]
    faces = [[high[0], high[3], high[2], high[1]]]
    for i in range(4):
        j = (i + 1) % 4
        faces.append([low[i], low[j], high[j], high[i]])
    return faces


BLOCKS = [
    ("Short", "White", block(0.375, 0.25, 0.3, 0.6, -17.0)),
    ("Tall", "White", block(-0.375, -0.375, 0.3, 1.2, 17.0)),
]

# The tall block is written in its own frame under an Xform translated by TALL_AT (USD) and as
# world points (glTF): the translation is dyadic, so the sums are exact either way.
TALL_AT = (0.0, 0.0, -0.125)

LIGHT_SIZE = 0.5
LIGHT_Y = 1.984375
LIGHT_NITS = 3000.0
LIGHT_EXPOSURE = 1.0
CAMERA_AT = (0.0, 1.0, 3.5)
FOCAL = 30.0
APERTURE = 24.0


def mesh_arrays(faces):
    points, counts, indices = [], [], []
    for face in faces:
        counts.append(len(face))
        for p in face:
            indices.append(len(points))
            points.append(p)
    return points, counts, indices


def write_usd():
    stage = Usd.Stage.CreateNew(os.path.join(OUT, "cornell.usda"))
    UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.y)
    UsdGeom.SetStageMetersPerUnit(stage, 1.0)
    world = UsdGeom.Xform.Define(stage, "/World")
    stage.SetDefaultPrim(world.GetPrim())

    looks = {}
    for name, rgb in (("White", WHITE), ("Red", RED), ("Green", GREEN)):
        material = UsdShade.Material.Define(stage, f"/World/Looks/{name}")
        shader = UsdShade.Shader.Define(stage, f"/World/Looks/{name}/Surface")
        shader.CreateIdAttr("UsdPreviewSurface")
        shader.CreateInput("diffuseColor", Sdf.ValueTypeNames.Color3f).Set(Gf.Vec3f(*rgb))
        shader.CreateInput("metallic", Sdf.ValueTypeNames.Float).Set(0.0)
        shader.CreateInput("roughness", Sdf.ValueTypeNames.Float).Set(1.0)
        material.CreateSurfaceOutput().ConnectToSource(shader.ConnectableAPI(), "surface")
        looks[name] = material

    def mesh(path, faces, look, offset=(0.0, 0.0, 0.0)):
        points, counts, indices = mesh_arrays(faces)
        local = [tuple(p[k] - offset[k] for k in range(3)) for p in points]
        m = UsdGeom.Mesh.Define(stage, path)
        m.CreatePointsAttr([Gf.Vec3f(*p) for p in local])
        m.CreateFaceVertexCountsAttr(counts)
        m.CreateFaceVertexIndicesAttr(indices)
        m.CreateSubdivisionSchemeAttr(UsdGeom.Tokens.none)
        UsdShade.MaterialBindingAPI.Apply(m.GetPrim()).Bind(looks[look])
        return m

    UsdGeom.Xform.Define(stage, "/World/Room")
    for name, look, faces in ROOM:
        mesh(f"/World/Room/{name}", faces, look)
    UsdGeom.Xform.Define(stage, "/World/Blocks")
    mesh("/World/Blocks/Short", BLOCKS[0][2], "White")
    tall = UsdGeom.Xform.Define(stage, "/World/Blocks/TallPlace")
    tall.AddTranslateOp().Set(Gf.Vec3d(*TALL_AT))
    mesh("/World/Blocks/TallPlace/Tall", BLOCKS[1][2], "White", offset=TALL_AT)

    light = UsdLux.RectLight.Define(stage, "/World/Light")
    light.CreateWidthAttr(LIGHT_SIZE)
    light.CreateHeightAttr(LIGHT_SIZE)
    light.CreateIntensityAttr(LIGHT_NITS)
    light.CreateExposureAttr(LIGHT_EXPOSURE)
    light.CreateColorAttr(Gf.Vec3f(1.0, 1.0, 1.0))
    # Local -Z (the emitting side) turned to -Y: rows are the images of x, y, z (row vectors).
    light.AddTransformOp().Set(
        Gf.Matrix4d(1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, LIGHT_Y, 0, 1)
    )

    camera = UsdGeom.Camera.Define(stage, "/World/Camera")
    camera.CreateFocalLengthAttr(FOCAL)
    camera.CreateHorizontalApertureAttr(APERTURE)
    camera.CreateVerticalApertureAttr(APERTURE)
    camera.CreateClippingRangeAttr(Gf.Vec2f(0.01, 100.0))
    camera.AddTranslateOp().Set(Gf.Vec3d(*CAMERA_AT))

    stage.GetRootLayer().Save()
    stage.GetRootLayer().Export(os.path.join(OUT, "cornell.usdc"))
    cwd = os.getcwd()
    os.chdir(OUT)
    try:
        if not UsdUtils.CreateNewUsdzPackage(Sdf.AssetPath("cornell.usdc"), "cornell.usdz"):
            raise SystemExit("UsdUtils could not write cornell.usdz")
    finally:
        os.chdir(cwd)


def light_quad():
    """The RectLight's quad as raygine makes it, in world coordinates (see formats/usd)."""
    h = LIGHT_SIZE / 2
    local = [(-h, -h, 0.0), (h, -h, 0.0), (h, h, 0.0), (-h, h, 0.0)]
    world = [(x, LIGHT_Y + z, -y) for x, y, z in local]
    # Wound to face local -Z: corners 0, 2, 1 and 0, 3, 2.
    return world, [0, 2, 1, 0, 3, 2]


def write_gltf():
    blob = bytearray()
    views, accessors, meshes, nodes = [], [], [], []

    def add(data, fmt, target):
        while len(blob) % 4:
            blob.append(0)
        start = len(blob)
        for item in data:
            blob.extend(struct.pack(fmt, *item) if isinstance(item, tuple) else struct.pack(fmt, item))
        views.append({"buffer": 0, "byteOffset": start, "byteLength": len(blob) - start, "target": target})
        return len(views) - 1

    def primitive(points, indices, material):
        pv = add([tuple(map(float, p)) for p in points], "<3f", 34962)
        iv = add(indices, "<I", 34963)
        lo = [min(p[k] for p in points) for k in range(3)]
        hi = [max(p[k] for p in points) for k in range(3)]
        accessors.append({"bufferView": pv, "componentType": 5126, "count": len(points), "type": "VEC3", "min": lo, "max": hi})
        accessors.append({"bufferView": iv, "componentType": 5125, "count": len(indices), "type": "SCALAR"})
        return {"attributes": {"POSITION": len(accessors) - 2}, "indices": len(accessors) - 1, "material": material}

    names = {"White": 0, "Red": 1, "Green": 2}
    materials = [
        {"name": n, "pbrMetallicRoughness": {"baseColorFactor": [*rgb, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}}
        for n, rgb in (("White", WHITE), ("Red", RED), ("Green", GREEN))
    ]
    materials.append({
        "name": "Light",
        "pbrMetallicRoughness": {"baseColorFactor": [0.0, 0.0, 0.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0},
        "emissiveFactor": [1.0, 1.0, 1.0],
        "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": LIGHT_NITS * 2.0 ** LIGHT_EXPOSURE}},
    })

    def fan(faces):
        points, counts, corners = mesh_arrays(faces)
        tris, at = [], 0
        for n in counts:
            for i in range(1, n - 1):
                tris += [corners[at], corners[at + i], corners[at + i + 1]]
            at += n
        return points, tris

    for name, look, faces in ROOM + BLOCKS:
        points, tris = fan(faces)
        meshes.append({"name": name, "primitives": [primitive(points, tris, names[look])]})
        nodes.append({"name": name, "mesh": len(meshes) - 1})
    quad, tris = light_quad()
    meshes.append({"name": "Light", "primitives": [primitive(quad, tris, 3)]})
    nodes.append({"name": "Light", "mesh": len(meshes) - 1})
    nodes.append({"name": "Camera", "camera": 0, "translation": list(CAMERA_AT)})
    doc = {
        "asset": {"version": "2.0", "generator": "raygine scripts/usd/make_cornell.py"},
        "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength"],
        "extensions": {"KHR_lights_punctual": {"lights": []}},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": materials,
        "cameras": [{"type": "perspective", "perspective": {
            "yfov": 2.0 * math.atan(APERTURE / 2.0 / FOCAL), "aspectRatio": 1.0, "znear": 0.01, "zfar": 100.0}}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
    }
    with open(os.path.join(OUT, "cornell.gltf"), "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    write_usd()
    write_gltf()
    print("wrote cornell.usda, cornell.usdc, cornell.usdz and cornell.gltf in", OUT)
