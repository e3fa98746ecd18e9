"""The learned denoiser's network, input transform and weights file, in PyTorch.

docs/LEARNED_DENOISER.md is the contract this file and the C++ inference
(src/pbrkit/denoise/learned/) both follow: a U-Net (Ronneberger et al. 2015) predicting
5x5 kernels at three scales (Bako et al. 2017) blended coarse to fine by the scale
compositor of Vogels et al. 2018 (section 4.2).
"""
from __future__ import annotations

import json
import math
import struct
import zlib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import torch
import torch.nn.functional as F
from torch import nn

NETWORK = "kpcn-blend-v2"  # what train.py trains unless told otherwise
NETWORKS = ("kpcn-unet-v1", "kpcn-blend-v2")
INPUT_TRANSFORM = "log1p-autoexposure-v1"
MAGIC = b"PBRKITNN"
FORMAT_VERSION = 1
KERNEL = 5  # the kernel's width at each scale
ALIGN = 16  # four 2x2 poolings

# (name, in, out) in the order of docs/LEARNED_DENOISER.md's table, for kpcn-unet-v1;
# kpcn-blend-v2 differs in enc0a (12 inputs: the classic denoiser's output too) and head0
# (27 outputs: the blend weight with the classic output too), layers(network).
LAYERS = [
    ("enc0a", 9, 16), ("enc0b", 16, 16), ("enc1", 16, 32), ("enc2", 32, 48),
    ("enc3", 48, 64), ("bot_a", 64, 64), ("bot_b", 64, 64), ("dec3a", 128, 64),
    ("dec3b", 64, 64), ("dec2a", 112, 48), ("dec2b", 48, 48), ("head2", 48, 25),
    ("dec1a", 80, 32), ("dec1b", 32, 32), ("head1", 32, 26), ("dec0a", 48, 16),
    ("dec0b", 16, 16), ("head0", 16, 26),
]


def uses_classic(network: str) -> bool:
    """Whether the network reads (and blends with) the classic denoiser's output."""
    return network == "kpcn-blend-v2"


def layers(network: str) -> list[tuple[str, int, int]]:
    if network not in NETWORKS:
        raise ValueError(f"unknown network {network!r} (known: {', '.join(NETWORKS)})")
    if not uses_classic(network):
        return list(LAYERS)
    widths = {"enc0a": (12, 16), "head0": (16, 27)}
    return [(n, *widths.get(n, (i, o))) for n, i, o in LAYERS]


def autoexposure(color: np.ndarray) -> float:
    """0.18 over the geometric mean of the 16x16 blocks' mean luminance (the contract's
    'Autoexposure'); color is (H, W, 3), linear, already made finite and non-negative."""
    h, w, _ = color.shape
    c = color.astype(np.float64)
    lum = 0.2126 * c[..., 0] + 0.7152 * c[..., 1] + 0.0722 * c[..., 2]
    logs = []
    for y in range(0, h, 16):
        for x in range(0, w, 16):
            m = lum[y:y + 16, x:x + 16].mean()
            if m > 1e-8:
                logs.append(math.log(m))
    return 0.18 / math.exp(sum(logs) / len(logs)) if logs else 1.0


def sanitize(color: np.ndarray) -> np.ndarray:
    c = np.nan_to_num(np.asarray(color, np.float32)[..., :3], nan=0.0, posinf=0.0,
                      neginf=0.0)
    return np.maximum(c, 0.0)


