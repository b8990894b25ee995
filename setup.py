"""Builds the compiled part of the imunoise Python package (imunoise._core) with CMake, the
same target the default build makes (python/CMakeLists.txt), and packages python/imunoise with
it. Used by `python3 -m pip install --no-build-isolation .` (docs/python.md)."""
import os
import pathlib
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        # IMUNOISE_CMAKE_BUILD_DIR: an existing build tree to (re)build the target in, e.g.
        # build/release of tools/test; by default a fresh tree under build_temp.
        given = os.environ.get("IMUNOISE_CMAKE_BUILD_DIR")
        build = pathlib.Path(given) if given else pathlib.Path(self.build_temp).resolve() / "cmake"
        if not given:
            build.mkdir(parents=True, exist_ok=True)
            subprocess.check_call([
                "cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                f"-DPython_EXECUTABLE={sys.executable}", "-DIMUNOISE_BUILD_TESTS=OFF",
                "-DIMUNOISE_BUILD_BENCH=OFF"])
        jobs = str(os.cpu_count() or 1)
        subprocess.check_call(["cmake", "--build", str(build), "--target", "imunoise_python",
                               "-j", jobs])
        built = next((build / "python" / "imunoise").glob("_core*.so"))
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


setup(
    packages=["imunoise"],
    package_dir={"": "python"},
    ext_modules=[CMakeExtension("imunoise._core")],
    cmdclass={"build_ext": CMakeBuild},
)
