"""Builds the extension glint._glint with CMake for `pip install --no-build-isolation .`
(pyproject.toml has the package's description). The extension is the build's target
glint_python, made for the interpreter pip runs; only it and the libraries it links are built."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


class CMakeBuild(build_ext):
    def build_extension(self, ext: Extension) -> None:
        build = Path(self.build_temp).resolve() / "cmake"
        # OpenVDB when its package is there, as `make demo` decides (GLINT_CMAKE_ARGS: more).
        vdb = Path("/usr/lib") / f"{os.uname().machine}-linux-gnu" / "cmake/OpenVDB"
        subprocess.check_call([
            "cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
            "-DGLINT_BUILD_TESTS=OFF", "-DGLINT_MPI=OFF",
            f"-DGLINT_OPENVDB={'ON' if vdb.is_dir() else 'OFF'}",
            f"-DPython_EXECUTABLE={sys.executable}",
            *os.environ.get("GLINT_CMAKE_ARGS", "").split(),
        ])
        jobs = str(os.cpu_count() or 2)
        subprocess.check_call(["cmake", "--build", str(build), "--target", "glint_python",
                               "-j", jobs])
        built = next((build / "python" / "glint").glob("_glint*.so"))
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


# setuptools' own build folder beside CMake's build/ rather than in it.
setup(ext_modules=[Extension("glint._glint", sources=[])], cmdclass={"build_ext": CMakeBuild},
      options={"build": {"build_base": "build-pip"}})