def network_input(color: np.ndarray, albedo: np.ndarray, normal: np.ndarray,
                  exposure: float | None = None,
                  classic: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The input channels (9, or 12 with the classic output, H, W) and the linear colour
    (3, H, W), both float32. The autoexposure is the noisy colour's, for both."""
    c = sanitize(color)
    s = autoexposure(c) if exposure is None else exposure
    parts = [
        np.log1p(c.astype(np.float64) * s).astype(np.float32),
        np.clip(np.nan_to_num(albedo[..., :3]), 0.0, 1.0).astype(np.float32),
        np.clip(np.nan_to_num(normal[..., :3]), -1.0, 1.0).astype(np.float32),
    ]
    if classic is not None:
        parts.append(np.log1p(sanitize(classic).astype(np.float64) * s).astype(np.float32))
    x = np.concatenate(parts, axis=2)
    return np.ascontiguousarray(x.transpose(2, 0, 1)), np.ascontiguousarray(c.transpose(2, 0, 1))


def box_down(c: torch.Tensor) -> torch.Tensor:
    return F.avg_pool2d(c, 2)


def up(c: torch.Tensor) -> torch.Tensor:
    return F.interpolate(c, scale_factor=2, mode="nearest")


def apply_kernel(logits: torch.Tensor, color: torch.Tensor) -> torch.Tensor:
    """d(y, x) = sum of softmax(logits)[(dy+2)*5 + dx+2] * color(clamp(y+dy), clamp(x+dx))."""
    n, _, h, w = color.shape
    r = KERNEL // 2
    weights = torch.softmax(logits[:, :KERNEL * KERNEL], dim=1)
    padded = F.pad(color, (r, r, r, r), mode="replicate")
    patches = F.unfold(padded, KERNEL).view(n, 3, KERNEL * KERNEL, h, w)
    return (patches * weights.unsqueeze(1)).sum(dim=2)


class KpcnUnet(nn.Module):
    def __init__(self, network: str = "kpcn-unet-v1") -> None:
        super().__init__()
        self.network = network
        self.layers = layers(network)
        for name, cin, cout in self.layers:
            setattr(self, name, nn.Conv2d(cin, cout, 3, padding=1))

    def heads(self, x: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        relu = F.relu
        s0 = relu(self.enc0b(relu(self.enc0a(x))))
        s1 = relu(self.enc1(F.max_pool2d(s0, 2)))
        s2 = relu(self.enc2(F.max_pool2d(s1, 2)))
        s3 = relu(self.enc3(F.max_pool2d(s2, 2)))
        b = relu(self.bot_b(relu(self.bot_a(F.max_pool2d(s3, 2)))))
        d3 = relu(self.dec3b(relu(self.dec3a(torch.cat([up(b), s3], 1)))))
        d2 = relu(self.dec2b(relu(self.dec2a(torch.cat([up(d3), s2], 1)))))
        d1 = relu(self.dec1b(relu(self.dec1a(torch.cat([up(d2), s1], 1)))))
        d0 = relu(self.dec0b(relu(self.dec0a(torch.cat([up(d1), s0], 1)))))
        return self.head0(d0), self.head1(d1), self.head2(d2)

    def forward(self, x: torch.Tensor, color: torch.Tensor,
                classic: torch.Tensor | None = None) -> torch.Tensor:
        """x: (N, 9 or 12, H, W), color and classic: (N, 3, H, W) linear, H and W multiples
        of 16; classic only for kpcn-blend-v2."""
        h0, h1, h2 = self.heads(x)
        c0 = color
        c1 = box_down(c0)
        c2 = box_down(c1)
        d0, d1, d2 = apply_kernel(h0, c0), apply_kernel(h1, c1), apply_kernel(h2, c2)
        a0 = torch.sigmoid(h0[:, 25:26])
        a1 = torch.sigmoid(h1[:, 25:26])
        r1 = d1 - a1 * up(box_down(d1)) + a1 * up(d2)
        r0 = d0 - a0 * up(box_down(d0)) + a0 * up(r1)
        if uses_classic(self.network):
            b = torch.sigmoid(h0[:, 26:27])
            r0 = b * classic + (1 - b) * r0
        return torch.clamp(r0, min=0.0)


def pad_to_multiple(a: np.ndarray, multiple: int = ALIGN) -> np.ndarray:
    """(C, H, W) padded on the right and bottom by repeating the last column and row."""
    _, h, w = a.shape
    ph, pw = (-h) % multiple, (-w) % multiple
    return np.pad(a, ((0, 0), (0, ph), (0, pw)), mode="edge")


@torch.no_grad()
def denoise(model: KpcnUnet, color: np.ndarray, albedo: np.ndarray,
            normal: np.ndarray, classic: np.ndarray | None = None) -> np.ndarray:
    """The whole image at once (no tiles): (H, W, 3) float32 in, (H, W, 3) out; `classic`
    (the classic denoiser's output of the same colour) for kpcn-blend-v2."""
    h, w = color.shape[:2]
    blend = uses_classic(model.network)
    if blend and classic is None:
        raise ValueError(f"{model.network} needs the classic denoiser's output")
    x, c = network_input(color, albedo, normal, classic=classic if blend else None)
    xt = torch.from_numpy(pad_to_multiple(x))[None]
    ct = torch.from_numpy(pad_to_multiple(c))[None]
    kt = None
    if blend:
        k = np.ascontiguousarray(sanitize(classic).transpose(2, 0, 1))
        kt = torch.from_numpy(pad_to_multiple(k))[None]
    out = model(xt, ct, kt)[0, :, :h, :w]
    return np.ascontiguousarray(out.numpy().transpose(1, 2, 0))


@dataclass
class WeightsMeta:
    commit: str = "unknown"
    dataset: str = "unknown"
    steps: int = 0
    created: str = ""


def write_weights(path: str | Path, model: KpcnUnet, meta: WeightsMeta) -> None:
    """The weights file of docs/LEARNED_DENOISER.md, written atomically."""
    tensors = []
    blobs = []
    offset = 0
    state = model.state_dict()
    for name, _, _ in model.layers:
        for part in ("weight", "bias"):
            t = state[f"{name}.{part}"].detach().cpu().float().contiguous().numpy()
            blob = t.astype("<f4").tobytes()
            tensors.append({"name": f"{name}.{part}", "shape": list(t.shape), "offset": offset})
            blobs.append(blob)
            offset += len(blob)
    data = b"".join(blobs)
    header: dict[str, Any] = {
        "network": model.network, "input_transform": INPUT_TRANSFORM, "tensors": tensors,
        "data_bytes": len(data), "crc32": zlib.crc32(data) & 0xFFFFFFFF,
        "commit": meta.commit, "dataset": meta.dataset, "steps": meta.steps,
        "created": meta.created,
    }
    hb = json.dumps(header, separators=(",", ":")).encode()
    head = MAGIC + struct.pack("<II", FORMAT_VERSION, len(hb)) + hb
    head += b"\0" * ((-len(head)) % 64)
    path = Path(path)
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_bytes(head + data)
    tmp.replace(path)


def read_weights(path: str | Path) -> tuple[KpcnUnet, dict[str, Any]]:
    raw = Path(path).read_bytes()
    if raw[:8] != MAGIC:
        raise ValueError(f"{path}: not a pbrkit network (magic)")
    version, n = struct.unpack("<II", raw[8:16])
    if version != FORMAT_VERSION:
        raise ValueError(f"{path}: format version {version}, expected {FORMAT_VERSION}")
    header = json.loads(raw[16:16 + n])
    start = 16 + n + ((-(16 + n)) % 64)
    data = raw[start:start + header["data_bytes"]]
    if len(data) != header["data_bytes"] or zlib.crc32(data) & 0xFFFFFFFF != header["crc32"]:
        raise ValueError(f"{path}: truncated or corrupt data")
    model = KpcnUnet(header["network"])
    state = {}
    for t in header["tensors"]:
        count = int(np.prod(t["shape"]))
        a = np.frombuffer(data, "<f4", count, t["offset"]).reshape(t["shape"])
        state[t["name"]] = torch.from_numpy(a.copy())
    model.load_state_dict(state)
    return model, header


def widened_from_file(path: str | Path, network: str,
                      classic_share: float) -> tuple[KpcnUnet, dict[str, Any]]:
    """widened() of the kpcn-unet-v1 weights file `path`, and that file's header. ValueError
    when the file holds another network or the share is not in (0, 1)."""
    if not 0.0 < classic_share < 1.0:
        raise ValueError(f"the classic share must be in (0, 1), not {classic_share}")
    source, header = read_weights(path)
    if header["network"] != "kpcn-unet-v1":
        raise ValueError(f"{path} is {header['network']}, not kpcn-unet-v1")
    return widened(source, network, classic_share), header


def widened(source: KpcnUnet, network: str, classic_share: float = 0.5) -> KpcnUnet:
    """`network` initialised from a trained kpcn-unet-v1: its weights where the layers
    agree, 0 for what the wider layers add (the classic output's input weights, the blend
    weight's logit) but the blend logit's bias, so that it starts as the v1 network's
    output blended with the classic denoiser's, `classic_share` of the latter."""
    model = KpcnUnet(network)
    state = model.state_dict()
    with torch.no_grad():
        for key, value in source.state_dict().items():
            target = state[key]
            target.zero_()
            target[tuple(slice(0, n) for n in value.shape)] = value
        if uses_classic(network):
            state["head0.bias"][26] = math.log(classic_share / (1.0 - classic_share))
    model.load_state_dict(state)
    return model
