#!/usr/bin/env python3
"""Writes a training run's checkpoint as the weights file the product reads
(docs/LEARNED_DENOISER.md, "The weights file"), without training further.

  python3 tools/denoiser/export.py --run $HOME/denoiser-run \
      --dataset "denoiser-data seed 1" -o data/denoiser/kpcn-blend-v2.pbnn
"""
from __future__ import annotations

import argparse
import datetime
import sys
from pathlib import Path

import torch

import model as net
from train import git_commit


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--run", required=True, type=Path, help="train.py's --run folder")
    ap.add_argument("--dataset", default="", help="the data set's name and seed, for the header")
    ap.add_argument("-o", "--output", required=True, type=Path)
    args = ap.parse_args()
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
        created=datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")))
    print(f"wrote {args.output} (step {state['step']})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
