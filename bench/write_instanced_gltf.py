#!/usr/bin/env python3
"""Writes a glTF 2.0 file of N plain nodes sharing one 5,696-triangle mesh (a UV sphere of
89 segments and 33 rings, as bench/instancing_bench.cpp's), on a square grid, each turned
and scaled a little (every seventh mirrored), with a camera looking across the field.

    bench/write_instanced_gltf.py OUT.gltf [N]     (N: 10000 by default)

The buffer is written beside OUT.gltf as OUT.bin. Plain nodes, no EXT_mesh_gpu_instancing:
every loader reads them, and pbrkit's path tracer shares the mesh among them.
"""
import json
import math
import os
import struct
import sys


def sphere(radius=0.4, segments=89, rings=33):
    # As pbrkit's make_uv_sphere (scene/primitives.cpp): rings + 1 rows of segments + 1
    # vertices, the degenerate triangles at the poles left out.
    positions, normals, indices = [], [], []
    for j in range(rings + 1):
        theta = math.pi * j / rings
        for i in range(segments + 1):
            phi = 2.0 * math.pi * i / segments
            n = (math.sin(theta) * math.sin(phi), math.cos(theta), math.sin(theta) * math.cos(phi))
            normals.append(n)
            positions.append(tuple(radius * c for c in n))
    row = segments + 1
    for j in range(rings):
        for i in range(segments):
            a = j * row + i
            b, c = a + 1, a + row
            d = c + 1
            if j != 0:
                indices += [a, c, b]
            if j != rings - 1:
                indices += [b, c, d]
    return positions, normals, indices


def main():
    out = sys.argv[1]
    count = int(sys.argv[2]) if len(sys.argv) > 2 else 10000
    positions, normals, indices = sphere()
    assert len(indices) // 3 == 5696, len(indices) // 3
    data = b"".join(struct.pack("<3f", *p) for p in positions)
    normal_offset = len(data)
    data += b"".join(struct.pack("<3f", *n) for n in normals)
    index_offset = len(data)
    data += struct.pack("<%dI" % len(indices), *indices)
    bin_path = os.path.splitext(out)[0] + ".bin"
    with open(bin_path, "wb") as f:
        f.write(data)
    lo = [min(p[i] for p in positions) for i in range(3)]
    hi = [max(p[i] for p in positions) for i in range(3)]
    side = math.ceil(math.sqrt(count))
    nodes = []
    for i in range(count):
        turn = ((i * 2654435761) % 1000) * 0.00628
        s = 0.8 + 0.4 * ((i * 40503) % 100) / 100.0
        nodes.append({
            "mesh": 0,
            "translation": [float(i % side), 0.4, float(i // side)],
            "rotation": [0.0, math.sin(turn / 2), 0.0, math.cos(turn / 2)],
            "scale": [-s if i % 7 == 0 else s, s * 1.2, s],
        })
    # Camera above one corner looking across the field (yaw 225 degrees, pitch down).
    e = float(side)
    eye = [-2.0, 0.25 * e + 3.0, -2.0]
    target = [0.5 * e, 0.0, 0.5 * e]
    d = [t - o for t, o in zip(target, eye)]
    yaw = math.atan2(-d[0], -d[2])
    pitch = math.atan2(d[1], math.hypot(d[0], d[2]))
    qy = [0.0, math.sin(yaw / 2), 0.0, math.cos(yaw / 2)]
    qx = [math.sin(pitch / 2), 0.0, 0.0, math.cos(pitch / 2)]
    # q = qy * qx (yaw, then pitch about the turned x axis)
    q = [
        qy[3] * qx[0] + qy[0] * qx[3] + qy[1] * qx[2] - qy[2] * qx[1],
        qy[3] * qx[1] - qy[0] * qx[2] + qy[1] * qx[3] + qy[2] * qx[0],
        qy[3] * qx[2] + qy[0] * qx[1] - qy[1] * qx[0] + qy[2] * qx[3],
        qy[3] * qx[3] - qy[0] * qx[0] - qy[1] * qx[1] - qy[2] * qx[2],
    ]
    nodes.append({"camera": 0, "translation": eye, "rotation": q})
    gltf = {
        "asset": {"version": "2.0", "generator": "pbrkit bench/write_instanced_gltf.py"},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.05}}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.5, 0.4, 1.0],
                                                "metallicFactor": 0.0, "roughnessFactor": 0.6}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2,
                                    "material": 0}]}],
        "buffers": [{"uri": os.path.basename(bin_path), "byteLength": len(data)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": normal_offset, "target": 34962},
            {"buffer": 0, "byteOffset": normal_offset, "byteLength": index_offset - normal_offset,
             "target": 34962},
            {"buffer": 0, "byteOffset": index_offset, "byteLength": len(data) - index_offset,
             "target": 34963},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
             "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5126, "count": len(normals), "type": "VEC3"},
            {"bufferView": 2, "componentType": 5125, "count": len(indices), "type": "SCALAR"},
        ],
    }
    with open(out, "w") as f:
        json.dump(gltf, f)


if __name__ == "__main__":
    main()
