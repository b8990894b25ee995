"""`pip install --no-build-isolation .` builds and installs the package offline (setup.py with
Debian's setuptools), here into a temporary target folder and re-using the test build tree."""
import os
import pathlib
import subprocess
import sys

import pytest

from conftest import SOURCE_DIR


def test_pip_install_from_the_checkout_works_offline(tmp_path):
    binary = os.environ.get("IMUNOISE_BINARY")
    if not binary:
        pytest.skip("IMUNOISE_BINARY is not set (ctest sets it)")
    build_dir = pathlib.Path(binary).resolve().parents[1]  # build/release/tools/imunoise
    env = dict(os.environ, IMUNOISE_CMAKE_BUILD_DIR=str(build_dir), PIP_NO_INDEX="1",
               PIP_DISABLE_PIP_VERSION_CHECK="1")
    env.pop("PYTHONPATH", None)
    r = subprocess.run([sys.executable, "-m", "pip", "install", "--no-build-isolation",
                        "--no-deps", "--target", str(tmp_path / "site"), str(SOURCE_DIR)],
                       capture_output=True, text=True, env=env, cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    check = subprocess.run(
        [sys.executable, "-c",
         "import imunoise, numpy as np; "
         "print(imunoise.__file__); "
         "print(imunoise.deviation(np.ones(64), 'oadev', taus=[1]).value[0])"],
        capture_output=True, text=True, env=dict(env, PYTHONPATH=str(tmp_path / "site")),
        cwd=tmp_path)
    assert check.returncode == 0, check.stderr
    assert str(tmp_path / "site") in check.stdout
    assert check.stdout.splitlines()[1] == "0.0"
