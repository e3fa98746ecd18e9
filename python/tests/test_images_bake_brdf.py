"""Images (read, write, compare, tone map, denoise), the IBL bake and the BRDF functions,
each against a closed form or the CLI's own output."""

import math

import numpy as np
import pytest

import pbrkit


def test_exr_round_trip_is_exact(tmp_path):
    rng = np.random.default_rng(1)
    a = rng.random((7, 9, 3), dtype=np.float32) * 100
    pbrkit.write_image(str(tmp_path / "a.exr"), a)
    assert np.array_equal(pbrkit.read_image(tmp_path / "a.exr"), a)
    pbrkit.write_image(str(tmp_path / "h.exr"), a, half=True)
    h = pbrkit.read_image(tmp_path / "h.exr")
    assert np.allclose(h, a, rtol=1e-3) and not np.array_equal(h, a)


def test_png_stores_display_values_that_read_back_through_the_srgb_curve(tmp_path):
    v = np.linspace(0, 1, 16, dtype=np.float32)
    img = np.repeat(v[None, :, None], 3, axis=2).copy()
    pbrkit.write_image(str(tmp_path / "p.png"), img, bits=16)
    back = pbrkit.read_image(tmp_path / "p.png")[..., :3]
    q = np.round(v * 65535) / 65535  # what 16 bits keep
    srgb_to_linear = np.where(q <= 0.04045, q / 12.92, ((q + 0.055) / 1.055) ** 2.4)
    assert np.allclose(back[0, :, 0], srgb_to_linear, atol=2e-6)


def srgb_to_linear(q):
    return np.where(q <= 0.04045, q / 12.92, ((q + 0.055) / 1.055) ** 2.4)


def test_write_image_names_its_files_as_the_cli_does(tmp_path):
    # An .exr name writes the linear EXR and, beside it, the PNG of its display transform;
    # a .png name (any case) the display PNG and, beside it, the same image in linear light.
    rng = np.random.default_rng(2)
    linear = rng.random((5, 6, 3), dtype=np.float32) * 4
    pbrkit.write_image(str(tmp_path / "out" / "r.exr"), linear, exposure=-1.0, tonemapper="aces")
    assert np.array_equal(pbrkit.read_image(tmp_path / "out" / "r.exr"), linear)
    display = pbrkit.tonemap(linear, -1.0, "aces")
    png = pbrkit.read_image(tmp_path / "out" / "r.png")[..., :3]
    assert np.allclose(png, srgb_to_linear(np.round(display * 255) / 255), atol=1e-6)

    v = np.linspace(-0.5, 1.5, 12, dtype=np.float32)
    img = np.repeat(v[None, :, None], 3, axis=2).copy()
    pbrkit.write_image(str(tmp_path / "d.PNG"), img, bits=16)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["d.PNG", "d.exr", "out"]
    exr = pbrkit.read_image(tmp_path / "d.exr")
    assert np.allclose(exr[0, :, 0], srgb_to_linear(np.clip(v, 0, 1)), atol=1e-6)
    back = pbrkit.read_image(tmp_path / "d.PNG")[..., :3]
    assert np.allclose(back[0, :, 0], exr[0, :, 0], atol=1e-4)  # the PNG, unquantised

    pbrkit.write_image(str(tmp_path / "e.hdr"), linear)  # documented: that file alone
    assert not (tmp_path / "e.png").exists() and not (tmp_path / "e.exr").exists()
    for bad in ["x.jpg", "x", "x.exr.tmp"]:
        with pytest.raises(ValueError, match=r"must end in \.png or \.exr"):
            pbrkit.write_image(str(tmp_path / bad), linear)
    with pytest.raises(ValueError, match="bits"):
        pbrkit.write_image(str(tmp_path / "b.png"), img, bits=12)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["d.PNG", "d.exr", "e.hdr", "out"]


def test_compare_metrics_closed_forms():
    a = np.full((4, 5, 3), 0.5, np.float32)
    m = pbrkit.compare(a, a)
    assert m["rmse"] == 0 and math.isinf(m["psnr"]) and m["pixels"] == 20
    m = pbrkit.compare(a + np.float32(0.1), a)
    assert m["rmse"] == pytest.approx(0.1, rel=1e-5)
    assert m["relative_mse"] == pytest.approx(0.01 / (0.25 + 0.01), rel=1e-5)
    with pytest.raises(pbrkit.Error, match="size"):
        pbrkit.compare(a, np.zeros((4, 4, 3), np.float32))


