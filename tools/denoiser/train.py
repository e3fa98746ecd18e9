#!/usr/bin/env python3
"""Trains the learned denoiser (model.py) on examples from generate.py.

Noise2Noise training (Lehtinen et al. 2018): the target is an independent noisy render,
and the loss is the relative squared error whose denominator is the network's own output
without gradient (their section 3.3 for Monte Carlo renders), in the exposure-normalised
units the network sees, so that an L2-type loss trains toward the mean. Random crops,
flips, quarter turns and colour-channel permutations of the examples.

Resumable: --run DIR holds the checkpoint (the model, the optimiser, the step and both
random generators), the loss log and its curves (loss.png); a second call with the same
DIR continues from the last checkpoint. The data set may grow while training: the folder
is rescanned every --rescan steps.

  python3 tools/denoiser/train.py --data $HOME/denoiser-data --run $HOME/denoiser-run \
      --steps 20000 --export data/denoiser/kpcn-unet-v1.pbnn
"""
from __future__ import annotations

import argparse
import datetime
import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import torch
import torch.nn.functional as F

import model as net

EPS = 1e-2  # the relative loss's floor (Lehtinen et al. 2018, section 3.3)
ERROR_CAP = 100.0  # a pixel's largest relative squared error in the loss
ENERGY_BLOCK = 16  # the block of the loss's energy term, in pixels
ENERGY_WEIGHT = 10.0


class Example:
    __slots__ = ("x", "color", "classic", "target", "scale", "name", "spp")

    def __init__(self, path: Path, with_classic: bool, raw_target: bool = False) -> None:
        with np.load(path) as z:
            color, albedo, normal = z["color"], z["albedo"], z["normal"]
            # A set made with --denoised-targets keeps the raw target too.
            target = z["target_raw"] if raw_target and "target_raw" in z.files else z["target"]
            if with_classic and "classic" not in z.files:
                raise ValueError("no classic output (rendered before generate.py kept it)")
            classic = z["classic"] if with_classic else None
            self.spp = int(json.loads(str(z["meta"])).get("spp", 0)) if "meta" in z.files else 0
        c = net.sanitize(color)
        self.scale = net.autoexposure(c)
        self.x, self.color = net.network_input(c, albedo.astype(np.float32),
                                               normal.astype(np.float32), self.scale, classic)
        # Without it, the colour stands in (never read by kpcn-unet-v1): one batch layout.
        self.classic = (np.ascontiguousarray(net.sanitize(classic).transpose(2, 0, 1))
                        if classic is not None else self.color)
        self.target = np.ascontiguousarray(net.sanitize(target).transpose(2, 0, 1))
        self.name = path.name


class DataSet:
    def __init__(self, folder: Path, limit: int = 0, with_classic: bool = False,
                 min_spp: int = 1, raw_target: bool = False) -> None:
        self.folder = folder
        self.limit = limit
        self.with_classic = with_classic
        self.min_spp = min_spp
        self.raw_target = raw_target
        self.examples: list[Example] = []
        self.seen: set[str] = set()
        self.rescan()

    def rescan(self) -> int:
        paths = sorted(self.folder.glob("*.npz")) if self.folder.is_dir() else []
        added = 0
        for p in paths:
            if p.name in self.seen or p.name.endswith(".tmp.npz"):
                continue
            if self.limit and len(self.examples) >= self.limit:
                break
            try:
                ex = Example(p, self.with_classic, self.raw_target)
                if ex.spp < self.min_spp:
                    self.seen.add(p.name)
                    continue
                self.examples.append(ex)
            except Exception as e:  # a file being written, or damaged: skipped, and said
                print(f"train.py: {p}: skipped ({e})", file=sys.stderr)
                continue
            self.seen.add(p.name)
            added += 1
        return added


