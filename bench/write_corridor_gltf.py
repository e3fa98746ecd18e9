#!/usr/bin/env python3
"""Writes a glTF 2.0 many-lights scene: a corridor 100 m long and 4 m wide of N small
emissive panels 2 m above a floor, and a camera in it looking down the corridor.
No punctual lights; render it with --no-env (the scene has no environment).

    bench/write_corridor_gltf.py OUT.gltf N [--no-camera]

The panels (0.1 m squares facing down, 2 triangles each: 2N emissive triangles in all) lie
on a grid filling the ceiling plane evenly, as many across the 4 m width as keep the grid
near square (one row for N <= 25, 20 across for N = 10,000). Their colours (six hues) and
powers (a factor of 0.5 to 2) vary deterministically from panel to panel, and their
emissive strength scales with 1000 / N, so the corridor's total emitted power is about the
same at every N: what changes with N is only how many lights share it.

The camera (35 m along the corridor, 1.5 m up, pitched 20 degrees down, yfov 0.6, aspect
2) sees only the floor, from 2 m to 30 m ahead (the middle panel, the only one at N = 1,
lights it 15 m ahead; most panels are behind or far ahead): the panels stay above the
frame and the floor (40 m wide) reaches past its sides. An image error then measures the lighting alone: a tiny panel seen
directly, or the floor's edge against the black, would add the pixel filter's coverage
noise, the same for every light sampler. The buffer is written beside OUT.gltf as OUT.bin.
"""
import json
import math
import os
import struct
import sys

LENGTH = 100.0  # along -Z, from z = 0 to z = -100
WIDTH = 4.0  # the panels' x in [-2, 2]
FLOOR_WIDTH = 40.0  # wider than the camera's view
HEIGHT = 2.0  # the panels' plane
PANEL = 0.1  # panel side
HUES = [(1.0, 0.85, 0.6), (0.7, 0.85, 1.0), (1.0, 0.5, 0.3), (0.5, 1.0, 0.6),
        (0.9, 0.6, 1.0), (1.0, 1.0, 1.0)]