def test_tonemap_none_is_the_srgb_encoding_of_clamped_values():
    lin = np.array([[[0.0, 0.0031308, 0.5], [1.0, 2.0, 0.2]]], np.float32)
    out = pbrkit.tonemap(lin, tonemapper="none")
    c = np.clip(lin, 0, 1)
    srgb = np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1 / 2.4) - 0.055)
    assert np.allclose(out, srgb, atol=1e-5)
    assert set(pbrkit.tonemappers()) >= {"none", "pbr-neutral", "aces", "agx"}
    # One stop up doubles the linear values before the curve.
    assert np.allclose(pbrkit.tonemap(lin * np.float32(0.25), 1.0, "none"),
                       pbrkit.tonemap(lin * np.float32(0.5), 0.0, "none"), atol=1e-6)


def test_denoise_equals_the_cli_on_the_same_half_buffers(cli, tmp_path):
    cli("render", "cornell", "--spp", 8, "--width", 32, "--height", 24, "--aov", "denoise",
        "--float", "-o", tmp_path / "n.png")
    cli("denoise", tmp_path / "n.exr", "--float", "-o", tmp_path / "d.png")
    layers = pbrkit.read_exr_layers(str(tmp_path / "n.exr"))

    def pair(name, decode=lambda x: x):
        return decode(layers[name + "_a"]), decode(layers[name + "_b"])

    normal = lambda x: np.float32(2) * x - np.float32(1)  # noqa: E731 (stored 0.5 n + 0.5)
    out = pbrkit.denoise(pair("color"), pair("albedo"), pair("normal", normal), pair("depth"))
    expected = pbrkit.read_image(tmp_path / "d.exr")
    assert out.shape == (24, 32, 3)
    assert np.array_equal(out, expected)
    with pytest.raises(TypeError, match="pair"):
        pbrkit.denoise(layers["color_a"], pair("albedo"), pair("normal"), pair("depth"))
    with pytest.raises(ValueError, match="channels"):
        pbrkit.denoise(pair("depth"), pair("albedo"), pair("normal"), pair("depth"))


def test_bake_of_a_constant_environment_is_constant_and_writes_its_files(tmp_path):
    env = np.full((16, 32, 3), 0.5, np.float32)
    maps = pbrkit.bake(env, face_size=16, samples=32, irradiance_size=8, lut_size=16,
                       out_dir=tmp_path / "bake")
    levels = maps["specular"]
    assert levels[0].shape == (6, 16, 16, 4) and len(levels) == 2  # 16 and 8 px faces
    for level in levels:
        assert np.allclose(level[..., :3], 0.5, rtol=1e-3)
    # Irradiance of uniform radiance L: E = pi L (not divided by pi, ibl/bake.h).
    assert np.allclose(maps["irradiance"][..., :3], math.pi * 0.5, rtol=1e-3)
    # SH of a constant: only the band-0 coefficient, E / Y00-weighting gives pi L there.
    assert np.allclose(maps["sh"][1:], 0, atol=1e-4)
    lut = maps["lut"]
    assert lut.shape == (16, 16, 4) and np.all(lut[..., 2] <= 1.0 + 1e-4)
    files = {p.name for p in (tmp_path / "bake").iterdir()}
    assert "manifest.json" in files and any(f.endswith(".ktx2") for f in files)
    assert maps["interrupted"] is False


# The progress callable runs on the waiting thread every 50 ms: the work below takes far
# longer, so its first False stops it midway.
def test_a_bake_stopped_by_progress_returns_the_stages_done_and_writes_nothing(tmp_path):
    rng = np.random.default_rng(1)
    env = rng.random((256, 512, 3), dtype=np.float32)
    maps = pbrkit.bake(env, face_size=256, samples=4096, out_dir=tmp_path / "bake",
                       progress=lambda f, d: False)
    assert maps["interrupted"] is True
    assert maps["environment"][0].shape == (6, 256, 256, 4)
    # Stopped after the cube or in the specular stage (seconds of work): the specular
    # levels done, if any, and no later stage.
    for m, level in enumerate(maps["specular"]):
        assert level.shape == (6, 256 >> m, 256 >> m, 4)
    assert "irradiance" not in maps and "lut" not in maps and maps["sheen"] == []
    assert not (tmp_path / "bake").exists() or not any((tmp_path / "bake").iterdir())


