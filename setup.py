"""Builds the extension deltamesh._deltamesh with the project's CMake build
(python/CMakeLists.txt) and puts it in the package; pyproject.toml holds
the metadata. DELTAMESH_BUILD_DIR=<a configured build tree> reuses that
tree (nothing is recompiled when it is up to date: how the wheel test in
`make test` stays quick); otherwise a fresh Release tree is configured
under setuptools' build_temp. DELTAMESH_JOBS sets the parallel jobs.
"""
import glob
import os
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


def project_version():
    with open(os.path.join(ROOT, "CMakeLists.txt")) as f:
        return re.search(r"project\(deltamesh VERSION ([0-9.]+)", f.read()).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build_dir = os.environ.get("DELTAMESH_BUILD_DIR")
        if build_dir:
            build_dir = os.path.abspath(build_dir)
        else:
            build_dir = os.path.abspath(os.path.join(self.build_temp, "cmake"))
            if not os.path.exists(os.path.join(build_dir, "CMakeCache.txt")):
                subprocess.check_call(["cmake", "-S", ROOT, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release",
                                       "-DDELTAMESH_TESTS=OFF", "-DDELTAMESH_PYTHON=ON",
                                       f"-DPython_EXECUTABLE={sys.executable}"])
        jobs = os.environ.get("DELTAMESH_JOBS", str(os.cpu_count() or 1))
        subprocess.check_call(["cmake", "--build", build_dir, "--target", "deltamesh_python", "-j", jobs])
        built = glob.glob(os.path.join(build_dir, "python", "deltamesh", "_deltamesh*.so"))
        if len(built) != 1:
            raise RuntimeError(f"expected one extension in {build_dir}/python/deltamesh, found {built} "
                               "(were the bindings skipped? see CMake's messages)")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copy2(built[0], target)


setup(version=project_version(), ext_modules=[Extension("deltamesh._deltamesh", sources=[])],
      cmdclass={"build_ext": CMakeBuild})
