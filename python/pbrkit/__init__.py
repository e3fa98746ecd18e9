"""pbrkit from Python: load glTF scenes, render them with the path tracer (ground truth)
or the OpenGL renderer, bake image-based lighting, denoise, compare and tone map, with
numpy arrays in and out.

Images are float32 arrays of shape (H, W, C) (or (H, W) for one channel), row 0 at the
top, linear values unless a function says otherwise. Every long call releases the GIL
(two renders in two threads run at once), reports through an optional
``progress(fraction, detail)`` callable (return False to stop early and get what is done)
and raises KeyboardInterrupt promptly on Ctrl-C. Library errors raise ``pbrkit.Error``
with the library's message (the file, the JSON path, the problem).
"""

from __future__ import annotations

import os as _os

from . import _pbrkit
from ._pbrkit import (  # noqa: F401  (re-exported)
    Camera,
    Error,
    Scene,
    D,
    F,
    G,
    albedo,
    builtin_scenes,
    compare,
    look_at,
    read_exr_layers,
    tonemap,
    tonemappers,
    write_image,
)

__all__ = [
    "Camera", "Error", "Scene", "D", "F", "G", "albedo", "bake", "builtin_scenes", "compare",
    "denoise", "load", "look_at", "read_exr_layers", "read_image", "render", "tonemap",
    "tonemappers", "write_image",
]


def _existing(path, what="file"):
    path = _os.fspath(path)
    if not _os.path.exists(path):
        raise FileNotFoundError(2, f"no such {what}", path)
    return path


def load(path_or_builtin_name) -> Scene:
    """Loads a .gltf/.glb file, or a built-in scene by name (``pbrkit.builtin_scenes()``)."""
    name = _os.fspath(path_or_builtin_name)
    if not (name in builtin_scenes() or name.startswith("builtin:")):
        _existing(name)
    return _pbrkit._load(name)


def read_image(path):
    """Reads an EXR, HDR, PNG or JPEG as a float32 array (linear; the EXR's main layer)."""
    return _pbrkit.read_image(_existing(path))


def _env_arg(env):
    if env is None or isinstance(env, str) and env == "builtin":
        return env
    if isinstance(env, (str, _os.PathLike)):
        return _existing(env)
    return env


def render(scene, renderer="path", *, width=None, height=None, spp=None, seed=None,
           env="builtin", env_rotation=0.0, env_intensity=1.0, camera=None,
           model="reference", multiscatter=None, max_bounces=None, time=None,
           noise_threshold=None, threads=None, denoise=None, denoiser=None, aovs=None,
           light_sampler=None, guiding=None, variant=None, animation=None,
           animation_time=0.0, shutter=None, progress=None):
    """Renders ``scene`` (a Scene, a file path or a built-in name) and returns the linear
    RGB image as a float32 (H, W, 3) array; with ``aovs`` (any of "albedo", "normal",
    "depth", "samples", "noise") returns ``(image, {name: array})``.

    The defaults are ``pbrkit render``'s: for the same scene, options and seed the array
    equals the EXR the command writes. ``renderer`` is "path" (the Monte Carlo path tracer)
    or "gl" (the real-time OpenGL renderer, headless). ``env`` is "builtin" (pbrkit's
    default environment), a path to an .exr/.hdr, an (H, 2H, 3) float32 array of linear
    radiance (equirectangular, row 0 the zenith), or None for no environment light.
    ``camera`` is None (the scene's first camera, or automatic framing), a camera index, or
    a ``pbrkit.Camera`` (``look_at``). Path tracer only (an error with "gl", as on the
    command line): ``spp`` (1024), ``seed`` (0), ``max_bounces`` (24), ``time`` (seconds,
    0: no limit), ``noise_threshold`` (adaptive sampling, 0.02; 0 turns it off),
    ``threads`` (0: all cores), ``light_sampler`` ("bvh", the light BVH, or "power"),
    ``guiding`` ("off", the default, or "on": path guiding, docs/MODEL.md), ``denoise``, ``denoiser`` ("classic", the default: the feature-guided filter of
    docs/DENOISER.md; or "learned", the trained network of docs/LEARNED_DENOISER.md) and
    ``aovs`` (with ``denoise``, the raw image is the AOV "raw"). ``variant`` is a material
    variant of the file (KHR_materials_variants; ``Scene.variants`` lists them), by name or
    index; None renders each primitive's own material. ``animation`` (a name or index of
    ``Scene.animations``) and ``animation_time`` (seconds, clamped to its keys) pose a copy
    of the scene for this render, as ``pbrkit render --animation --animation-time`` does;
    None renders the Scene as it is (its rest pose, or ``Scene.pose()``'s). ``shutter``
    (with ``animation``): ``(open, close)`` seconds around ``animation_time``, as
    ``--shutter OPEN:CLOSE``: the path tracer renders the motion blur, the OpenGL renderer
    the shutter's centre.
    """
    if not isinstance(scene, Scene):
        scene = load(scene)
    path = _pbrkit._PathArgs()
    for name, value in (("spp", spp), ("seed", seed), ("max_bounces", max_bounces),
                        ("time", time), ("noise_threshold", noise_threshold),
                        ("threads", threads), ("denoise", denoise), ("denoiser", denoiser),
                        ("light_sampler", light_sampler), ("guiding", guiding)):
        if value is not None:
            setattr(path, name, value)
    if aovs is not None:
        path.aovs = [aovs] if isinstance(aovs, str) else list(aovs)
    return _pbrkit._render(scene, renderer, width, height, _env_arg(env), float(env_rotation),
                           float(env_intensity), camera, model, multiscatter, progress, path,
                           variant, animation, float(animation_time), shutter)


