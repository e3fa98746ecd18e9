"""glTF animations from Python: Scene.animations lists them, Scene.pose() poses the Scene,
and render(animation=, animation_time=) poses a copy for one render (both renderers); the
posed bounds and the image's motion against numbers worked out by hand; bad arguments
raise errors that name the argument."""

import base64
import json
import math
import struct

import numpy as np
import pytest

import pbrkit


def _animated_file(tmp_path):
    """A white unlit triangle (-1,-1,0) (1,-1,0) (0,1,0) on node 0, seen by a camera at
    (0, 0, 6) looking down -z with a 90 degree field of view. Two animations of node 0:
    "slide" moves it from (0,0,0) at 1 s to (4,2,0) at 3 s; "grow" scales it from 1 to 3
    and moves it from (0,0,0) to (0,0,-2), both over [0, 1] s."""
    chunks = []

    def data(fmt, *values):
        offset = sum(len(c) for c in chunks)
        chunks.append(struct.pack(fmt, *values))
        return offset, len(chunks[-1])

    accessors = []
    views = []

    def accessor(fmt, values, type_, count, minmax=None):
        offset, length = data(fmt, *values)
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": length})
        a = {"bufferView": len(views) - 1, "componentType": 5126, "count": count, "type": type_}
        if minmax:
            a["min"], a["max"] = minmax
        accessors.append(a)
        return len(accessors) - 1

    positions = accessor("9f", (-1, -1, 0, 1, -1, 0, 0, 1, 0), "VEC3", 3,
                         ([-1, -1, 0], [1, 1, 0]))
    slide_t = accessor("2f", (1, 3), "SCALAR", 2, ([1], [3]))
    slide_v = accessor("6f", (0, 0, 0, 4, 2, 0), "VEC3", 2)
    grow_t = accessor("2f", (0, 1), "SCALAR", 2, ([0], [1]))
    grow_s = accessor("6f", (1, 1, 1, 3, 3, 3), "VEC3", 2)
    grow_v = accessor("6f", (0, 0, 0, 0, 0, -2), "VEC3", 2)
    buffer = b"".join(chunks)
    gltf = {
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_materials_unlit"],
        "buffers": [{"byteLength": len(buffer),
                     "uri": "data:application/octet-stream;base64,"
                            + base64.b64encode(buffer).decode()}],
        "bufferViews": views,
        "accessors": accessors,
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1]},
                       "doubleSided": True,
                       "extensions": {"KHR_materials_unlit": {}}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": positions}, "material": 0}]}],
        "cameras": [{"type": "perspective",
                     "perspective": {"yfov": math.pi / 2, "aspectRatio": 1, "znear": 0.1}}],
        "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0, 0, 6]}],
        "animations": [
            {"name": "slide",
             "samplers": [{"input": slide_t, "output": slide_v}],
             "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}]},
            {"name": "grow",
             "samplers": [{"input": grow_t, "output": grow_s},
                          {"input": grow_t, "output": grow_v}],
             "channels": [{"sampler": 0, "target": {"node": 0, "path": "scale"}},
                          {"sampler": 1, "target": {"node": 0, "path": "translation"}}]},
        ],
        "scenes": [{"nodes": [0, 1]}],
        "scene": 0,
    }
    path = tmp_path / "animated.gltf"
    path.write_text(json.dumps(gltf))
    return path


def _bounds(scene):
    lo, hi = scene.bounds
    return np.array(lo), np.array(hi)


def _assert_bounds(scene, lo, hi):
    got_lo, got_hi = _bounds(scene)
    np.testing.assert_allclose(got_lo, lo, atol=1e-5)
    np.testing.assert_allclose(got_hi, hi, atol=1e-5)


def _centroid(image):
    """The mean pixel position (x, y) of the lit pixels (the triangle on black)."""
    ys, xs = np.nonzero(image[..., 1] > 0.5)
    assert len(xs) > 10, "the triangle is not in the image"
    return np.array([xs.mean(), ys.mean()])


def test_animations_lists_names_times_and_channels(tmp_path):
    scene = pbrkit.load(_animated_file(tmp_path))
    assert scene.animations == [
        {"name": "slide", "start": 1.0, "end": 3.0, "channels": 1},
        {"name": "grow", "start": 0.0, "end": 1.0, "channels": 2},
    ]
    assert pbrkit.load("spheres").animations == []


def test_pose_moves_the_scene_and_pose_again_is_absolute(tmp_path):
    scene = pbrkit.load(_animated_file(tmp_path))
    _assert_bounds(scene, (-1, -1, 0), (1, 1, 0))
    # slide at 2 s: half way from (0,0,0) to (4,2,0), so + (2, 1, 0).
    scene.pose("slide", 2.0)
    _assert_bounds(scene, (1, 0, 0), (3, 2, 0))
    # Before the first key and after the last the keys hold (clamped).
    scene.pose(0, 0.0)
    _assert_bounds(scene, (-1, -1, 0), (1, 1, 0))
    scene.pose("slide", 10.0)
    _assert_bounds(scene, (3, 1, 0), (5, 3, 0))
    # grow at 0.5 s: scale 2 first, then translate (0, 0, -1) (T * R * S).
    scene.pose("grow", 0.5)
    _assert_bounds(scene, (-2, -2, -1), (2, 2, -1))
    scene.pose()
    _assert_bounds(scene, (-1, -1, 0), (1, 1, 0))


