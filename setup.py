"""Builds the _pathlab extension with CMake for `pip install .` (the package's
metadata is in pyproject.toml). The extension is the `pathlab_python` target
of this repository's CMake build, configured in build/pip (or in
$PATHLAB_CMAKE_BUILD_DIR, e.g. an existing build to reuse) for the Python
that runs pip."""

import glob
import os
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = os.environ.get("PATHLAB_CMAKE_BUILD_DIR", os.path.join(ROOT, "build", "pip"))
        jobs = os.environ.get("PATHLAB_BUILD_JOBS", str(os.cpu_count() or 1))
        subprocess.check_call([
            "cmake", "-S", ROOT, "-B", build, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
            "-DPATHLAB_PYTHON=ON", "-DPython_EXECUTABLE=" + sys.executable])
        subprocess.check_call(["cmake", "--build", build, "-j", jobs, "--target",
                               "pathlab_python"])
        built = glob.glob(os.path.join(build, "python", "pathlab", "_pathlab*.so"))
        if len(built) != 1:
            raise RuntimeError("expected one _pathlab module in %s, found %r" % (build, built))
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copy2(built[0], target)


setup(ext_modules=[CMakeExtension("pathlab._pathlab")], cmdclass={"build_ext": CMakeBuild})
