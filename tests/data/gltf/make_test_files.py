#!/usr/bin/env python3
"""Writes the hand-checkable glTF test files (valid/) and the malformed corpus
(malformed/, with malformed/expected.json: file -> a substring its error must contain).
Everything here is written by hand from the glTF 2.0 specification, not by pbrkit.
Run from anywhere: python3 tests/data/gltf/make_test_files.py"""
import base64, json, math, os, struct, zlib

HERE = os.path.dirname(os.path.abspath(__file__))
VALID = os.path.join(HERE, "valid")
BAD = os.path.join(HERE, "malformed")
os.makedirs(VALID, exist_ok=True)
os.makedirs(BAD, exist_ok=True)

FLOAT, UBYTE, BYTE, USHORT, SHORT, UINT = 5126, 5121, 5120, 5123, 5122, 5125


def png(width, height, rows, declared=None):
    """RGBA8 PNG; rows = list of lists of (r, g, b, a). `declared` overrides IHDR size."""
    raw = b"".join(b"\0" + bytes(c for px in row for c in px) for row in rows)
    w, h = declared or (width, height)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def data_uri(data, mime="application/octet-stream"):
    return f"data:{mime};base64," + base64.b64encode(data).decode()


class Builder:
    """Accumulates one buffer and its views/accessors."""

    def __init__(self):
        self.data = b""
        self.gltf = {"asset": {"version": "2.0"}, "buffers": [], "bufferViews": [], "accessors": []}

    def view(self, blob, stride=None):
        while len(self.data) % 4:
            self.data += b"\0"
        v = {"buffer": 0, "byteOffset": len(self.data), "byteLength": len(blob)}
        if stride:
            v["byteStride"] = stride
        self.data += blob
        self.gltf["bufferViews"].append(v)
        return len(self.gltf["bufferViews"]) - 1

    def accessor(self, fmt, values, ctype, atype, count, normalized=False, minmax=None, stride=None):
        blob = struct.pack("<" + fmt * len(values), *values)
        a = {"bufferView": self.view(blob, stride), "componentType": ctype, "type": atype, "count": count}
        if normalized:
            a["normalized"] = True
        if minmax:
            a["min"], a["max"] = minmax
        self.gltf["accessors"].append(a)
        return len(self.gltf["accessors"]) - 1

    def finish(self, embed=True):
        self.gltf["buffers"] = [{"byteLength": len(self.data)}]
        if embed:
            self.gltf["buffers"][0]["uri"] = data_uri(self.data)
        return self.gltf


def triangle_builder():
    b = Builder()
    pos = b.accessor("f", [0, 0, 0, 1, 0, 0, 0, 1, 0], FLOAT, "VEC3", 3, minmax=([0, 0, 0], [1, 1, 0]))
    idx = b.accessor("H", [0, 1, 2], USHORT, "SCALAR", 3)
    b.gltf["meshes"] = [{"primitives": [{"attributes": {"POSITION": pos}, "indices": idx}]}]
    b.gltf["nodes"] = [{"mesh": 0}]
    b.gltf["scenes"] = [{"nodes": [0]}]
    return b


def write_json(path, obj):
    with open(path, "w") as f:
        json.dump(obj, f, indent=1)


def glb(gltf, bin_data):
    js = json.dumps(gltf).encode()
    js += b" " * (-len(js) % 4)
    bin_data += b"\0" * (-len(bin_data) % 4)
    body = struct.pack("<II", len(js), 0x4E4F534A) + js
    if bin_data:
        body += struct.pack("<II", len(bin_data), 0x004E4942) + bin_data
    return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body


# ---------------------------------------------------------------------------- valid files

