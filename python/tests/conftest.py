"""Shared fixtures of the pbrkit Python tests: the CLI binary (for outputs to compare with)
and a scratch directory. ctest sets PYTHONPATH to the build tree's package and PBRKIT_CLI
to the pbrkit binary (python/CMakeLists.txt)."""

import os
import subprocess

import pytest


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("PBRKIT_CLI")
    if not path or not os.path.exists(path):
        pytest.fail("PBRKIT_CLI must name the pbrkit binary (ctest sets it)")

    def run(*args):
        r = subprocess.run([path, *map(str, args)], capture_output=True, text=True)
        assert r.returncode == 0, f"pbrkit {' '.join(map(str, args))} failed:\n{r.stderr}"
        return r

    return run


@pytest.fixture(scope="session")
def assets_dir():
    return os.environ.get("PBRKIT_ASSETS_DIR", "")
