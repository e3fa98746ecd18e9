#!/usr/bin/env python3
"""Renders N random views of a model with the path tracer, each with its albedo, normal
and depth AOVs, to EXR files: the start of a dataset for learning (a denoiser, an inverse
renderer). Cameras orbit the model's bounding box at random azimuths and elevations,
looking at its centre.

    PYTHONPATH=build/release/python python3 examples/python/dataset.py spheres -n 8 -o out/dataset

Each view i writes view_<i>.exr (linear RGB), view_<i>_albedo.exr, view_<i>_normal.exr
and view_<i>_depth.exr. The seed makes the set reproducible.
"""

import argparse
import math
import os
import random
import sys
import time

import numpy as np

import pbrkit


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("scene", help="a .gltf/.glb file or a built-in scene name")
    p.add_argument("-n", "--views", type=int, default=8, help="number of views (default 8)")
    p.add_argument("-o", "--output", default="out/dataset", help="output folder")
    p.add_argument("--size", type=int, default=256, help="image width and height (256)")
    p.add_argument("--spp", type=int, default=64, help="samples per pixel (64)")
    p.add_argument("--seed", type=int, default=0, help="seed of the views and the renders")
    p.add_argument("--env", default="builtin", help="environment map (default: built-in)")
    a = p.parse_args()
    if a.views < 1 or a.size < 1 or a.spp < 1:
        p.error("--views, --size and --spp must be positive")

    scene = pbrkit.load(a.scene)
    lo, hi = (np.array(v) for v in scene.bounds)
    centre, radius = (lo + hi) / 2, max(np.linalg.norm(hi - lo) / 2, 1e-3)
    os.makedirs(a.output, exist_ok=True)
    rng = random.Random(a.seed)
    start = time.perf_counter()
    for i in range(a.views):
        azimuth = rng.uniform(0, 2 * math.pi)
        elevation = rng.uniform(math.radians(5), math.radians(60))
        fov = 40.0
        distance = radius / math.sin(math.radians(fov) / 2) * 1.1
        eye = centre + distance * np.array([math.cos(elevation) * math.sin(azimuth),
                                            math.sin(elevation),
                                            math.cos(elevation) * math.cos(azimuth)])
        camera = pbrkit.look_at(eye.tolist(), centre.tolist(), fov=fov)

        def progress(fraction, detail, i=i):
            done = (i + fraction) / a.views
            bar = "#" * int(30 * done)
            elapsed = time.perf_counter() - start
            sys.stderr.write(f"\r[{bar:<30}] {100 * done:5.1f}%  view {i + 1}/{a.views}  "
                             f"{elapsed:6.1f} s")
            sys.stderr.flush()

        image, aovs = pbrkit.render(scene, camera=camera, width=a.size, height=a.size,
                                    spp=a.spp, seed=a.seed + i, env=a.env,
                                    aovs=["albedo", "normal", "depth"], progress=progress)
        stem = os.path.join(a.output, f"view_{i:04d}")
        pbrkit.write_image(stem + ".exr", image)
        for name, layer in aovs.items():
            pbrkit.write_image(f"{stem}_{name}.exr", layer)
    sys.stderr.write(f"\nwrote {a.views} views to {a.output} in "
                     f"{time.perf_counter() - start:.1f} s\n")


if __name__ == "__main__":
    main()
