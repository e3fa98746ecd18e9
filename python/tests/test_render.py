"""render(): the arrays equal what the CLI writes, environments given as arrays equal the
same environment from its file, and bad arguments raise the right exceptions."""

import os

import numpy as np
import pytest

import pbrkit

HERE = os.path.dirname(os.path.abspath(__file__))
NIGHT = os.path.join(HERE, "..", "..", "tests", "data", "images", "night.exr")


def test_path_tracer_array_equals_the_cli_exr_bit_for_bit(cli, tmp_path):
    out = tmp_path / "c.png"
    cli("render", "cornell", "--spp", 6, "--seed", 3, "--width", 40, "--height", 30, "--float",
        "-o", out)
    expected = pbrkit.read_image(tmp_path / "c.exr")
    image = pbrkit.render("cornell", spp=6, seed=3, width=40, height=30)
    assert image.shape == (30, 40, 3) and image.dtype == np.float32
    assert np.array_equal(image, expected)
    # A different seed is a different image: the comparison above can fail.
    other = pbrkit.render("cornell", spp=6, seed=4, width=40, height=30)
    assert not np.array_equal(other, expected)


def test_gl_array_equals_the_cli_exr_bit_for_bit(cli, tmp_path):
    out = tmp_path / "g.png"
    cli("render", "spheres", "--renderer", "gl", "--width", 48, "--height", 32, "-o", out)
    expected = pbrkit.read_image(tmp_path / "g.exr")
    image = pbrkit.render("spheres", "gl", width=48, height=32)
    assert image.shape == (32, 48, 3)
    assert np.array_equal(image, expected)


def test_aovs_come_back_as_arrays_of_the_film():
    image, aovs = pbrkit.render("cornell", spp=4, width=24, height=16,
                                aovs=["albedo", "normal", "depth", "samples"])
    assert set(aovs) == {"albedo", "normal", "depth", "samples"}
    assert aovs["albedo"].shape == (16, 24, 3) and aovs["depth"].shape == (16, 24)
    # Every pixel took 4 samples (noise_threshold stops no pixel before min_spp = spp).
    assert np.all(aovs["samples"] == 4)
    # Unit normals on average (a mean of unit vectors is at most 1 long).
    lengths = np.linalg.norm(aovs["normal"], axis=2)
    assert np.all(lengths <= 1.0 + 1e-5) and np.median(lengths) > 0.99
    # The box is 2 wide and the camera 3.8 from its centre: every first hit is within reach
    # (0 where the ray leaves through the open front beside the box; edge pixels average
    # hits and misses).
    depth = aovs["depth"]
    assert np.all((depth >= 0) & (depth < 8.0)) and depth[8, 12] > 2.5
    assert np.array_equal(image, pbrkit.render("cornell", spp=4, width=24, height=16))


def test_environment_array_equals_the_same_environment_from_its_file():
    env = pbrkit.read_image(NIGHT)
    assert env.shape == (256, 512, 3)
    kwargs = dict(spp=4, width=32, height=32, env_rotation=30.0)
    from_file = pbrkit.render("spheres", env=NIGHT, **kwargs)
    from_array = pbrkit.render("spheres", env=env, **kwargs)
    assert np.array_equal(from_file, from_array)
    darker = pbrkit.render("spheres", env=env * np.float32(0.5), **kwargs)
    assert darker.mean() < 0.75 * from_array.mean()


def test_light_sampler_matches_the_cli(cli, tmp_path):
    cli("render", "lights", "--no-env", "--spp", 2, "--width", 32, "--height", 24, "--float",
        "--light-sampler", "power", "-o", tmp_path / "l.png")
    expected = pbrkit.read_image(tmp_path / "l.exr")
    kwargs = dict(env=None, spp=2, width=32, height=24)
    assert np.array_equal(pbrkit.render("lights", light_sampler="power", **kwargs), expected)
    assert not np.array_equal(pbrkit.render("lights", **kwargs), expected)  # bvh by default


def test_guiding_matches_the_cli(cli, tmp_path):
    # Large enough for some regions to learn that their guide pays (smaller, the learned
    # BSDF share keeps every guide off and the image is the unguided one).
    cli("render", "interior", "--spp", 127, "--width", 64, "--height", 64, "--float",
        "--noise-threshold", 0, "--guiding", "on", "-o", tmp_path / "g.png")
    expected = pbrkit.read_image(tmp_path / "g.exr")
    kwargs = dict(spp=127, width=64, height=64, noise_threshold=0)
    assert np.array_equal(pbrkit.render("interior", guiding="on", **kwargs), expected)
    assert not np.array_equal(pbrkit.render("interior", **kwargs), expected)  # off by default