# 1. Three-level hierarchy: root translates (10, 0, 0); child rotates 90 degrees about +Z
# and scales 2; grandchild translates (1, 0, 0) and holds the triangle. A vertex p maps to
# (10, 0, 0) + Rz90 * 2 * ((1, 0, 0) + p): (0,0,0) -> (10, 2, 0); (1,0,0) -> (10, 4, 0);
# (0,1,0) -> (8, 2, 0).
b = triangle_builder()
s = math.sqrt(0.5)
b.gltf["nodes"] = [
    {"name": "root", "translation": [10, 0, 0], "children": [1]},
    {"name": "child", "rotation": [0, 0, s, s], "scale": [2, 2, 2], "children": [2]},
    {"name": "grandchild", "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 1], "mesh": 0},
]
write_json(os.path.join(VALID, "hierarchy.gltf"), b.finish())

# 2. Textured quad: a 4x4 texture, texel (x, y) = (60 x, 60 y, 200, 255) in sRGB bytes,
# nearest filtering; the quad covers uv [0,1]^2. External .bin and .png files.
rows = [[(60 * x, 60 * y, 200, 255) for x in range(4)] for y in range(4)]
with open(os.path.join(VALID, "checker.png"), "wb") as f:
    f.write(png(4, 4, rows))
b = Builder()
pos = b.accessor("f", [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0], FLOAT, "VEC3", 4, minmax=([0, 0, 0], [1, 1, 0]))
uv = b.accessor("f", [0, 1, 1, 1, 1, 0, 0, 0], FLOAT, "VEC2", 4)
idx = b.accessor("H", [0, 1, 2, 0, 2, 3], USHORT, "SCALAR", 6)
b.gltf.update({
    "meshes": [{"primitives": [{"attributes": {"POSITION": pos, "TEXCOORD_0": uv}, "indices": idx, "material": 0},
                               {"attributes": {"POSITION": pos, "TEXCOORD_0": uv}, "indices": idx, "material": 1}]}],
    "materials": [
        {"name": "plain", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}},
        {"name": "transformed", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "extensions": {
            "KHR_texture_transform": {"offset": [0, 1], "rotation": 1.57079632679, "scale": [0.5, 0.5]}}}},
         "normalTexture": {"index": 0, "scale": 0.5}},
    ],
    "textures": [{"source": 0, "sampler": 0}],
    "samplers": [{"magFilter": 9728, "minFilter": 9728, "wrapS": 33071, "wrapT": 33648}],
    "images": [{"uri": "checker.png"}],
    "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}],
    "extensionsUsed": ["KHR_texture_transform"],
})
g = b.finish(embed=False)
g["buffers"][0]["uri"] = "textured_quad.bin"
with open(os.path.join(VALID, "textured_quad.bin"), "wb") as f:
    f.write(b.data)
write_json(os.path.join(VALID, "textured_quad.gltf"), g)

