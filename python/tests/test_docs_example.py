"""Runs the Python example of docs/python.md (every ```python block, in order, in one
namespace) in a temporary directory, with the paths it names made to exist there."""
import os
import re
import shutil

from conftest import SOURCE_DIR


def test_docs_python_md_example_runs(imunoise_cli, tmp_path):
    text = (SOURCE_DIR / "docs" / "python.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    assert blocks, "docs/python.md has no python block"
    # The recording the example reads: 30 min of the reference IMU at 100 Hz.
    imunoise_cli("simulate", SOURCE_DIR / "configs" / "reference-imu.yaml", "--duration",
                 "30min", "--rate", 100, "--seed", 1, "-o", tmp_path / "imu.csv", "--quiet")
    shutil.copy(SOURCE_DIR / "configs" / "reference-imu.yaml", tmp_path / "reference-imu.yaml")
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        namespace = {}
        for block in blocks:
            exec(compile(block, "docs/python.md", "exec"), namespace)
    finally:
        os.chdir(cwd)
    assert (tmp_path / "model.yaml").exists()
    assert (tmp_path / "kalibr_imu.yaml").exists()
