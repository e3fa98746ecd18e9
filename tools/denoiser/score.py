#!/usr/bin/env python3
"""Scores training checkpoints and weights files on the benchmark's scenes, as BENCHMARKS.md
reports the trained blends: one 16-spp render of each of denoise_bench's 256x256 scenes
through the Python module (seed 7, independent of the bench's renders), against the bench's
cached 1,024-spp references, as raw / denoised relative MSE per scene and as geometric
means over the main eight and the held-out four (the forest ones and engine/city).

  build/release/bin/denoise_bench --size 256 --ref-spp 1024 --cache REFS ...   # references
  PYTHONPATH=build/release/python python3 tools/denoiser/score.py --refs REFS \\
      --assets ../shared/assets RUN/checkpoint.pt data/denoiser/kpcn-blend-v2.pbnn

The renders (with the classic denoiser's output and the AOVs) are kept in REFS/score/ and
reused. Scoring runs the network on the whole image in PyTorch (model.denoise), without the
C++ path's pass-through of the directly seen environment.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
import torch

import model as net

# (denoise_bench's cache key, scene, environment under the assets folder or None); the last
# four are held out of training.
SCENES = [
    ("spheres", "spheres", None),
    ("cornell", "cornell", None),
    ("suzi___studio", "models/suzi.glb", "hdri/studio.exr"),
    ("suzi___sunset", "models/suzi.glb", "hdri/sunset.exr"),
    ("bunny___studio", "models/bunny.glb", "hdri/studio.exr"),
    ("bunny___sunset", "models/bunny.glb", "hdri/sunset.exr"),
    ("spheres___warehouse", "spheres", "hdri/warehouse.exr"),
    ("spheres___night", "spheres", "hdri/night.exr"),
    ("suzi___forest", "models/suzi_uncompressed.glb", "hdri/forest.exr"),
    ("engine___forest", "models/2CylinderEngine/2CylinderEngine.glb", "hdri/forest.exr"),
    ("engine___city", "models/2CylinderEngine/2CylinderEngine.glb", "hdri/city.exr"),
    ("spheres___forest", "spheres", "hdri/forest.exr"),
]
HELD_OUT = 4


def inputs(key: str, scene: str, env: str | None, refs: Path, assets: Path) -> dict:
    cached = refs / "score" / f"{key}.npz"
    if cached.exists():
        return dict(np.load(cached))
    import pbrkit
    reference = refs / f"{key}_256_1024.exr"
    if not reference.exists():
        sys.exit(f"score.py: {reference}: no reference (run denoise_bench with --cache {refs})")
    path = scene if "/" not in scene else str(assets / scene)
    loaded = pbrkit.load(path)
    kw = dict(width=256, height=256, spp=16, seed=7, env=str(assets / env) if env else "builtin",
              threads=0, noise_threshold=0)
    classic, aovs = pbrkit.render(loaded, denoise=True, denoiser="classic",
                                  aovs=["albedo", "normal"], **kw)
    z = {"color": aovs["raw"], "albedo": aovs["albedo"], "normal": aovs["normal"],
         "classic": classic, "ref": np.asarray(pbrkit.read_image(str(reference)))[..., :3]}
    cached.parent.mkdir(exist_ok=True)
    np.savez(cached, **z)
    return z


def load(path: Path) -> net.KpcnUnet:
    if path.suffix == ".pbnn":
        model, _ = net.read_weights(path)
    else:
        state = torch.load(path)
        model = net.KpcnUnet(state.get("network", "kpcn-unet-v1"))
        model.load_state_dict(state["model"])
    return model.eval()


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("models", nargs="+", type=Path, help="checkpoint.pt or .pbnn files")
    ap.add_argument("--refs", required=True, type=Path, help="denoise_bench's --cache folder")
    ap.add_argument("--assets", required=True, type=Path, help="the shared assets folder")
    args = ap.parse_args()
    torch.set_num_threads(1)
    data = [inputs(key, scene, env, args.refs, args.assets) for key, scene, env in SCENES]
    models = [load(p) for p in args.models]
    ratios = []  # per scene: classic, then each model
    for (key, _, _), z in zip(SCENES, data):
        ref = z["ref"]
        error = lambda a: float(np.mean((a - ref) ** 2 / (ref ** 2 + 1e-2)))  # noqa: E731
        raw = error(z["color"])
        row = [raw / error(z["classic"])]
        with torch.no_grad():
            for m in models:
                row.append(raw / error(net.denoise(m, z["color"], z["albedo"].astype(np.float32),
                                                   z["normal"].astype(np.float32), z["classic"])))
        ratios.append(row)
        print(f"{key:22s} " + " ".join(f"{r:6.1f}x" for r in row))
    r = np.log(np.array(ratios))
    names = ["classic"] + [str(p) for p in args.models]
    for label, rows in (("main", r[:-HELD_OUT]), ("held out", r[-HELD_OUT:])):
        means = np.exp(rows.mean(axis=0))
        print(f"{label}: " + ", ".join(f"{n} {g:.2f}x" for n, g in zip(names, means)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
