"""Builds the extension module hgridlab with the project's CMake build
(target hgridlab_python: the library and the pybind11 module, nothing else)
and puts it where setuptools packs it. See pyproject.toml."""
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


def version():
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(hgridlab VERSION ([0-9.]+)", text).group(1)


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        out = Path(self.get_ext_fullpath(ext.name)).resolve()
        build = Path(self.build_temp).resolve() / "cmake"
        config = [
            "cmake", "-S", str(ROOT), "-B", str(build),
            "-DCMAKE_BUILD_TYPE=Release",
            f"-DPython3_EXECUTABLE={sys.executable}",
            "-DHGRID_BUILD_PYTHON=ON", "-DHGRID_BUILD_TESTS=OFF", "-DHGRID_BUILD_BENCH=OFF",
            "-DHGRID_BUILD_CLI=OFF", "-DHGRID_INSTALL=OFF", "-DHGRID_MPI=OFF",
            # A one-shot build: sources compiled in batches (the same code and
            # flags, so the same module; 113 s against 156 s on 2 cores,
            # docs/record/PERFORMANCE.md). `make` keeps the library one file per
            # unit, which catches a source that leans on another's includes.
            "-DCMAKE_UNITY_BUILD=ON",
        ]
        subprocess.run(config, check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 2))
        subprocess.run(["cmake", "--build", str(build), "--target", "hgridlab_python", "-j", jobs], check=True)
        built = sorted((build / "python").glob("hgridlab*.so"))
        if len(built) != 1:
            raise RuntimeError(f"expected one hgridlab module in {build / 'python'}, found {built}")
        out.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], out)


setup(version=version(), ext_modules=[CMakeExtension("hgridlab")], cmdclass={"build_ext": CMakeBuild},
      zip_safe=False)
