"""KHR_materials_variants from Python: Scene.variants lists the file's variants, and
render(variant=) switches a copy of the scene (by name or index) without changing the
Scene itself; an unknown variant raises ValueError listing the variants."""

import base64
import json
import struct

import numpy as np
import pytest

import pbrkit


def _variants_file(tmp_path):
    """A triangle facing the camera: grey, red under "Red" (0), blue under "Blue shoe" (1)."""
    positions = struct.pack("9f", -1, -1, 0, 1, -1, 0, 0, 1, 0)

    def material(name, rgb):
        return {"name": name,
                "pbrMetallicRoughness": {"baseColorFactor": [*rgb, 1], "metallicFactor": 0}}

    gltf = {
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_materials_variants"],
        "extensions": {"KHR_materials_variants": {
            "variants": [{"name": "Red"}, {"name": "Blue shoe"}]}},
        "buffers": [{"byteLength": len(positions),
                     "uri": "data:application/octet-stream;base64,"
                            + base64.b64encode(positions).decode()}],
        "bufferViews": [{"buffer": 0, "byteLength": len(positions)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [-1, -1, 0], "max": [1, 1, 0]}],
        "materials": [material("grey", (0.5, 0.5, 0.5)), material("red", (1, 0, 0)),
                      material("blue", (0, 0, 1))],
        "meshes": [{"primitives": [{
            "attributes": {"POSITION": 0}, "material": 0,
            "extensions": {"KHR_materials_variants": {"mappings": [
                {"material": 1, "variants": [0]}, {"material": 2, "variants": [1]}]}}}]}],
        "nodes": [{"mesh": 0}],
        "scenes": [{"nodes": [0]}],
        "scene": 0,
    }
    path = tmp_path / "variants.gltf"
    path.write_text(json.dumps(gltf))
    return path


def test_render_takes_a_variant_by_name_or_index(tmp_path):
    scene = pbrkit.load(_variants_file(tmp_path))
    assert scene.variants == ["Red", "Blue shoe"]
    for renderer, extra in (("path", {"spp": 8}), ("gl", {})):
        red = pbrkit.render(scene, renderer, width=16, height=16, variant="Red", **extra)[9, 8]
        blue = pbrkit.render(scene, renderer, width=16, height=16, variant=1, **extra)[9, 8]
        assert red[0] > 10 * red[2], renderer
        assert blue[2] > 10 * blue[0], renderer
        # The Scene keeps its own materials: no variant is the file's grey.
        grey = pbrkit.render(scene, renderer, width=16, height=16, **extra)[9, 8]
        assert max(grey[0], grey[2]) < 2 * min(grey[0], grey[2]), renderer
    assert pbrkit.load("spheres").variants == []


def test_unknown_variant_raises_listing_the_variants(tmp_path):
    scene = pbrkit.load(_variants_file(tmp_path))
    with pytest.raises(ValueError, match="variants are 0 'Red', 1 'Blue shoe'"):
        pbrkit.render(scene, "gl", width=8, height=8, variant="Green")
    with pytest.raises(TypeError):
        pbrkit.render(scene, "gl", width=8, height=8, variant=1.5)