def augment(rng: np.random.Generator, ex: Example, crop: int):
    _, h, w = ex.x.shape
    y0 = int(rng.integers(0, h - crop + 1))
    x0 = int(rng.integers(0, w - crop + 1))
    sl = (slice(None), slice(y0, y0 + crop), slice(x0, x0 + crop))
    x, c, k_, t = ex.x[sl], ex.color[sl], ex.classic[sl], ex.target[sl]
    k = int(rng.integers(4))
    flip = bool(rng.integers(2))
    perm = rng.permutation(3)

    def geo(a):
        a = np.rot90(a, k, axes=(1, 2))
        return a[:, :, ::-1] if flip else a

    x = geo(x)
    parts = [x[0:3][perm], x[3:6][perm], x[6:9]]
    if x.shape[0] == 12:  # the classic output's channels
        parts.append(x[9:12][perm])
    return (np.ascontiguousarray(np.concatenate(parts, 0)), np.ascontiguousarray(geo(c)[perm]),
            np.ascontiguousarray(geo(k_)[perm]), np.ascontiguousarray(geo(t)[perm]), ex.scale)


def batch(rng, data: DataSet, size: int, crop: int):
    picks = [data.examples[int(i)] for i in rng.integers(0, len(data.examples), size)]
    parts = [augment(rng, ex, crop) for ex in picks]
    x, c, k, t = (torch.from_numpy(np.stack([p[i] for p in parts])) for i in range(4))
    s = torch.tensor([p[4] for p in parts], dtype=torch.float32).view(-1, 1, 1, 1)
    return x, c, k, t, s


def relative_loss(out: torch.Tensor, target: torch.Tensor, scale: torch.Tensor,
                  denominator: torch.Tensor | None = None) -> torch.Tensor:
    """The relative squared error per pixel, each pixel's capped at ERROR_CAP, plus
    ENERGY_WEIGHT times the relative squared error of ENERGY_BLOCK-pixel block means.

    The cap: a noisy target's rare very bright samples (a caustic path at 128 spp)
    otherwise made single batches' losses a thousand times the others' and their
    gradients drowned the rest. A cap biases toward darker outputs where the target is
    such an outlier, and a kernel-predicting network can darken by weighting its darker
    neighbours: trained with a cap of 10 and no block term, the network lost 2.5 to 3% of
    the frame's energy (13 to 27 standard errors at 64 spp). The block term is the same
    Noise2Noise loss on block means, whose noise is far smaller than a pixel's, so it
    weighs a low-frequency bias as much as the pixels' noise and still trains toward the
    mean.

    `denominator` (an image independent of the target, e.g. the classic denoiser's output
    of the input): each channel's error is divided by its square rather than by the
    output's own channel mean squared. The benchmarks' relative MSE divides by the
    reference's square per channel; the output's own value makes an output that is too
    dark where the reference is not cost far more than the benchmark says (on the shared
    models under studio the two disagreed on which of two denoised images was better by a
    factor 3.5). Being independent of the target, it keeps the Noise2Noise expectation."""
    o = out * scale
    t = target * scale
    if denominator is None:
        denom = o.detach().mean(dim=1, keepdim=True) ** 2 + EPS
    else:
        denom = (denominator * scale) ** 2 + EPS
    pixels = torch.clamp(((o - t) ** 2) / denom, max=ERROR_CAP).mean()
    ob = F.avg_pool2d(o, ENERGY_BLOCK)
    tb = F.avg_pool2d(t, ENERGY_BLOCK)
    if denominator is None:
        bdenom = ob.detach().mean(dim=1, keepdim=True) ** 2 + EPS
    else:
        bdenom = F.avg_pool2d(denominator * scale, ENERGY_BLOCK) ** 2 + EPS
    blocks = (((ob - tb) ** 2) / bdenom).mean()
    return pixels + ENERGY_WEIGHT * blocks


