"""The training code on a tiny set: a few steps must lower the loss, the weights file must
round-trip, and a data set must be reproducible from its seed. Run by ctest
(denoiser_training_tests) with the build tree's pbrkit package on PYTHONPATH."""
from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

torch = pytest.importorskip("torch")

HERE = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(HERE))

import model as net  # noqa: E402
import train  # noqa: E402


def generate(out: Path, count: int, split: str = "train", seed: int = 7,
             extra: tuple[str, ...] = ()) -> None:
    subprocess.run([sys.executable, str(HERE / "generate.py"), "--out", str(out), "--split", split,
                    "--count", str(count), "--seed", str(seed), "--size", "48",
                    "--target-spp", "16", *extra], check=True, capture_output=True)


@pytest.fixture(scope="module")
def tiny_set(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("data")
    generate(out, 3)
    generate(out, 1, split="heldout")
    return out


def test_data_set_is_reproducible_from_its_seed(tiny_set: Path, tmp_path: Path) -> None:
    generate(tmp_path, 1)
    a = np.load(tiny_set / "train" / "000000.npz")
    b = np.load(tmp_path / "train" / "000000.npz")
    for key in ("color", "albedo", "normal", "target", "classic", "depth", "noise"):
        assert np.array_equal(a[key], b[key]), key
    assert a["color"].shape == (48, 48, 3)


def test_a_few_steps_lower_the_loss(tiny_set: Path, tmp_path: Path) -> None:
    # Fitting three 48x48 examples: after 60 steps the mean of the last ten losses must be
    # below the first ten's (an untrained network's kernels are near uniform 5x5 boxes;
    # learning anything about the features makes the error fall).
    rc = train.main(["--data", str(tiny_set), "--run", str(tmp_path / "run"), "--steps", "60",
                     "--batch", "4", "--crop", "32", "--lr", "3e-3", "--threads", "2",
                     "--eval-every", "60", "--ckpt-every", "30", "--quiet",
                     "--export", str(tmp_path / "w.pbnn")])
    assert rc == 0
    losses = train.main.losses
    assert len(losses) == 60
    assert np.mean(losses[-10:]) < 0.9 * np.mean(losses[:10])
    assert (tmp_path / "run" / "loss.png").stat().st_size > 1000
    # The exported file reads back into the same network.
    model, header = net.read_weights(tmp_path / "w.pbnn")
    assert header["network"] == net.NETWORK and header["steps"] == 60


def test_training_resumes_from_its_checkpoint(tiny_set: Path, tmp_path: Path) -> None:
    # 20 steps in one go equal 10 steps, a stop, and 10 more (same seed, same batches).
    common = ["--data", str(tiny_set), "--steps", "20", "--batch", "2", "--crop", "32",
              "--threads", "1", "--quiet", "--ckpt-every", "10", "--eval-every", "100",
              "--rescan", "1000"]
    train.main(common + ["--run", str(tmp_path / "a"), "--export", str(tmp_path / "a.pbnn")])
    train.main(common + ["--run", str(tmp_path / "b"), "--stop-after", "10"])
    train.main(common + ["--run", str(tmp_path / "b"), "--export", str(tmp_path / "b.pbnn")])
    a, _ = net.read_weights(tmp_path / "a.pbnn")
    b, _ = net.read_weights(tmp_path / "b.pbnn")
    for (name, pa), (_, pb) in zip(a.state_dict().items(), b.state_dict().items()):
        assert torch.equal(pa, pb), name


def test_output_is_a_normalised_average() -> None:
    # The kernels are softmax weights: a constant colour comes out unchanged whatever the
    # weights, and exposure scales the output exactly (the input transform divides it out).
    torch.manual_seed(3)
    m = net.KpcnUnet()
    for p in m.parameters():
        p.data.mul_(4)
    rng = np.random.default_rng(1)
    albedo = rng.random((40, 37, 3)).astype(np.float32)
    normal = rng.uniform(-1, 1, (40, 37, 3)).astype(np.float32)
    flat = np.full((40, 37, 3), 0.7, np.float32)
    assert np.allclose(net.denoise(m, flat, albedo, normal), 0.7, rtol=1e-5)
    color = rng.exponential(1.0, (40, 37, 3)).astype(np.float32)
    out = net.denoise(m, color, albedo, normal)
    out100 = net.denoise(m, color * 100, albedo, normal)
    # float32 rounding of color * 100 and of the log moves the kernels a little; pixels near
    # the clamp at 0 get an absolute tolerance on the image's scale
    assert np.allclose(out100, out * 100, rtol=1e-3, atol=1e-3 * 100 * color.mean())


def test_widened_network_starts_as_the_blend_of_v1_and_classic() -> None:
    # model.widened: the classic channels' weights are 0 and the blend logit's bias is the
    # share's logit, so the blend network's output is share * classic + (1 - share) * the
    # v1 network's output, pixel for pixel (where neither is clamped: both are >= 0).
    torch.manual_seed(5)
    v1 = net.KpcnUnet()
    rng = np.random.default_rng(2)
    color = rng.exponential(1.0, (32, 48, 3)).astype(np.float32)
    albedo = rng.random((32, 48, 3)).astype(np.float32)
    normal = rng.uniform(-1, 1, (32, 48, 3)).astype(np.float32)
    classic = rng.uniform(0.2, 2.0, (32, 48, 3)).astype(np.float32)
    blend = net.widened(v1, "kpcn-blend-v2", 0.8)
    expected = 0.8 * classic + 0.2 * net.denoise(v1, color, albedo, normal)
    assert np.allclose(net.denoise(blend, color, albedo, normal, classic), expected, rtol=1e-5,
                       atol=1e-6)
    with pytest.raises(ValueError, match="classic"):
        net.denoise(blend, color, albedo, normal)


def test_log_loss_weighs_every_example_alike() -> None:
    # batch_loss with per_example_log: scaling one example's error by 100 moves the loss by
    # log(100) / batch, whatever its size; the mean of the batch moves by the error itself.
    rng = np.random.default_rng(4)
    t = torch.from_numpy(rng.uniform(0.5, 1.5, (2, 3, 32, 32)).astype(np.float32))
    noise = torch.from_numpy(rng.normal(0.0, 0.005, (2, 3, 32, 32)).astype(np.float32))
    s = torch.ones(2, 1, 1, 1)
    out = t + noise
    worse = out.clone()
    worse[0] = t[0] + 10.0 * noise[0]  # 100x the squared error (the denominator moves a little)
    a = float(train.batch_loss(out, t, s, True))
    b = float(train.batch_loss(worse, t, s, True))
    assert abs((b - a) - math.log(100.0) / 2) < 0.1


def test_training_only_the_blend_changes_nothing_else(tiny_set: Path, tmp_path: Path) -> None:
    # --train blend from a widened kpcn-unet-v1: after a few steps every weight but head0's
    # last channel (the classic output's blend logit) is what it started as, and that one moved.
    torch.manual_seed(9)
    net.write_weights(tmp_path / "v1.pbnn", net.KpcnUnet(), net.WeightsMeta())
    start = net.widened(net.read_weights(tmp_path / "v1.pbnn")[0], "kpcn-blend-v2", 0.88)
    rc = train.main(["--data", str(tiny_set), "--run", str(tmp_path / "run"), "--steps", "6",
                     "--batch", "2", "--crop", "32", "--threads", "1", "--quiet",
                     "--network", "kpcn-blend-v2", "--init-from", str(tmp_path / "v1.pbnn"),
                     "--classic-share", "0.88", "--train", "blend", "--lr", "1e-2",
                     "--eval-every", "100", "--export", str(tmp_path / "b.pbnn")])
    assert rc == 0
    trained, _ = net.read_weights(tmp_path / "b.pbnn")
    before, after = start.state_dict(), trained.state_dict()
    for name in before:
        if name.startswith("head0."):
            assert torch.equal(before[name][:-1], after[name][:-1]), name
            assert not torch.equal(before[name][-1], after[name][-1]), name
        else:
            assert torch.equal(before[name], after[name]), name


def test_denoised_targets_are_the_same_samples_filtered(tiny_set: Path, tmp_path: Path) -> None:
    # --denoised-targets: the raw target is the plain set's, bit for bit (same seed, same
    # samples), and the target is another image of about the same energy (the classic
    # denoiser keeps a region's mean within its noise).
    generate(tmp_path, 1, extra=("--denoised-targets",))
    plain = np.load(tiny_set / "train" / "000000.npz")
    denoised = np.load(tmp_path / "train" / "000000.npz")
    assert np.array_equal(denoised["target_raw"], plain["target"])
    assert not np.array_equal(denoised["target"], plain["target"])
    assert abs(denoised["target"].mean() / plain["target"].mean() - 1.0) < 0.05
    # train.py --target raw trains toward the raw render of such a set, the default toward
    # the denoised one.
    path = tmp_path / "train" / "000000.npz"
    chw = lambda a: np.ascontiguousarray(a.transpose(2, 0, 1))  # noqa: E731
    assert np.array_equal(train.Example(path, True, raw_target=True).target,
                          chw(denoised["target_raw"]))
    assert np.array_equal(train.Example(path, True).target, chw(denoised["target"]))


def test_spp_choices_set_the_inputs_sample_counts(tmp_path: Path) -> None:
    # --spp 3: every example's input has 3 spp (a count the default distribution never
    # draws), and a bad list is refused before anything renders.
    generate(tmp_path, 2, extra=("--spp", "3"))
    for k in range(2):
        meta = np.load(tmp_path / "train" / f"{k:06d}.npz")["meta"]
        assert '"spp": 3,' in str(meta)
    bad = subprocess.run([sys.executable, str(HERE / "generate.py"), "--out", str(tmp_path),
                          "--spp", "8,0"], capture_output=True, text=True)
    assert bad.returncode == 2 and "at least 1" in bad.stderr
