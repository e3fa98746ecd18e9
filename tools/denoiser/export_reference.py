#!/usr/bin/env python3
"""The fixed inputs and PyTorch outputs the C++ learned denoiser is tested against.

tests/denoise/learned_denoiser_test.cpp runs src/pbrkit/denoise/learned/ (oneDNN) on
these files and compares with PyTorch's model.denoise (this directory's model.py), an
independent implementation of docs/LEARNED_DENOISER.md. Deterministic: a fixed seed, and
the files are the same on every run (the gzip stream has no time stamp).

Writes into --out (default tests/data/denoiser):
  reference.pbnn.gz      random weights, as model.write_weights writes them, gzipped. A
                         .pbnn of this network is 1.47 MB of float32 whatever its values,
                         so the weights are drawn on a coarse grid (multiples of a power of
                         two per layer, 17 levels) that deflate packs to about a quarter;
                         the grid changes nothing the C++ is tested for.
  reference_color.pfm    75x53 linear HDR colour: log-normal, a few very bright pixels
                         and a few NaN, infinite and negative ones (taken as 0)
  reference_albedo.pfm   albedo, some values outside [0, 1] and a NaN
  reference_normal.pfm   unit normals, some zero (nothing hit), some outside [-1, 1]
  reference_output.pfm   model.denoise of the three
  reference.json         the autoexposure s (model.py's and in double precision), the
                         seed, the versions, how far from uniform the kernels are
  blend_reference.pbnn.gz, blend_reference_classic.pfm, blend_reference_output.pfm
                         the same for a random kpcn-blend-v2 (seed + 1) on the same
                         colour, albedo and normal, with a stand-in for the classic
                         denoiser's output (a smooth image with a NaN and a negative pixel)

PFM (Portable Float Map): "PF\\n<width> <height>\\n-1.0\\n", then little-endian float32
RGB, rows bottom to top.

  /usr/bin/python3 tools/denoiser/export_reference.py
"""
from __future__ import annotations

import argparse
import gzip
import io
import json
import math
import sys
import tempfile
from pathlib import Path

import numpy as np
import torch

sys.path.insert(0, str(Path(__file__).resolve().parent))
import model as net  # noqa: E402

SEED = 20261129
WIDTH, HEIGHT = 75, 53  # odd: the padding to multiples of 16 is exercised
HEAD_GAIN = 32.0  # a softmax kernel's largest weight averages 0.28 (0.04 is uniform)


def quantised_uniform(gen: torch.Generator, shape: tuple[int, ...], bound: float) -> torch.Tensor:
    """Uniform in [-bound, bound], rounded to multiples of the power of two just under
    bound / 8 (at most 17 levels: few mantissa bits, which deflate compresses)."""
    step = 2.0 ** math.floor(math.log2(bound / 8.0))
    u = (torch.rand(shape, generator=gen, dtype=torch.float64) * 2.0 - 1.0) * bound
    return (torch.round(u / step) * step).float()


def random_model(gen: torch.Generator, network: str = "kpcn-unet-v1") -> net.KpcnUnet:
    """PyTorch's default Conv2d initialisation range (1/sqrt(fan_in)), quantised; the heads'
    weights scaled up so that the softmax kernels and blend weights are far from uniform."""
    model = net.KpcnUnet(network)
    with torch.no_grad():
        for name, cin, cout in model.layers:
            conv = getattr(model, name)
            bound = 1.0 / math.sqrt(cin * 9)
            gain = HEAD_GAIN if name.startswith("head") else 1.0
            conv.weight.copy_(quantised_uniform(gen, (cout, cin, 3, 3), bound) * gain)
            conv.bias.copy_(quantised_uniform(gen, (cout,), bound) * gain)
    return model