def batch_loss(out: torch.Tensor, target: torch.Tensor, scale: torch.Tensor,
               per_example_log: bool, denominator: torch.Tensor | None = None) -> torch.Tensor:
    """relative_loss over the batch, or (per_example_log) the mean of each example's log.

    The examples' raw errors differ by orders of magnitude (1 to 64 spp, dark and bright
    scenes): averaged as they are, the few 1- and 2-spp examples make most of the loss, and
    a network trained so is best where the input is worst (kpcn-unet-v1 at 1-2 spp beat the
    classic denoiser 9.4x to 3.7x, at 9-24 spp it lost 2.9x to 5.8x and at 25-64 spp 1.8x
    to 2.9x; docs/LEARNED_DENOISER.md). The log weighs every example's relative
    improvement alike, as the benchmarks' geometric mean of ratios does: its gradient is
    each example's divided by its own loss."""
    if not per_example_log:
        return relative_loss(out, target, scale, denominator)
    d = (lambda i: None) if denominator is None else (lambda i: denominator[i:i + 1])
    return torch.stack([torch.log(relative_loss(out[i:i + 1], target[i:i + 1], scale[i:i + 1],
                                                d(i)))
                        for i in range(out.shape[0])]).mean()


@torch.no_grad()
def evaluate(model, data: DataSet, count: int = 16) -> tuple[float, float, float]:
    """On the first `count` whole examples: the loss of the network's output and of the raw
    input against the targets (the targets' own noise is in both), and the output's mean
    relative deviation of the frame's energy from the target's (its bias)."""
    if not data.examples:
        return float("nan"), float("nan"), float("nan")
    den, raw, bias = [], [], []
    for ex in data.examples[:count]:
        _, h, w = ex.x.shape
        x = torch.from_numpy(net.pad_to_multiple(ex.x))[None]
        c = torch.from_numpy(net.pad_to_multiple(ex.color))[None]
        k = torch.from_numpy(net.pad_to_multiple(ex.classic))[None]
        out = model(x, c, k)[:, :, :h, :w]
        t = torch.from_numpy(ex.target)[None]
        s = torch.tensor(ex.scale).view(1, 1, 1, 1)
        den.append(float(relative_loss(out, t, s)))
        raw.append(float(relative_loss(torch.from_numpy(ex.color)[None], t, s)))
        bias.append(float(out.sum() / t.sum().clamp(min=1e-12) - 1))
    return float(np.mean(den)), float(np.mean(raw)), float(np.mean(bias))