def denoise(color, albedo, normal, depth, *, denoiser=None, progress=None):
    """Denoises a render from its two interleaved half buffers with ``denoiser``:
    "classic" (None: the default; docs/DENOISER.md) or "learned"
    (docs/LEARNED_DENOISER.md).

    Each argument is a pair ``(even, odd)``: the mean of the even-indexed and of the
    odd-indexed samples of each pixel, for the colour (H, W, 3), the first-hit albedo
    (H, W, 3), the shading normal (H, W, 3, XYZ in [-1, 1]) and the distance (H, W). A
    render's EXR written with ``--aov denoise`` has them as layers color_a, color_b, ...
    (``read_exr_layers``; its normals are encoded 0.5 n + 0.5). Returns the denoised
    (H, W, 3) image; when ``progress`` returns False, what it has: the halves' mean,
    undenoised.
    """
    halves = []
    for name, pair in (("color", color), ("albedo", albedo), ("normal", normal),
                       ("depth", depth)):
        if not isinstance(pair, (tuple, list)) or len(pair) != 2:
            raise TypeError(f"{name}: expected a pair (even half, odd half) of arrays")
        halves.extend(pair)
    return _pbrkit._denoise(halves, denoiser, progress)


def bake(env="builtin", *, rotation=0.0, intensity=1.0, face_size=256, samples=1024,
         irradiance_size=32, lut_size=128, model="reference", out_dir=None, progress=None):
    """Bakes image-based lighting from an environment (a path, "builtin" or an (H, 2H, 3)
    float32 array), as ``pbrkit bake`` does (Karis 2013's split sum). Returns a dict:
    "specular" (a list of GGX-prefiltered levels, each (6, S, S, 4), faces +X -X +Y -Y +Z
    -Z), "irradiance" ((6, S, S, 4)), "sh" ((9, 3) irradiance SH), "lut" ((N, N, 4): A, B,
    A+B, E_avg over n.v and roughness), "sheen" and "sheen_lut", and "environment" (the
    source as a cube with its mip chain), and "interrupted". With ``out_dir`` it also
    writes the usual KTX2, EXR, PNG and manifest files there. When ``progress`` returns
    False the bake stops early and returns what it has: "interrupted" is True, the chains
    hold the levels finished, the stages not reached are left out, and no files are written.
    """
    if out_dir is not None:
        out_dir = _os.fspath(out_dir)
    return _pbrkit._bake(_env_arg(env), float(rotation), float(intensity), face_size, samples,
                         irradiance_size, lut_size, model, out_dir, progress)