def panel_grid(count):
    """Columns across the width and rows along the length, cells near square."""
    columns = max(1, round(math.sqrt(count * WIDTH / LENGTH)))
    rows = math.ceil(count / columns)
    return columns, rows


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    if len(args) != 2:
        sys.exit("usage: bench/write_corridor_gltf.py OUT.gltf N [--no-camera]")
    out, count = args[0], int(args[1])
    if count < 1:
        sys.exit("bench/write_corridor_gltf.py: N must be at least 1")
    camera = "--no-camera" not in sys.argv[1:]

    # Mesh 0: the floor (up). Mesh 1: a unit panel facing down (-Y), centred on its node.
    h, f, s = 0.5 * WIDTH, 0.5 * FLOOR_WIDTH, 0.5 * PANEL
    floor = [(-f, 0.0, 0.0), (f, 0.0, 0.0), (f, 0.0, -LENGTH), (-f, 0.0, -LENGTH)]
    panel = [(-s, 0.0, -s), (s, 0.0, -s), (s, 0.0, s), (-s, 0.0, s)]
    # Counter-clockwise seen from the side the face points to (glTF: front faces CCW).
    floor_indices = [0, 1, 2, 0, 2, 3]
    panel_indices = [0, 1, 2, 0, 2, 3]
    data = b"".join(struct.pack("<3f", *p) for p in floor)
    panel_offset = len(data)
    data += b"".join(struct.pack("<3f", *p) for p in panel)
    normal_offset = len(data)
    data += struct.pack("<3f", 0.0, 1.0, 0.0) * 4 + struct.pack("<3f", 0.0, -1.0, 0.0) * 4
    index_offset = len(data)
    data += struct.pack("<12H", *(floor_indices + panel_indices))
    bin_path = os.path.splitext(out)[0] + ".bin"
    with open(bin_path, "wb") as f:
        f.write(data)

    def bounds(points):
        return ([min(p[i] for p in points) for i in range(3)],
                [max(p[i] for p in points) for i in range(3)])

    floor_lo, floor_hi = bounds(floor)
    panel_lo, panel_hi = bounds(panel)

    # One material per hue and power step: the panels share few materials and one mesh per
    # material (glTF puts the material on the primitive).
    steps = 4
    strength = 20.0 * 1000.0 / count
    materials = [{"name": "floor",
                  "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1.0],
                                           "metallicFactor": 0.0, "roughnessFactor": 1.0}}]
    meshes = [{"name": "floor", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 2},
                                                "indices": 4, "material": 0}]}]
    for hue in range(len(HUES)):
        for step in range(steps):
            power = 0.5 * 4.0 ** (step / (steps - 1))  # 0.5, 0.79, 1.26, 2
            materials.append({
                "name": "panel_%d_%d" % (hue, step),
                "pbrMetallicRoughness": {"baseColorFactor": [0.0, 0.0, 0.0, 1.0],
                                         "metallicFactor": 0.0, "roughnessFactor": 1.0},
                "emissiveFactor": list(HUES[hue]),
                "extensions": {"KHR_materials_emissive_strength": {
                    "emissiveStrength": strength * power}},
            })
            meshes.append({"name": materials[-1]["name"],
                           "primitives": [{"attributes": {"POSITION": 1, "NORMAL": 3},
                                           "indices": 5, "material": len(materials) - 1}]})

    nodes = [{"name": "floor", "mesh": 0}]
    columns, rows = panel_grid(count)
    dx, dz = WIDTH / columns, LENGTH / rows
    for i in range(count):
        row, column = divmod(i, columns)
        # A multiplicative hash picks the hue and power: varied, the same on every run.
        k = (i * 2654435761) % 4294967296
        mesh = 1 + (k >> 8) % len(HUES) * steps + (k >> 16) % steps
        nodes.append({"name": "panel_%d" % i, "mesh": mesh,
                      "translation": [-h + (column + 0.5) * dx, HEIGHT, -(row + 0.5) * dz]})
    cameras = []
    if camera:
        # 35 m in, 1.5 m up, looking down the corridor 20 degrees below the horizon: the
        # top of the frame (half of yfov 0.6 above the axis) is 2.8 degrees below it.
        pitch = math.radians(-20.0)
        nodes.append({"name": "camera", "camera": 0, "translation": [0.0, 1.5, -35.0],
                      "rotation": [math.sin(pitch / 2), 0.0, 0.0, math.cos(pitch / 2)]})
        cameras = [{"type": "perspective",
                    "perspective": {"yfov": 0.6, "aspectRatio": 2.0, "znear": 0.05}}]

    gltf = {
        "asset": {"version": "2.0", "generator": "pbrkit bench/write_corridor_gltf.py"},
        "extensionsUsed": ["KHR_materials_emissive_strength"],
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "materials": materials,
        "meshes": meshes,
        "buffers": [{"uri": os.path.basename(bin_path), "byteLength": len(data)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": normal_offset, "byteStride": 12,
             "target": 34962},
            {"buffer": 0, "byteOffset": normal_offset, "byteLength": index_offset - normal_offset,
             "byteStride": 12, "target": 34962},
            {"buffer": 0, "byteOffset": index_offset, "byteLength": len(data) - index_offset,
             "target": 34963},
        ],
        "accessors": [
            {"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 4,
             "type": "VEC3", "min": floor_lo, "max": floor_hi},
            {"bufferView": 0, "byteOffset": panel_offset, "componentType": 5126, "count": 4,
             "type": "VEC3", "min": panel_lo, "max": panel_hi},
            {"bufferView": 1, "byteOffset": 0, "componentType": 5126, "count": 4,
             "type": "VEC3"},
            {"bufferView": 1, "byteOffset": 48, "componentType": 5126, "count": 4,
             "type": "VEC3"},
            {"bufferView": 2, "byteOffset": 0, "componentType": 5123, "count": 6,
             "type": "SCALAR"},
            {"bufferView": 2, "byteOffset": 12, "componentType": 5123, "count": 6,
             "type": "SCALAR"},
        ],
    }
    if cameras:
        gltf["cameras"] = cameras
    with open(out, "w") as f:
        json.dump(gltf, f)


if __name__ == "__main__":
    main()
