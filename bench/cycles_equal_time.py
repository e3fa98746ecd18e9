#!/usr/bin/python3
"""pbrkit at equal time against Blender Cycles: by default the denoiser (docs/benchmarks_archive.md,
"The denoiser at equal time against Cycles"), the built-in `spheres` under the default
environment; with `--compare guiding`, path guiding on a scene (BENCHMARKS.md, "Path
guiding"; `--scene interior`), pbrkit's raw image with guiding on and off. 256x256, 8
bounces, 2 threads. Cycles renders 256 spp; its render call's wall time T is the budget.
pbrkit gets T for its whole process (start-up, render, denoise, write): `pbrkit render
--time t` with t = T less its measured overhead. Each image is compared with its
own renderer's reference, rendered twice with different seeds (r1, r2), with the
reference's own variance subtracted ((r1 - r2)^2 / 4 estimates the variance of r, the mean
of two independent renders):

    relMSE = mean(((x - r)^2 - (r1 - r2)^2 / 4) / (r^2 + 0.01)),  r = (r1 + r2) / 2

Measuring only (Blender and the shared peers folder are not dependencies of the build or
the tests). Usage:

    bench/cycles_equal_time.py [--pbrkit build/release/bin/pbrkit] [--runs 3]
                               [--cache build/cycles_equal_time] [--ref-spp 2048]
                               [--scene spheres] [--compare denoise|guiding]
(PBRKIT_PEERS=DIR: the peers folder when it is not ../shared/peers beside the checkout)
"""
import argparse
import json
import os
import struct
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
# The shared peers folder beside the checkout (PBRKIT_PEERS elsewhere).
PEERS = os.environ.get("PBRKIT_PEERS",
                       os.path.normpath(os.path.join(HERE, "..", "..", "shared", "peers")))


def read_exr(path):
    if PEERS not in sys.path:
        sys.path.insert(0, PEERS)
    import exrio
    return exrio.read_exr(path)


def rgb(path, layer=""):
    arr, order, _, _ = read_exr(path)
    prefix = layer + "." if layer else ""
    return np.stack([arr[..., order.index(prefix + c)] for c in "RGB"], axis=-1).astype(np.float64)


def rel_mse(x, r1, r2):
    r = 0.5 * (r1 + r2)
    return float(np.mean(((x - r) ** 2 - (r1 - r2) ** 2 / 4.0) / (r * r + 0.01)))


def cycles(args, scene, env, spp, seed, out):
    stats = out + ".json"
    cmd = ["blender", "-b", "--factory-startup", "--python", os.path.join(PEERS, "cycles_render.py"),
           "--", "--scene", scene, "--env", env, "--env-convention", "pbrkit", "--width", "256",
           "--height", "256", "--spp", str(spp), "--max-bounces", "8", "--threads", "2",
           "--camera", "0", "--seed", str(seed), "--out", out, "--stats", stats]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(stats) as f:
        return json.load(f)["render_wall_s"]