# 3. Strips and fans over the same 5 vertices (0..4). Strip -> (0,1,2) (1,3,2) (2,3,4);
# fan -> (1,2,0) (2,3,0) (3,4,0).
b = Builder()
pos = b.accessor("f", [0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 2, 0], FLOAT, "VEC3", 5, minmax=([0, 0, 0], [1, 2, 0]))
idx = b.accessor("B", [0, 1, 2, 3, 4], UBYTE, "SCALAR", 5)
b.gltf.update({
    "meshes": [{"primitives": [{"attributes": {"POSITION": pos}, "indices": idx, "mode": 5},
                               {"attributes": {"POSITION": pos}, "mode": 6},
                               {"attributes": {"POSITION": pos}, "mode": 1}]}],
    "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]})
write_json(os.path.join(VALID, "strip_fan.gltf"), b.finish())

# 4. KHR_mesh_quantization: SHORT normalized positions, BYTE normalized normals,
# UNSIGNED_BYTE normalized texcoords, USHORT normalized COLOR_0, and an interleaved
# (byteStride 8) SHORT position view. Expected floats are in the test.
b = Builder()
pos = b.accessor("h", [32767, 0, 0, 0, 0, 0, 0, -32768, 16384, 0], SHORT, "VEC3", 3, normalized=True,
                 stride=8, minmax=([0, -1, 0], [1, 0, 0.5]))
# stride 8: each element is 3 shorts + 2 padding bytes; rebuild the view by hand.
b.data = b.data[:b.gltf["bufferViews"][pos]["byteOffset"]]
blob = struct.pack("<3hxx3hxx3hxx", 32767, 0, 0, 0, 0, 0, 0, -32768, 16384)
b.gltf["bufferViews"][pos]["byteLength"] = len(blob)
b.data += blob
nrm = b.accessor("b", [0, 0, 127, 0, 0, 127, 0, 0, 127, 0], BYTE, "VEC3", 3, normalized=True)
uv = b.accessor("B", [0, 255, 255, 51, 0, 0], UBYTE, "VEC2", 3, normalized=True)
col = b.accessor("H", [65535, 0, 0, 65535] * 3, USHORT, "VEC4", 3, normalized=True)
b.gltf.update({
    "meshes": [{"primitives": [{"attributes": {"POSITION": pos, "NORMAL": nrm, "TEXCOORD_0": uv, "COLOR_0": col}}]}],
    "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}],
    "extensionsUsed": ["KHR_mesh_quantization"], "extensionsRequired": ["KHR_mesh_quantization"]})
write_json(os.path.join(VALID, "quantized.gltf"), b.finish())

# 5. Spec defaults: a material with no properties, a primitive with no material and no
# normals (flat normals must be generated), and no scene (all root nodes are shown).
b = triangle_builder()
b.gltf["materials"] = [{}]
b.gltf["meshes"][0]["primitives"].append(dict(b.gltf["meshes"][0]["primitives"][0], material=0))
del b.gltf["scenes"]
write_json(os.path.join(VALID, "defaults.gltf"), b.finish())

# 6. Sparse accessor: base positions of the triangle, vertex 2 replaced by (0, 5, 0); and a
# morph target (weight 0.5 by default) moving vertex 1 by (2, 0, 0) -> (2, 0, 0).
b = triangle_builder()
sidx = b.view(struct.pack("<H", 2))
sval = b.view(struct.pack("<3f", 0, 5, 0))
b.gltf["accessors"][0]["sparse"] = {"count": 1, "indices": {"bufferView": sidx, "componentType": USHORT},
                                    "values": {"bufferView": sval}}
b.gltf["accessors"][0]["max"] = [1, 5, 0]
delta = b.accessor("f", [0, 0, 0, 2, 0, 0, 0, 0, 0], FLOAT, "VEC3", 3, minmax=([0, 0, 0], [2, 0, 0]))
b.gltf["meshes"][0]["primitives"][0]["targets"] = [{"POSITION": delta}]
b.gltf["meshes"][0]["weights"] = [0.5]
write_json(os.path.join(VALID, "sparse_morph.gltf"), b.finish())

# 7. Cameras and KHR_lights_punctual: a perspective camera at (0, 0, 5), an orthographic
# one rotated to look down -Y from (0, 3, 0) with scale 4 (ignored), a point, a spot and
# a directional light.
b = triangle_builder()
b.gltf["cameras"] = [
    {"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1, "zfar": 100, "aspectRatio": 1.5}},
    {"type": "orthographic", "orthographic": {"xmag": 2, "ymag": 1, "znear": 0.01, "zfar": 10}}]
b.gltf["extensions"] = {"KHR_lights_punctual": {"lights": [
    {"type": "point", "color": [1, 0.5, 0.25], "intensity": 40, "range": 10},
    {"type": "spot", "intensity": 100, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.6}},
    {"type": "directional", "intensity": 3}]}}
b.gltf["nodes"] += [
    {"camera": 0, "translation": [0, 0, 5]},
    {"camera": 1, "translation": [0, 3, 0], "rotation": [-s, 0, 0, s], "scale": [4, 4, 4]},
    {"translation": [1, 2, 3], "extensions": {"KHR_lights_punctual": {"light": 0}}},
    {"translation": [0, 4, 0], "rotation": [-s, 0, 0, s], "extensions": {"KHR_lights_punctual": {"light": 1}}},
    {"extensions": {"KHR_lights_punctual": {"light": 2}}}]
b.gltf["scenes"] = [{"nodes": [0, 1, 2, 3, 4, 5]}]
b.gltf["extensionsUsed"] = ["KHR_lights_punctual", "EXT_fancy_optional"]
write_json(os.path.join(VALID, "cameras_lights.gltf"), b.finish())

# 8. The same triangle as a .glb with its buffer in the BIN chunk.
b = triangle_builder()
g = b.finish(embed=False)
with open(os.path.join(VALID, "triangle.glb"), "wb") as f:
    f.write(glb(g, b.data))

# ---------------------------------------------------------------------------- malformed
expected = {}


def bad(name, content, error):
    mode = "wb" if isinstance(content, bytes) else "w"
    with open(os.path.join(BAD, name), mode) as f:
        f.write(content)
    expected[name] = error


def bad_json(name, mutate, error):
    b = triangle_builder()
    g = b.finish()
    mutate(g, b)
    bad(name, json.dumps(g, indent=1), error)


b = triangle_builder()
good_glb = glb(b.finish(embed=False), b.data)
bad("truncated.glb", good_glb[: len(good_glb) // 2], "truncated GLB")
bad("header_only.glb", good_glb[:12][:8] + struct.pack("<I", 12), "no JSON chunk header")
bad("tiny.glb", good_glb[:7], "truncated GLB")
bad("wrong_magic.glb", b"glTX" + good_glb[4:], "does not start with 'glTF'")
bad("wrong_version.glb", good_glb[:4] + struct.pack("<I", 1) + good_glb[8:], "unsupported GLB version 1")
bad("length_too_long.glb", good_glb[:8] + struct.pack("<I", len(good_glb) + 100) + good_glb[12:],
    "the header says")
bad("json_chunk_too_long.glb", good_glb[:12] + struct.pack("<I", 1 << 30) + good_glb[16:],
    "JSON chunk length")
bad("first_chunk_not_json.glb", good_glb[:16] + struct.pack("<I", 0x004E4942) + good_glb[20:],
    "first GLB chunk is not JSON")
js_len = struct.unpack("<I", good_glb[12:16])[0]
bin_at = 20 + js_len
bad("bin_chunk_too_long.glb", good_glb[:bin_at] + struct.pack("<I", 1 << 20) + good_glb[bin_at + 4:],
    "exceeds the")
bad("empty.gltf", "", "invalid JSON")
bad("not_json.gltf", "{ this is not json", "invalid JSON")
bad("root_array.gltf", "[1, 2, 3]", "root is not an object")
bad_json("missing_asset.gltf", lambda g, b: g.pop("asset"), "asset: missing")
bad_json("version_1.gltf", lambda g, b: g["asset"].update(version="1.0"), "unsupported glTF version")
bad_json("accessors_not_array.gltf", lambda g, b: g.update(accessors=5), "accessors: must be an array")
bad_json("node_not_object.gltf", lambda g, b: g["nodes"].append("node"), "nodes[1]: must be an object")
bad_json("accessor_out_of_bounds.gltf", lambda g, b: g["accessors"][0].update(count=1000), "accessors[0]")
bad_json("accessor_offset_out_of_bounds.gltf", lambda g, b: g["accessors"][0].update(byteOffset=4000),
         "accessors[0]")
bad_json("index_out_of_range.gltf",
         lambda g, b: g["buffers"][0].update(uri=data_uri(b.data[:36] + struct.pack("<3H", 0, 1, 7) + b.data[42:])),
         "out of range")
bad_json("bad_byte_stride.gltf", lambda g, b: g["bufferViews"][0].update(byteStride=6), "byteStride")
bad_json("stride_smaller_than_element.gltf", lambda g, b: g["bufferViews"][0].update(byteStride=8),
         "smaller than the element size")
bad_json("buffer_view_out_of_bounds.gltf", lambda g, b: g["bufferViews"][1].update(byteLength=400),
         "bufferViews[1]")
bad_json("buffer_view_bad_buffer.gltf", lambda g, b: g["bufferViews"][1].update(buffer=3), "bufferViews[1]")
bad_json("buffer_shorter_than_declared.gltf", lambda g, b: g["buffers"][0].update(byteLength=400),
         "byteLength is 400")
bad_json("huge_buffer.gltf", lambda g, b: g["buffers"][0].update(byteLength=1 << 40), "more than the limit")
bad_json("missing_buffer_file.gltf", lambda g, b: g["buffers"][0].update(uri="missing.bin"), "does not exist")
bad_json("bad_data_uri.gltf", lambda g, b: g["buffers"][0].update(uri="data:application/octet-stream;base64,@@@@"),
         "invalid base64")
bad_json("data_uri_not_base64.gltf", lambda g, b: g["buffers"][0].update(uri="data:text/plain,hello"),
         "not base64-encoded")
bad_json("uri_escapes_folder.gltf", lambda g, b: g["buffers"][0].update(uri="../valid/textured_quad.bin"),
         "outside the asset's folder")
bad_json("uri_escapes_encoded.gltf", lambda g, b: g["buffers"][0].update(uri="%2e%2e/valid/textured_quad.bin"),
         "outside the asset's folder")
bad_json("uri_absolute.gltf", lambda g, b: g["buffers"][0].update(uri="/etc/passwd"), "absolute path")
bad_json("uri_network.gltf", lambda g, b: g["buffers"][0].update(uri="https://example.com/a.bin"), "has a scheme")
bad_json("uri_file_scheme.gltf", lambda g, b: g["buffers"][0].update(uri="file:///etc/passwd"), "has a scheme")
bad_json("image_uri_escapes.gltf", lambda g, b: g.update(images=[{"uri": "../../secret.png"}]),
         "images[0].uri")
bad_json("cyclic_nodes.gltf", lambda g, b: g.update(nodes=[{"mesh": 0, "children": [1]}, {"children": [2]},
                                                           {"children": [1]}]), "cycle")
bad_json("self_child.gltf", lambda g, b: g["nodes"][0].update(children=[0]), "its own child")
bad_json("child_out_of_range.gltf", lambda g, b: g["nodes"][0].update(children=[9]), "node 9 does not exist")
bad_json("scene_node_out_of_range.gltf", lambda g, b: g["scenes"][0].update(nodes=[4]), "node 4 does not exist")
bad_json("mesh_out_of_range.gltf", lambda g, b: g["nodes"][0].update(mesh=3), "mesh")
bad_json("unsupported_required_extension.gltf",
         lambda g, b: g.update(extensionsUsed=["KHR_physics_rigid_bodies"], extensionsRequired=["KHR_physics_rigid_bodies"]),
         "required extension 'KHR_physics_rigid_bodies' is not supported")
bad_json("material_out_of_range.gltf", lambda g, b: g["meshes"][0]["primitives"][0].update(material=5),
         "material")
bad_json("texture_out_of_range.gltf", lambda g, b: g.update(materials=[{"pbrMetallicRoughness": {
    "baseColorTexture": {"index": 3}}}]) or g["meshes"][0]["primitives"][0].update(material=0),
         "texture 3 does not exist")
bad_json("bad_primitive_mode.gltf", lambda g, b: g["meshes"][0]["primitives"][0].update(mode=9), "mode")
bad_json("indices_are_floats.gltf", lambda g, b: g["meshes"][0]["primitives"][0].update(indices=0),
         "must be SCALAR")
bad_json("position_is_vec2.gltf", lambda g, b: g["accessors"][0].update(type="VEC2"), "expected 3")
bad_json("infinite_transform.gltf", lambda g, b: g["nodes"][0].update(translation=[1e39, 0, 0]),
         "NaN or infinite")
bad_json("bad_sparse_index.gltf", lambda g, b: g["accessors"][0].update(sparse={
    # UNSIGNED_INT over the bytes 00 00 01 00 of the index view: sparse index 65536.
    "count": 1, "indices": {"bufferView": 1, "componentType": UINT}, "values": {"bufferView": 0}}),
         "out of range")
bad_json("bad_camera.gltf", lambda g, b: g.update(cameras=[{"type": "perspective", "perspective": {
    "yfov": -1, "znear": 0.1}}]) or g["nodes"][0].update(camera=0), "yfov")
bad_json("bad_light_index.gltf", lambda g, b: g["nodes"][0].update(extensions={"KHR_lights_punctual": {"light": 2}}),
         "light 2 does not exist")


def nan_positions(g, b):
    data = struct.pack("<9f", 0, 0, 0, float("nan"), 0, 0, 0, 1, 0) + b.data[36:]
    g["buffers"][0]["uri"] = data_uri(data)


bad_json("nan_position.gltf", nan_positions, "not finite")


def huge_image(g, b):
    g["images"] = [{"uri": data_uri(png(1, 1, [[(0, 0, 0, 255)]], declared=(20000, 20000)), "image/png")}]
    g["textures"] = [{"source": 0}]
    g["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
    g["meshes"][0]["primitives"][0]["material"] = 0


bad_json("absurd_image_size.gltf", huge_image, "images[0]: image size 20000 x 20000 exceeds the limit")


def garbage_image(g, b):
    g["images"] = [{"uri": data_uri(b"this is not an image", "image/png")}]
    g["textures"] = [{"source": 0}]
    g["materials"] = [{"emissiveTexture": {"index": 0}}]
    g["meshes"][0]["primitives"][0]["material"] = 0


bad_json("garbage_image.gltf", garbage_image, "images[0]")

with open(os.path.join(BAD, "expected.json"), "w") as f:
    json.dump(expected, f, indent=1, sort_keys=True)
print(f"{len(expected)} malformed files")