def test_a_denoise_stopped_by_progress_returns_the_undenoised_mean():
    rng = np.random.default_rng(2)
    size = (512, 512)
    color = tuple(rng.random(size + (3,), dtype=np.float32) for _ in range(2))
    albedo = tuple(np.full(size + (3,), 0.5, np.float32) for _ in range(2))
    normal = tuple(np.dstack([np.zeros(size), np.zeros(size), np.ones(size)]).astype(np.float32)
                   for _ in range(2))
    depth = tuple(np.full(size, 2.0, np.float32) for _ in range(2))
    out = pbrkit.denoise(color, albedo, normal, depth, progress=lambda f, d: False)
    assert np.array_equal(out, np.float32(0.5) * (color[0] + color[1]))


def test_ggx_d_integrates_to_one_over_the_projected_hemisphere():
    theta = np.linspace(0, np.pi / 2, 20001, dtype=np.float64)
    c = np.cos(theta).astype(np.float32)
    for r in (0.3, 0.6, 1.0):
        d = pbrkit.D(c, r).astype(np.float64)
        integral = np.trapz(2 * np.pi * d * np.cos(theta) * np.sin(theta), theta)
        assert integral == pytest.approx(1.0, abs=2e-3)


def test_g_and_f_and_albedo_closed_forms():
    assert pbrkit.F(1.0, 0.04) == pytest.approx(0.04)
    assert pbrkit.F(0.0, 0.04) == pytest.approx(1.0)
    assert pbrkit.F(0.5, 0.04) == pytest.approx(0.04 + 0.96 * 0.5 ** 5)
    for model in ("reference", "classic", "classic-ibl"):
        assert pbrkit.G(1.0, 1.0, 0.5, model) == pytest.approx(1.0, abs=1e-6)
        g = pbrkit.G(np.linspace(0.05, 1, 20), 0.7, 0.5, model)
        assert np.all(g <= 1.0 + 1e-6) and np.all(np.diff(g) >= -1e-6)
    # Schlick-GGX with k = (r+1)^2/8: G1 = n.v / (n.v (1-k) + k), G = G1(v) G1(l).
    k = (0.5 + 1) ** 2 / 8
    g1 = lambda x: x / (x * (1 - k) + k)  # noqa: E731
    assert pbrkit.G(0.3, 0.8, 0.5, "classic") == pytest.approx(g1(0.3) * g1(0.8), rel=1e-5)
    e = pbrkit.albedo(0.5, np.array([0.05, 0.5, 1.0], np.float32))
    assert e[0] == pytest.approx(1.0, abs=0.02) and np.all(np.diff(e) < 0) and e[-1] > 0.3
    with pytest.raises(ValueError, match="model"):
        pbrkit.G(0.5, 0.5, 0.5, "phong")


def test_the_learned_denoiser_is_chosen_by_name(cli, tmp_path):
    # render(denoise=True, denoiser=...) and denoise(denoiser=...) run the named denoiser:
    # the two differ on the same samples, and each equals the CLI's on them.
    kw = dict(width=32, height=24, spp=8, seed=2, noise_threshold=0.0)
    learned, layers = pbrkit.render("cornell", denoise=True, denoiser="learned", aovs="albedo",
                                    **kw)
    classic = pbrkit.render("cornell", denoise=True, denoiser="classic", **kw)
    assert not np.array_equal(learned, classic)
    assert np.isfinite(learned).all() and (learned >= 0).all()
    cli("render", "cornell", "--spp", 8, "--seed", 2, "--width", 32, "--height", 24,
        "--noise-threshold", 0, "--denoise", "--denoiser", "learned", "--float",
        "-o", tmp_path / "l.exr")
    assert np.array_equal(pbrkit.read_image(tmp_path / "l.exr"), learned)
    with pytest.raises(ValueError, match="denoiser must be"):
        pbrkit.render("cornell", denoise=True, denoiser="oidn", **kw)
