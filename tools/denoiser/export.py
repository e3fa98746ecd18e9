#!/usr/bin/env python3
"""Writes a training run's checkpoint as the weights file the product reads
(docs/LEARNED_DENOISER.md, "The weights file"), without training further.

  python3 tools/denoiser/export.py --run $HOME/denoiser-run \
      --dataset "denoiser-data seed 1" -o data/denoiser/kpcn-blend-v2.pbnn

Or a kpcn-blend-v2 made from a kpcn-unet-v1 file with no training (model.widened): the v1
network's output blended with the classic denoiser's at a fixed share, as shipped:

  python3 tools/denoiser/export.py --widen data/denoiser/kpcn-unet-v1.pbnn \
      --classic-share 0.88 -o data/denoiser/kpcn-blend-v2.pbnn
"""
from __future__ import annotations

import argparse
import datetime
import sys
from pathlib import Path

import torch

import model as net
from train import git_commit


def now() -> str:
    return datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--run", type=Path, help="train.py's --run folder")
    ap.add_argument("--widen", type=Path, help="a kpcn-unet-v1 weights file (instead of --run)")
    ap.add_argument("--classic-share", type=float, default=0.88,
                    help="with --widen: the classic output's share of the blend")
    ap.add_argument("--dataset", default="", help="the data set's name and seed, for the header")
    ap.add_argument("-o", "--output", required=True, type=Path)
    args = ap.parse_args()
    if bool(args.run) == bool(args.widen):
        ap.error("give --run or --widen")
    if args.widen:
        try:
            model, header = net.widened_from_file(args.widen, "kpcn-blend-v2", args.classic_share)
        except ValueError as e:
            ap.error(f"--widen: {e}")
        net.write_weights(args.output, model, net.WeightsMeta(
            commit=git_commit(),
            dataset=(f"none: kpcn-unet-v1 ({args.widen.name}, {header['dataset']}, "
                     f"{header['steps']} steps) widened, classic share {args.classic_share}"),
            steps=0,
            created=now()))
        print(f"wrote {args.output} (kpcn-unet-v1 widened, classic share {args.classic_share})")
        return 0
    ckpt = args.run / "checkpoint.pt"
    if not ckpt.exists():
        print(f"export.py: {ckpt}: no checkpoint", file=sys.stderr)
        return 1
    state = torch.load(ckpt)
    model = net.KpcnUnet(state.get("network", "kpcn-unet-v1"))
    model.load_state_dict(state["model"])
    dataset = args.dataset or f"{state.get('examples', '?')} examples"
    net.write_weights(args.output, model, net.WeightsMeta(
        commit=git_commit(), dataset=dataset, steps=int(state["step"]),
        created=now()))
    print(f"wrote {args.output} (step {state['step']})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