def cycles_copy(scene, out):
    """A copy of the binary glTF `scene` for Cycles: Blender 3.4's importer divides a
    directional light's lux by 683 (lumens per watt) to get its sun's W/m^2, where pbrkit
    (and glTF's renderers) take the lux as the irradiance in the image's units; the copy's
    suns carry 683 times the intensity, so that both renderers' suns give the same
    irradiance. Other punctual lights are refused (not needed yet)."""
    with open(scene, "rb") as f:
        data = f.read()
    n = struct.unpack("<I", data[12:16])[0]
    gltf = json.loads(data[20:20 + n])
    for light in gltf.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", []):
        if light["type"] != "directional":
            raise SystemExit(f"{scene}: a {light['type']} light; only suns are converted for Cycles")
        light["intensity"] = light.get("intensity", 1.0) * 683.0
    text = json.dumps(gltf, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    rest = data[20 + n:]
    with open(out, "wb") as f:
        f.write(data[:8] + struct.pack("<II", 20 + len(text) + len(rest), len(text)) + b"JSON" +
                text + rest)


def pbrkit(args, scene, out, spp, seed, extra):
    cmd = [args.pbrkit, "render", scene, "--renderer", "path", "--width", "256", "--height",
           "256", "--max-bounces", "8", "--threads", "2", "--spp", str(spp), "--seed", str(seed),
           "--float", "-o", out] + extra
    start = time.monotonic()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.monotonic() - start


def median(values):
    return sorted(values)[len(values) // 2]


def overhead_of(args, scene, c, extra):
    """pbrkit's whole process less its render at the budget (load, BVH, denoise, write):
    one run with a one-second limit."""
    return pbrkit(args, scene, c("overhead.exr"), 1000000, 7,
                  ["--noise-threshold", "0", "--time", "1"] + extra) - 1


def pbrkit_in_time(args, scene, out, run, budget, extra):
    """pbrkit with render --time `budget` (at least 0.1 s) and run's seed, no adaptive stop:
    what each comparison gives the time Cycles took, less pbrkit's overhead."""
    return pbrkit(args, scene, out, 1000000, 200 + run,
                  ["--noise-threshold", "0", "--time", f"{max(0.1, budget):.3f}"] + extra)


def cycles_run(args, cycles_scene, c, refs, run):
    """Cycles at 256 spp: its render call's seconds (the budget) and relMSE."""
    t = cycles(args, cycles_scene, args.env, 256, 200 + run, c("cycles.exr"))
    return t, rel_mse(rgb(c("cycles.exr")), *refs["cycles"])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--pbrkit", default="build/release/bin/pbrkit")
    ap.add_argument("--cache", default="build/cycles_equal_time")
    ap.add_argument("--env", default="data/env/city.exr")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--ref-spp", type=int, default=2048, help="Cycles' references (pbrkit: twice)")
    ap.add_argument("--refs-only", action="store_true", help="render the cached references, stop")
    ap.add_argument("--scene", default="spheres", help="a built-in scene")
    ap.add_argument("--compare", choices=["denoise", "guiding"], default="denoise")
    ap.add_argument("--denoiser", choices=["classic", "learned"],
                    help="with --compare denoise: pbrkit's denoiser (default: render's)")
    args = ap.parse_args()
    os.makedirs(args.cache, exist_ok=True)
    c = lambda name: os.path.join(args.cache, f"{args.scene}_{name}")  # noqa: E731
    scene = c("scene.glb")
    subprocess.run([args.pbrkit, "scene", "write", args.scene, scene], check=True,
                   stdout=subprocess.DEVNULL)
    cycles_scene = c("scene_cycles.glb")
    cycles_copy(scene, cycles_scene)
    refs = {}
    for who in ("cycles", "pbrkit"):
        for seed in (101, 102):
            path = c(f"{who}_ref_{seed}.exr")
            if not os.path.exists(path):
                print(f"rendering {who}'s reference, seed {seed}...", file=sys.stderr, flush=True)
                if who == "cycles":
                    cycles(args, cycles_scene, args.env, args.ref_spp, seed, path)
                else:
                    pbrkit(args, scene, path, 2 * args.ref_spp, seed, ["--noise-threshold", "0"])
            refs.setdefault(who, []).append(rgb(path))
    if args.refs_only:
        return
    if args.compare == "guiding":
        return compare_guiding(args, c, cycles_scene, scene, refs)
    denoiser = ["--denoiser", args.denoiser] if args.denoiser else []
    overhead = overhead_of(args, scene, c, ["--denoise"] + denoiser)
    print(f"pbrkit's start-up + denoise + write: {overhead:.2f} s", flush=True)
    print("| run | Cycles 256 spp: render s | relMSE | pbrkit whole process s | raw relMSE | "
          "denoised relMSE | raw / Cycles | denoised / Cycles |")
    print("|---|---|---|---|---|---|---|---|")
    rows = []
    for run in range(args.runs):
        t, e_c = cycles_run(args, cycles_scene, c, refs, run)
        wall = pbrkit_in_time(args, scene, c("pbrkit.exr"), run, t - overhead,
                              ["--denoise"] + denoiser)
        e_raw = rel_mse(rgb(c("pbrkit.exr"), "raw"), *refs["pbrkit"])
        e_dn = rel_mse(rgb(c("pbrkit.exr")), *refs["pbrkit"])
        rows.append((e_raw / e_c, e_dn / e_c))
        print(f"| {run + 1} | {t:.2f} | {e_c:.3g} | {wall:.2f} | {e_raw:.3g} | {e_dn:.3g} | "
              f"{e_raw / e_c:.2f}x | {e_dn / e_c:.2f}x |", flush=True)
    print(f"median: raw {median([r[0] for r in rows]):.2f}x, denoised "
          f"{median([r[1] for r in rows]):.2f}x Cycles' relative MSE")


def compare_guiding(args, c, cycles_scene, scene, refs):
    overhead = overhead_of(args, scene, c, [])
    print(f"pbrkit's start-up + write: {overhead:.2f} s", flush=True)
    print("| run | Cycles 256 spp: render s | relMSE | pbrkit guided: whole process s | relMSE | "
          "unguided: s | relMSE | guided / unguided | guided / Cycles |")
    print("|---|---|---|---|---|---|---|---|---|")
    rows = []
    for run in range(args.runs):
        t, e_c = cycles_run(args, cycles_scene, c, refs, run)
        e = {}
        wall = {}
        for guiding in ("on", "off"):
            wall[guiding] = pbrkit_in_time(args, scene, c(f"pbrkit_{guiding}.exr"), run,
                                           t - overhead, ["--guiding", guiding])
            e[guiding] = rel_mse(rgb(c(f"pbrkit_{guiding}.exr")), *refs["pbrkit"])
        rows.append((e["on"] / e["off"], e["on"] / e_c))
        print(f"| {run + 1} | {t:.2f} | {e_c:.3g} | {wall['on']:.2f} | {e['on']:.3g} | "
              f"{wall['off']:.2f} | {e['off']:.3g} | {rows[-1][0]:.2f}x | {rows[-1][1]:.2f}x |",
              flush=True)
    print(f"median: guided / unguided {median([r[0] for r in rows]):.2f}x, guided / Cycles "
          f"{median([r[1] for r in rows]):.2f}x relative MSE")


if __name__ == "__main__":
    main()