def learning_rate(step: int, steps: int, peak: float) -> float:
    warm = min(500, steps // 10 + 1)
    if step < warm:
        return peak * (step + 1) / warm
    return 1e-5 + 0.5 * (peak - 1e-5) * (1 + math.cos(math.pi * (step - warm) / max(1, steps - warm)))


def save_checkpoint(path: Path, state: dict) -> None:
    tmp = path.with_name(path.name + ".tmp")
    torch.save(state, tmp)
    os.replace(tmp, path)


def plot(log_path: Path, png: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = [json.loads(line) for line in log_path.read_text().splitlines() if line.strip()]
    if not rows:
        return
    fig, ax = plt.subplots(figsize=(7, 4))
    train = [(r["step"], r["loss"]) for r in rows if "loss" in r]
    if train:
        ax.plot(*zip(*train), label="training loss (running mean)", lw=1)
    for key, label in (("val", "validation (training scenes)"), ("heldout", "held-out scenes")):
        pts = [(r["step"], r[key]) for r in rows if key in r and math.isfinite(r[key])]
        if pts:
            ax.plot(*zip(*pts), "o-", label=label, ms=3)
    raw = [r["heldout_raw"] for r in rows if "heldout_raw" in r and math.isfinite(r["heldout_raw"])]
    if raw:
        ax.axhline(raw[-1], color="gray", ls="--", lw=0.8, label="held-out raw input")
    ax.set_yscale("log")
    ax.set_xlabel("step")
    ax.set_ylabel("relative MSE against a noisy target")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    tmp = png.with_name(png.name + ".tmp.png")
    fig.savefig(tmp, dpi=110)
    plt.close(fig)
    os.replace(tmp, png)


def git_commit() -> str:
    try:
        return subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=Path(__file__).parent,
                              capture_output=True, text=True, check=True).stdout.strip()
    except Exception:
        return "unknown"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--data", required=True, type=Path, help="generate.py's folder (train/, heldout/)")
    ap.add_argument("--run", required=True, type=Path, help="checkpoint, log and curves folder")
    ap.add_argument("--steps", type=int, default=20000, help="total steps (the schedule's length)")
    ap.add_argument("--stop-after", type=int, default=0, help="stop at this step (0: --steps)")
    ap.add_argument("--batch", type=int, default=8)
    ap.add_argument("--crop", type=int, default=96, help="crop size, a multiple of 16")
    ap.add_argument("--lr", type=float, default=1e-3)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--network", choices=net.NETWORKS, default=net.NETWORK)
    ap.add_argument("--init-from", type=Path,
                    help="a kpcn-unet-v1 weights file to start from (new runs only; "
                    "model.widened for kpcn-blend-v2)")
    ap.add_argument("--classic-share", type=float, default=0.88,
                    help="with --init-from: the classic output's starting share of the blend")
    ap.add_argument("--min-spp", type=int, default=1,
                    help="train on the examples rendered with at least this many samples")
    ap.add_argument("--denominator", choices=["output", "classic"], default="classic",
                    help="the relative loss's denominator: the classic denoiser's output "
                    "(kpcn-blend-v2 only) or the network's own (relative_loss says why)")
    ap.add_argument("--train", choices=["all", "blend"], default="all",
                    help="blend: only the classic output's blend weight (head0's last "
                    "channel) learns; the rest keeps the weights it starts from")
    ap.add_argument("--loss", choices=["log", "mean"], default="log",
                    help="log: the mean of each example's log loss; mean: the batch's mean "
                    "(how kpcn-unet-v1 was trained); batch_loss says why")
    ap.add_argument("--target", choices=["denoised", "raw"], default="denoised",
                    help="with a set made by generate.py --denoised-targets: train toward the "
                    "classic denoiser's output of the target render (less noise, but its "
                    "filter's bias is shared with the classic input), or the raw render "
                    "(Noise2Noise: unbiased, noisier)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--limit", type=int, default=0, help="use at most this many examples")
    ap.add_argument("--ckpt-every", type=int, default=250)
    ap.add_argument("--eval-every", type=int, default=500)
    ap.add_argument("--rescan", type=int, default=500)
    ap.add_argument("--export", type=Path, help="write the weights file here at the end")
    ap.add_argument("--quiet", action="store_true")
    args = ap.parse_args(argv)
    if args.crop % net.ALIGN:
        ap.error(f"--crop must be a multiple of {net.ALIGN}")
    torch.set_num_threads(args.threads)
    args.run.mkdir(parents=True, exist_ok=True)
    ckpt = args.run / "checkpoint.pt"
    log_path = args.run / "log.jsonl"

    with_classic = net.uses_classic(args.network)
    use_classic_denominator = with_classic and args.denominator == "classic"
    raw_target = args.target == "raw"
    train = DataSet(args.data / "train", args.limit, with_classic, args.min_spp, raw_target)
    heldout = DataSet(args.data / "heldout", 64, with_classic, args.min_spp, raw_target)
    if not train.examples:
        print(f"train.py: no examples in {args.data / 'train'}", file=sys.stderr)
        return 1
    torch.manual_seed(args.seed)  # before the model: its initial weights come from it
    model = net.KpcnUnet(args.network)
    if args.init_from and not ckpt.exists():
        try:
            model, _ = net.widened_from_file(args.init_from, args.network, args.classic_share)
        except ValueError as e:
            ap.error(f"--init-from: {e}")
    if args.train == "blend":
        if not with_classic:
            ap.error("--train blend: only kpcn-blend-v2 has a blend with the classic output")
        for p in model.parameters():
            p.requires_grad_(False)
        # head0's last output channel (its weights and bias) only: a gradient mask.
        mask = torch.zeros_like(model.head0.bias)
        mask[-1] = 1.0
        for p in (model.head0.weight, model.head0.bias):
            p.requires_grad_(True)
            p.register_hook(lambda g, m=mask: g * m.view(-1, *([1] * (g.dim() - 1))))
    opt = torch.optim.Adam([p for p in model.parameters() if p.requires_grad], lr=args.lr)
    step = 0
    rng = np.random.default_rng(args.seed)
    if ckpt.exists():
        state = torch.load(ckpt)
        if state.get("network", "kpcn-unet-v1") != args.network:
            ap.error(f"{ckpt} holds a {state.get('network', 'kpcn-unet-v1')} run, "
                     f"not {args.network}")
        model.load_state_dict(state["model"])
        opt.load_state_dict(state["optimizer"])
        step = state["step"]
        rng.bit_generator.state = state["numpy_rng"]
        torch.set_rng_state(state["torch_rng"])
        if not args.quiet:
            print(f"resumed {ckpt} at step {step}")
    stop = args.stop_after or args.steps
    running = None
    t0 = time.time()
    first_step = step
    losses = []
    with log_path.open("a") as log:
        while step < stop:
            for g in opt.param_groups:
                g["lr"] = learning_rate(step, args.steps, args.lr)
            x, c, k, t, s = batch(rng, train, args.batch, args.crop)
            loss = batch_loss(model(x, c, k), t, s, args.loss == "log",
                              k if use_classic_denominator else None)
            opt.zero_grad()
            loss.backward()
            torch.nn.utils.clip_grad_norm_(model.parameters(), 1.0)
            opt.step()
            step += 1
            # Logged as a loss, not its log: the geometric mean of the examples' losses.
            value = math.exp(float(loss)) if args.loss == "log" else float(loss)
            losses.append(value)
            running = value if running is None else 0.98 * running + 0.02 * value
            record = {"step": step, "loss": running}
            if step % args.eval_every == 0 or step == stop:
                record["val"], record["val_raw"], record["val_bias"] = evaluate(model, train)
                record["heldout"], record["heldout_raw"], record["heldout_bias"] = evaluate(
                    model, heldout)
            log.write(json.dumps(record) + "\n")
            if step % args.ckpt_every == 0 or step == stop:
                log.flush()
                save_checkpoint(ckpt, {"model": model.state_dict(), "optimizer": opt.state_dict(),
                                       "step": step, "numpy_rng": rng.bit_generator.state,
                                       "torch_rng": torch.get_rng_state(),
                                       "network": args.network,
                                       "examples": len(train.examples)})
                plot(log_path, args.run / "loss.png")
            if step % args.rescan == 0:
                added = train.rescan() + heldout.rescan()
                if added and not args.quiet:
                    print(f"  {added} new examples ({len(train.examples)} for training)")
            if not args.quiet and (step % 50 == 0 or "val" in record):
                rate = (step - first_step) / (time.time() - t0)
                extra = ""
                if "val" in record:
                    extra = (f" val {record['val']:.4f} (raw {record['val_raw']:.4f}) held-out "
                             f"{record['heldout']:.4f} (raw {record['heldout_raw']:.4f})")
                print(f"step {step}/{args.steps} loss {running:.4f} lr "
                      f"{opt.param_groups[0]['lr']:.2e} {rate:.2f} steps/s{extra}", flush=True)
    if args.export:
        meta = net.WeightsMeta(commit=git_commit(),
                               dataset=f"{args.data.name} ({len(train.examples)} examples)",
                               steps=step,
                               created=datetime.datetime.now(datetime.timezone.utc).isoformat())
        net.write_weights(args.export, model, meta)
        if not args.quiet:
            print(f"wrote {args.export}")
    main.losses = losses  # for the tests
    return 0


if __name__ == "__main__":
    sys.exit(main())
