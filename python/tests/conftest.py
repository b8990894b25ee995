"""Shared set-up of the Python tests: the imunoise binary (IMUNOISE_BINARY, set by ctest), the
reference data (IMUNOISE_REFERENCE_DATA, default ../shared/data beside the source tree; tests
that need it skip with a message when it is absent) and the robotics-log fixtures."""
import os
import pathlib
import subprocess

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("IMUNOISE_SOURCE_DIR",
                                         pathlib.Path(__file__).resolve().parents[2]))


def reference_data_dir():
    d = pathlib.Path(os.environ.get("IMUNOISE_REFERENCE_DATA", SOURCE_DIR / ".." / "shared" / "data"))
    return d if d.is_dir() else None


@pytest.fixture
def reference_data():
    d = reference_data_dir()
    if d is None:
        pytest.skip("reference data not found: set IMUNOISE_REFERENCE_DATA (default ../shared/data)")
    return d


@pytest.fixture
def imunoise_cli():
    binary = os.environ.get("IMUNOISE_BINARY")
    if not binary or not os.path.exists(binary):
        pytest.skip("IMUNOISE_BINARY is not set (ctest sets it)")

    def run(*args, check=True):
        env = dict(os.environ)
        env.pop("IMUNOISE_FFTW_WISDOM", None)  # both sides plan their FFTs alike
        r = subprocess.run([binary, *map(str, args)], capture_output=True, text=True, env=env)
        if check and r.returncode != 0:
            raise AssertionError(f"imunoise {' '.join(map(str, args))}: exit {r.returncode}: {r.stderr}")
        return r

    return run
