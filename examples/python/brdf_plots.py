#!/usr/bin/env python3
"""Plots the BRDF's building blocks as the renderers evaluate them, with matplotlib:
GGX D(n.h) for several roughnesses, Smith G(n.v) at n.l = n.v for the reference and the
classic (Schlick-GGX) forms, Schlick's Fresnel for a few F0, and the directional albedo
E(mu) of the single-scattering lobe (the energy multiple-scattering compensation puts
back).

    PYTHONPATH=build/release/python python3 examples/python/brdf_plots.py -o out/brdf.png
"""

import argparse

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pbrkit  # noqa: E402


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("-o", "--output", default="out/brdf_plots.png", help="output PNG")
    a = p.parse_args()

    x = np.linspace(0.001, 1.0, 400, dtype=np.float32)
    roughnesses = [0.25, 0.5, 0.75, 1.0]
    fig, ax = plt.subplots(2, 2, figsize=(10, 8))

    for r in roughnesses:
        ax[0, 0].plot(x, pbrkit.D(x, r), label=f"roughness {r}")
    ax[0, 0].set(title="GGX D(n.h)", xlabel="n.h", yscale="log", ylim=(1e-2, 1e2))

    for r in (0.25, 0.5, 1.0):
        ax[0, 1].plot(x, pbrkit.G(x, x, r, "reference"), label=f"r={r} height-correlated")
        ax[0, 1].plot(x, pbrkit.G(x, x, r, "classic"), "--", label=f"r={r} Schlick-GGX")
    ax[0, 1].set(title="Smith G(n.v, n.l = n.v)", xlabel="n.v")

    for name, f0 in (("water", 0.02), ("glass", 0.04), ("gold (R)", 1.0), ("iron (G)", 0.53)):
        ax[1, 0].plot(x, pbrkit.F(x, f0), label=f"{name}, F0={f0}")
    ax[1, 0].set(title="Schlick Fresnel F(v.h)", xlabel="v.h")

    mu = np.linspace(0.02, 1.0, 400, dtype=np.float32)  # as `pbrkit brdf`: not at grazing
    for r in roughnesses:
        ax[1, 1].plot(mu, pbrkit.albedo(mu, r), label=f"roughness {r}")
    ax[1, 1].set(title="Directional albedo E(mu), F = 1", xlabel="mu = n.v", ylim=(0, 1.05))

    for axis in ax.flat:
        axis.legend(fontsize=7)
        axis.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(a.output, dpi=100)
    print(f"wrote {a.output}")


if __name__ == "__main__":
    main()
