"""The two examples in examples/python run as a user would run them, and write what they
say they write."""

import os
import subprocess
import sys

import pbrkit

EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples",
                        "python")


def run(script, *args):
    r = subprocess.run([sys.executable, os.path.join(EXAMPLES, script), *map(str, args)],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    return r


def test_dataset_writes_each_view_with_its_aovs(tmp_path):
    run("dataset.py", "cornell", "-n", 2, "--size", 24, "--spp", 2, "-o", tmp_path)
    for i in range(2):
        image = pbrkit.read_image(tmp_path / f"view_{i:04d}.exr")
        assert image.shape == (24, 24, 3) and image.mean() > 0
        assert pbrkit.read_image(tmp_path / f"view_{i:04d}_depth.exr").shape == (24, 24)
        for aov in ("albedo", "normal"):
            assert pbrkit.read_image(tmp_path / f"view_{i:04d}_{aov}.exr").shape == (24, 24, 3)
    # Two random views of the same box are different images.
    a, b = (pbrkit.read_image(tmp_path / f"view_{i:04d}.exr") for i in range(2))
    assert not (a == b).all()


def test_brdf_plots_writes_a_png(tmp_path):
    out = tmp_path / "brdf.png"
    run("brdf_plots.py", "-o", out)
    image = pbrkit.read_image(out)
    assert image.shape[0] > 100 and image.shape[1] > 100