def test_look_at_camera_and_camera_index():
    s = pbrkit.load("cornell")
    cam = s.cameras[0]
    by_index = pbrkit.render(s, camera=0, spp=2, width=16, height=16)
    by_object = pbrkit.render(s, camera=cam, spp=2, width=16, height=16)
    assert np.array_equal(by_index, by_object)
    # Looking straight up from the floor at the ceiling's light sees it: brighter.
    up = pbrkit.look_at((0, 0.1, 0), (0, 2, 0), up=(0, 0, -1), fov=30)
    assert pbrkit.render(s, camera=up, spp=2, width=16, height=16).mean() > by_index.mean()


@pytest.mark.parametrize("kwargs, error, words", [
    (dict(renderer="gl", spp=4), ValueError, "does not take spp"),
    (dict(renderer="vulkan"), ValueError, "renderer"),
    (dict(model="phong"), ValueError, "model"),
    (dict(width=0), ValueError, "width"),
    (dict(spp=0), ValueError, "spp"),
    (dict(time=float("nan")), ValueError, "time"),
    (dict(camera=5), IndexError, "camera 5"),
    (dict(camera="front"), TypeError, "camera"),
    (dict(aovs=["beauty"]), ValueError, "beauty"),
    (dict(env=np.zeros((8, 16, 3))), TypeError, "float32"),
    (dict(env=np.zeros((8, 8, 3), np.float32)), ValueError, "2:1"),
    (dict(env=np.zeros((8, 16), np.float32)), ValueError, "3 to 4 channels"),
    (dict(env=np.zeros((16, 32, 3), np.float32)[:, :, ::-1]), ValueError, "contiguous"),
    (dict(env=np.full((8, 16, 3), np.nan, np.float32)), ValueError, "row 0, column 0"),
    (dict(env=np.full((8, 16, 3), -1.0, np.float32)), ValueError, ">= 0"),
    (dict(env="/no/such/env.exr"), FileNotFoundError, "no such file"),
    (dict(progress=42), TypeError, "progress"),
    (dict(light_sampler="uniform"), ValueError, "light_sampler"),
    (dict(renderer="gl", light_sampler="bvh"), ValueError, "light_sampler"),
    (dict(guiding="yes"), ValueError, "guiding"),
    (dict(renderer="gl", guiding="on"), ValueError, "guiding"),
])
def test_bad_arguments_raise_clear_errors(kwargs, error, words):
    args = dict(width=8, height=8)
    args.update(kwargs)
    with pytest.raises(error, match=words):
        pbrkit.render("cornell", **args)


def test_bad_files_raise(tmp_path):
    with pytest.raises(FileNotFoundError):
        pbrkit.load(tmp_path / "missing.glb")
    bad = tmp_path / "bad.gltf"
    bad.write_text('{"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], '
                   '"nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": '
                   '{"POSITION": 7}}]}]}')
    with pytest.raises(pbrkit.Error, match="bad.gltf"):
        pbrkit.load(bad)
    with pytest.raises(pbrkit.Error):
        pbrkit.load("builtin:nonexistent")
    with pytest.raises(pbrkit.Error, match="not-an-image"):
        (tmp_path / "not-an-image.exr").write_bytes(b"hello")
        pbrkit.read_image(tmp_path / "not-an-image.exr")


def test_scene_summary():
    s = pbrkit.load("spheres")
    assert s.source == "builtin:spheres"
    assert s.triangle_count > 0 and len(s.materials) == 49
    lo, hi = s.bounds
    assert all(a < b for a, b in zip(lo, hi))
    assert "cornell" in pbrkit.builtin_scenes()


def test_material_extension_factors():
    # The built-in sheen scene: its first row raises a white sheen at roughness 0.5
    # (builtin_scenes.cpp), its second row the sheen roughness under a white sheen.
    s = pbrkit.load("sheen")
    sheen = [m for m in s.materials if "KHR_materials_sheen" in m["extensions"]]
    assert sheen
    factors = [m["extension_factors"]["KHR_materials_sheen"] for m in sheen]
    assert all(set(f) == {"sheenColorFactor", "sheenRoughnessFactor"} for f in factors)
    assert any(f["sheenRoughnessFactor"] == 0.5 and f["sheenColorFactor"][0] < 1.0 for f in factors)
    assert any(f["sheenColorFactor"] == (1.0, 1.0, 1.0) and f["sheenRoughnessFactor"] != 0.5
               for f in factors)
    # A material without extensions lists none.
    plain = pbrkit.load("spheres").materials[0]
    assert plain["extensions"] == [] and plain["extension_factors"] == {}