def random_inputs(rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    h, w = HEIGHT, WIDTH
    # Colour: a smooth gradient times log-normal noise (an HDR range of about 1e-3 to 1e2),
    # a few very bright pixels (fireflies), and a few that the input transform zeroes.
    yy, xx = np.mgrid[0:h, 0:w]
    base = 0.05 + 2.0 * (xx / w) * (1.0 - 0.5 * yy / h)
    color = (base[..., None] * np.exp(rng.normal(0.0, 1.2, (h, w, 3)))).astype(np.float32)
    for _ in range(6):
        color[rng.integers(h), rng.integers(w)] = rng.uniform(1e3, 1e4, 3)
    color[3, 5] = [np.nan, 1.0, 2.0]
    color[10, 60] = [np.inf, -np.inf, 0.5]
    color[40, 20] = [-3.0, 0.25, -0.01]
    # Albedo in [0, 1], with out-of-range values that are clamped and a NaN (zero).
    albedo = rng.uniform(0.0, 1.0, (h, w, 3)).astype(np.float32)
    albedo[7, 7] = [1.5, -0.2, np.nan]
    albedo[30, 70] = [np.inf, 0.5, -np.inf]
    # Unit normals, a patch with nothing hit (0) and values outside [-1, 1].
    n = rng.normal(0.0, 1.0, (h, w, 3))
    normal = (n / np.linalg.norm(n, axis=2, keepdims=True)).astype(np.float32)
    normal[45:50, 0:6] = 0.0
    normal[20, 33] = [1.7, -2.5, np.nan]
    return color, albedo, normal


def autoexposure_float64(color: np.ndarray) -> float:
    """The contract's autoexposure with every product in double precision, written apart
    from model.py's (which casts to float64 first, as the C++ does) as a check of it."""
    lum = color.astype(np.float64) @ np.array([0.2126, 0.7152, 0.0722])
    h, w = lum.shape
    logs = [math.log(m) for y in range(0, h, 16) for x in range(0, w, 16)
            if (m := lum[y:y + 16, x:x + 16].mean()) > 1e-8]
    return 0.18 / math.exp(sum(logs) / len(logs)) if logs else 1.0


def write_pfm(path: Path, image: np.ndarray) -> None:
    h, w, _ = image.shape
    rows = np.ascontiguousarray(image[::-1].astype("<f4"))  # bottom row first
    path.write_bytes(f"PF\n{w} {h}\n-1.0\n".encode() + rows.tobytes())


def write_gzipped_weights(path: Path, model: net.KpcnUnet, seed: int, check) -> None:
    """model.write_weights's file, gzipped without a time stamp; `check(read_back_model)`
    must hold for the file as read back."""
    with tempfile.TemporaryDirectory() as tmp:
        pbnn = Path(tmp) / "reference.pbnn"
        meta = net.WeightsMeta(commit="none (random weights)",
                               dataset=f"none (export_reference.py, seed {seed})", steps=0,
                               created="fixed")
        net.write_weights(pbnn, model, meta)
        buffer = io.BytesIO()
        with gzip.GzipFile(filename=path.name[:-3], mode="wb", fileobj=buffer, mtime=0) as gz:
            gz.write(pbnn.read_bytes())
        path.write_bytes(buffer.getvalue())
        back, _ = net.read_weights(pbnn)
        assert check(back)


def main() -> None:
    root = Path(__file__).resolve().parent.parent.parent
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", type=Path, default=root / "tests" / "data" / "denoiser")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)

    torch.set_num_threads(1)
    gen = torch.Generator().manual_seed(SEED)
    model = random_model(gen).eval()
    color, albedo, normal = random_inputs(np.random.default_rng(SEED))
    output = net.denoise(model, color, albedo, normal)
    exposure = net.autoexposure(net.sanitize(color))
    assert np.all(np.isfinite(output)) and np.all(output >= 0.0)

    # The file must read back as the model that made the output.
    write_gzipped_weights(args.out / "reference.pbnn.gz", model, SEED, lambda back: np.array_equal(
        net.denoise(back, color, albedo, normal), output))

    # kpcn-blend-v2: its own weights, the same inputs and a stand-in for the classic output.
    blend = random_model(torch.Generator().manual_seed(SEED + 1), "kpcn-blend-v2").eval()
    yy, xx = np.mgrid[0:HEIGHT, 0:WIDTH]
    classic = np.stack([0.1 + xx / WIDTH, 0.2 + yy / HEIGHT, 0.3 + 0.0 * xx], 2) * 1.5
    classic = classic.astype(np.float32)
    classic[12, 40] = [np.nan, 0.5, 0.5]
    classic[50, 2] = [-1.0, 0.5, 0.5]
    blend_output = net.denoise(blend, color, albedo, normal, classic)
    assert np.all(np.isfinite(blend_output)) and np.all(blend_output >= 0.0)
    write_gzipped_weights(args.out / "blend_reference.pbnn.gz", blend, SEED + 1,
                          lambda back: np.array_equal(
                              net.denoise(back, color, albedo, normal, classic), blend_output))
    write_pfm(args.out / "blend_reference_classic.pfm", classic)
    write_pfm(args.out / "blend_reference_output.pfm", blend_output)

    write_pfm(args.out / "reference_color.pfm", color)
    write_pfm(args.out / "reference_albedo.pfm", albedo)
    write_pfm(args.out / "reference_normal.pfm", normal)
    write_pfm(args.out / "reference_output.pfm", output)
    with torch.no_grad():
        x, c = net.network_input(color, albedo, normal)
        h0, h1, h2 = model.heads(torch.from_numpy(net.pad_to_multiple(x))[None])
    info = {
        "width": WIDTH, "height": HEIGHT, "seed": SEED,
        # model.py's autoexposure, which the output used, and the contract's (in double).
        "exposure": exposure, "exposure_float64": autoexposure_float64(net.sanitize(color)),
        "torch": torch.__version__, "numpy": np.__version__,
        # How far from uniform the kernels are (a uniform 5x5 kernel has weights of 0.04).
        "head0_largest_weight_mean": float(torch.softmax(h0[:, :25], 1).amax(1).mean()),
        "blend_weight_range": [float(torch.sigmoid(h[:, 25]).min()) for h in (h0, h1)] +
                              [float(torch.sigmoid(h[:, 25]).max()) for h in (h0, h1)],
    }
    (args.out / "reference.json").write_text(json.dumps(info, indent=2) + "\n")
    print(json.dumps(info, indent=2))
    for f in sorted(args.out.glob("reference*")):
        print(f"{f.name}: {f.stat().st_size} bytes")


if __name__ == "__main__":
    main()
