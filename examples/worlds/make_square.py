#!/usr/bin/env python3
"""Writes square.gltf: a small town square (60 x 60 m, metres, y up as glTF has it) with a road
across it, sidewalks, buildings round it, trees and lamp poles; one node per part, named so that
the scenario's class patterns (examples/scenarios/user_world_square.json) label it. The project's
own data (CC BY 4.0, like the rest of the built-in assets). Run: python3 make_square.py"""
import base64
import json
import math
import struct
from pathlib import Path

positions, indices, nodes, meshes = bytearray(), bytearray(), [], []
vertex_count = index_count = 0
accessors, views = [], []


def add_mesh(name, triangles_xyz, material):
    """One node and mesh from a list of triangles given in our frame (x east, y north, z up)."""
    global vertex_count, index_count
    first_pos, first_idx = len(positions), len(indices)
    lo, hi = [1e9] * 3, [-1e9] * 3
    for k, tri in enumerate(triangles_xyz):
        for x, y, z in tri:
            p = (y, z, x)  # glTF: y up; its z is our x (forward), its x our y (left)
            positions.extend(struct.pack("<3f", *p))
            lo = [min(a, b) for a, b in zip(lo, p)]
            hi = [max(a, b) for a, b in zip(hi, p)]
        indices.extend(struct.pack("<3I", 3 * k, 3 * k + 1, 3 * k + 2))
    n = 3 * len(triangles_xyz)
    views.append({"buffer": 0, "byteOffset": first_pos, "byteLength": 12 * n})
    accessors.append({"bufferView": len(views) - 1, "componentType": 5126, "count": n,
                      "type": "VEC3", "min": lo, "max": hi})
    views.append({"buffer": 0, "byteOffset": first_idx, "byteLength": 4 * n, "_index": True})
    accessors.append({"bufferView": len(views) - 1, "componentType": 5125, "count": n,
                      "type": "SCALAR"})
    meshes.append({"name": name, "primitives": [{"attributes": {"POSITION": len(accessors) - 2},
                                                 "indices": len(accessors) - 1,
                                                 "material": material}]})
    nodes.append({"name": name, "mesh": len(meshes) - 1})


def quad(a, b, c, d):  # counter-clockwise seen from outside
    return [(a, b, c), (a, c, d)]


def box(x0, y0, z0, x1, y1, z1):
    p = [(x, y, z) for z in (z0, z1) for y in (y0, y1) for x in (x0, x1)]
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    return [t for f in faces for t in quad(*(p[i] for i in f))]


def cone(cx, cy, z0, radius, height, sides=12):
    tris = []
    for k in range(sides):
        a, b = 2 * math.pi * k / sides, 2 * math.pi * (k + 1) / sides
        pa = (cx + radius * math.cos(a), cy + radius * math.sin(a), z0)
        pb = (cx + radius * math.cos(b), cy + radius * math.sin(b), z0)
        tris += [(pa, pb, (cx, cy, z0 + height)), (pb, pa, (cx, cy, z0))]
    return tris


MATERIALS = [("asphalt", [0.08, 0.08, 0.085], 0.9), ("paving", [0.42, 0.40, 0.37], 0.8),
             ("plaster", [0.62, 0.52, 0.40], 0.9), ("brick", [0.45, 0.22, 0.16], 0.9),
             ("leaves", [0.12, 0.25, 0.08], 0.9), ("bark", [0.20, 0.14, 0.09], 0.9),
             ("steel", [0.30, 0.30, 0.32], 0.4), ("grass", [0.16, 0.26, 0.10], 1.0)]
ASPHALT, PAVING, PLASTER, BRICK, LEAVES, BARK, STEEL, GRASS = range(len(MATERIALS))

add_mesh("road_main", quad((-40, -4, 0), (40, -4, 0), (40, 4, 0), (-40, 4, 0)), ASPHALT)
add_mesh("sidewalk_south", quad((-40, -12, 0.12), (40, -12, 0.12), (40, -4, 0.12),
                                (-40, -4, 0.12)) + quad((-40, -4, 0), (40, -4, 0),
                                                        (40, -4, 0.12), (-40, -4, 0.12)), PAVING)
add_mesh("sidewalk_north", quad((-40, 4, 0.12), (40, 4, 0.12), (40, 30, 0.12),
                                (-40, 30, 0.12)) + quad((40, 4, 0), (-40, 4, 0),
                                                        (-40, 4, 0.12), (40, 4, 0.12)), PAVING)
add_mesh("lawn_square", quad((-10, 12, 0.13), (10, 12, 0.13), (10, 24, 0.13), (-10, 24, 0.13)),
         GRASS)
for k, (x0, width, depth, height, material) in enumerate(
        [(-40, 14, 10, 12, PLASTER), (-24, 10, 12, 18, BRICK), (-12, 12, 9, 9, PLASTER),
         (2, 16, 11, 15, BRICK), (20, 18, 10, 11, PLASTER)]):
    add_mesh(f"building_south_{k}", box(x0, -12 - depth, 0, x0 + width, -12, height), material)
for k, (x0, width, height, material) in enumerate(
        [(-40, 16, 14, BRICK), (-22, 10, 10, PLASTER), (14, 12, 16, PLASTER), (28, 12, 9, BRICK)]):
    add_mesh(f"building_north_{k}", box(x0, 30, 0, x0 + width, 42, height), material)
for k, (x, y) in enumerate([(-14, 10), (-6, 26), (6, 26), (14, 10), (-30, 8), (30, 8)]):
    add_mesh(f"tree_{k}_crown", cone(x, y, 2.2, 2.0, 5.0), LEAVES)
    add_mesh(f"tree_{k}_trunk", box(x - 0.15, y - 0.15, 0.12, x + 0.15, y + 0.15, 2.4), BARK)
for k, x in enumerate(range(-35, 40, 14)):
    add_mesh(f"pole_lamp_{k}", box(x - 0.08, 4.6, 0.12, x + 0.08, 4.76, 6.0), STEEL)
add_mesh("ground_outside", quad((-80, -60, -0.01), (80, -60, -0.01), (80, 80, -0.01),
                                (-80, 80, -0.01)), GRASS)

data = bytes(positions) + bytes(indices)
for v in views:
    if v.pop("_index", False):
        v["byteOffset"] += len(positions)
gltf = {
    "asset": {"version": "2.0", "generator": "flowscape examples/worlds/make_square.py",
              "copyright": "FlowScape toolkit authors, CC BY 4.0"},
    "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes, "meshes": meshes,
    "materials": [{"name": n, "pbrMetallicRoughness": {"baseColorFactor": c + [1.0],
                                                       "metallicFactor": 0.0,
                                                       "roughnessFactor": r}}
                  for n, c, r in MATERIALS],
    "accessors": accessors, "bufferViews": views,
    "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64," +
                 base64.b64encode(data).decode()}]}
Path(__file__).with_name("square.gltf").write_text(json.dumps(gltf, indent=1) + "\n")