@pytest.mark.parametrize("renderer,extra", [("gl", {}), ("path", {"spp": 4})])
def test_render_poses_a_copy_and_the_image_moves_by_the_pose(tmp_path, renderer, extra):
    scene = pbrkit.load(_animated_file(tmp_path))
    kw = dict(width=48, height=48, env=None, **extra)
    rest = _centroid(pbrkit.render(scene, renderer, **kw))
    # The camera sees 12 units across 48 pixels at the triangle's depth (6 away, 90 degrees):
    # 4 pixels a unit, so slide's (2, 1, 0) at 2 s is 8 pixels right and 4 up (rows go down).
    slid = _centroid(pbrkit.render(scene, renderer, animation="slide", animation_time=2.0, **kw))
    np.testing.assert_allclose(slid - rest, (8.0, -4.0), atol=0.25)
    # The Scene keeps its rest pose ...
    _assert_bounds(scene, (-1, -1, 0), (1, 1, 0))
    # ... until pose() changes it; a render without animation= renders it as posed.
    scene.pose("slide", 2.0)
    posed = _centroid(pbrkit.render(scene, renderer, **kw))
    np.testing.assert_allclose(posed, slid, atol=1e-6)
    # An index is the same animation; the render's pose replaces the Scene's.
    by_index = _centroid(pbrkit.render(scene, renderer, animation=0, animation_time=1.0, **kw))
    np.testing.assert_allclose(by_index, rest, atol=1e-6)


def test_bad_animation_arguments_name_the_argument(tmp_path):
    scene = pbrkit.load(_animated_file(tmp_path))
    with pytest.raises(ValueError, match=r"^animation: .* has no animation 'walk'; it has: "
                                         r"0 'slide' \(1 to 3 s\), 1 'grow' \(0 to 1 s\)"):
        pbrkit.render(scene, "gl", width=8, height=8, animation="walk")
    with pytest.raises(ValueError, match="^animation: .* has no animation '2'"):
        scene.pose(2)
    with pytest.raises(TypeError, match="^animation: expected None, an animation's name"):
        pbrkit.render(scene, "gl", width=8, height=8, animation=1.5)
    with pytest.raises(TypeError, match="^animation:"):
        scene.pose(True)
    with pytest.raises(ValueError, match="^animation_time: needs animation"):
        pbrkit.render(scene, "gl", width=8, height=8, animation_time=1.0)
    with pytest.raises(ValueError, match="^animation_time: expected a finite number"):
        pbrkit.render(scene, "gl", width=8, height=8, animation="slide",
                      animation_time=float("nan"))
    with pytest.raises(ValueError, match="^time: expected a finite number"):
        scene.pose("slide", float("inf"))
    with pytest.raises(ValueError, match="^animation: .* has no animations"):
        pbrkit.load("spheres").pose("walk")
    # A failed pose leaves the Scene as it was.
    _assert_bounds(scene, (-1, -1, 0), (1, 1, 0))


def test_shutter_blurs_the_path_tracers_image_around_the_pose(tmp_path):
    scene = pbrkit.load(_animated_file(tmp_path))
    kw = dict(width=48, height=48, env=None, spp=64, noise_threshold=0)
    still = pbrkit.render(scene, "path", animation="slide", animation_time=2.0, **kw)
    # slide moves at (2, 1) units/s = (8, -4) pixels/s: a 1 s shutter centred on 2 s smears
    # the triangle over 8 pixels sideways, symmetric about the still pose.
    blurred = pbrkit.render(scene, "path", animation="slide", animation_time=2.0,
                            shutter=(-0.5, 0.5), **kw)
    # The intensity-weighted centroid (a threshold's would not be a translate of the blur).
    def weighted(image):
        w = image[..., 1]
        ys, xs = np.mgrid[0:w.shape[0], 0:w.shape[1]]
        return np.array([(w * xs).sum(), (w * ys).sum()]) / w.sum()
    np.testing.assert_allclose(weighted(blurred), weighted(still), atol=0.15)
    partial = lambda image: int(np.sum((image[..., 1] > 0.2) & (image[..., 1] < 0.8)))
    assert partial(blurred) > 2 * partial(still) + 20  # 67 against 16 when written
    # The OpenGL renderer draws the shutter's centre: here the still pose at 2 s.
    centre = pbrkit.render(scene, "gl", width=48, height=48, env=None, animation="slide",
                           animation_time=1.75, shutter=(0.0, 0.5))
    gl_still = pbrkit.render(scene, "gl", width=48, height=48, env=None, animation="slide",
                             animation_time=2.0)
    np.testing.assert_allclose(centre, gl_still, atol=1e-6)
    with pytest.raises(ValueError, match="^shutter: needs animation"):
        pbrkit.render(scene, "gl", width=8, height=8, shutter=(0, 1))
    with pytest.raises(ValueError, match="^shutter: .* open < close"):
        pbrkit.render(scene, "gl", width=8, height=8, animation=0, shutter=(1, 0))
    with pytest.raises(TypeError, match="^shutter: expected"):
        pbrkit.render(scene, "gl", width=8, height=8, animation=0, shutter="0:1")
