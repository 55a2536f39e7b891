"""Builds the extension igm._igm with CMake (python/CMakeLists.txt) for pip install.

IGM_CMAKE_BUILD_DIR=DIR: use the CMake build in DIR (configured with IGM_BUILD_PYTHON for this
interpreter), only building its target igm_python; otherwise a Release build of the target in
a folder of setuptools' build tree, configured for the interpreter running this script.
"""
import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build_dir = os.environ.get("IGM_CMAKE_BUILD_DIR")
        if build_dir:
            build_dir = Path(build_dir).resolve()
        else:
            build_dir = Path(self.build_temp).resolve() / "cmake"
            subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                            "-DIGM_BUILD_PYTHON=ON", "-DIGM_BUILD_TESTS=OFF", "-DIGM_BUILD_BENCH=OFF",
                            "-DIGM_INSTALL=OFF", f"-DPython_EXECUTABLE={sys.executable}"], check=True)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "igm_python", "-j",
                        str(os.cpu_count() or 1)], check=True)
        built = sorted((build_dir / "python" / "igm").glob("_igm*" + (".so" if os.name != "nt" else ".pyd")))
        if not built:
            raise RuntimeError(f"no igm/_igm module in {build_dir}/python")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[-1], target)


setup(
    packages=["igm"],
    package_dir={"igm": "python/igm"},
    ext_modules=[Extension("igm._igm", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": "build-pip"}},  # not build/, the CMake build's usual folder
)
