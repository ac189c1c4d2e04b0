"""Builds the `oscilab` wheel with the project's CMake (pyproject.toml names this the backend's
script: setuptools.build_meta runs it for `pip install .`).

The extension is not compiled by setuptools: build_ext configures the project with CMake (a
Release build without the GUI and the tests, for the interpreter that runs pip), builds the one
target oscilab_python (the extension and Oscilab's modules it loads, laid out as a package in
<build>/python/oscilab) and copies its binaries into the wheel beside the pure-Python files.

OSCILAB_CMAKE_BUILD_DIR names a build directory to use instead of a fresh one under
build-python-wheel/: one already configured is only built (its cache is left as it is, so a
developer's or CI's build directory serves as well), one without a CMakeCache.txt is configured
first. CMAKE_BUILD_PARALLEL_LEVEL limits the build's jobs.

The version is the project's one number, CMakeLists.txt's project(Oscilab VERSION ...), which the
extension also reports as oscilab.__version__.
"""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


def project_version():
    text = (ROOT / "CMakeLists.txt").read_text(encoding="utf-8")
    match = re.search(r"^project\(\s*Oscilab\s+VERSION\s+([0-9]+(?:\.[0-9]+)*)", text, re.M)
    if not match:
        raise RuntimeError("CMakeLists.txt: no project(Oscilab VERSION ...)")
    return match.group(1)


def cmake_cache_value(build_dir, name):
    for line in (build_dir / "CMakeCache.txt").read_text(encoding="utf-8").splitlines():
        if line.startswith(name + ":"):
            return line.split("=", 1)[1]
    return None


class CMakeBuild(build_ext):
    """build_ext for the one CMake-built extension (and the modules the package carries)."""

    def build_extension(self, ext):
        build_dir = os.environ.get("OSCILAB_CMAKE_BUILD_DIR")
        if build_dir:
            build_dir = Path(build_dir).resolve()
        else:
            build_dir = Path(self.build_temp).resolve() / "cmake"
        if not (build_dir / "CMakeCache.txt").exists():
            self.configure(build_dir)
        python = cmake_cache_value(build_dir, "Python3_EXECUTABLE")
        if not (build_dir / "python").is_dir():
            raise RuntimeError(f"{build_dir}: the Python module is not configured there (it needs "
                               "python3-dev, pybind11-dev and NumPy; see the CMake output)")
        self.check_same_python(build_dir, python)
        command = ["cmake", "--build", str(build_dir), "--target", "oscilab_python"]
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL")
        if jobs:
            command += ["-j", jobs]
        self.announce("running " + " ".join(command), level=2)
        subprocess.run(command, check=True)

        # <build>/python/oscilab is the package as CMake lays it out: the extension in _native/,
        # Oscilab's modules beside it. The .py, .pyi and py.typed files come from the source tree
        # (build_py), and bytecode an import there left is not the wheel's.
        built = build_dir / "python" / "oscilab"
        package = Path(self.get_ext_fullpath(ext.name)).resolve().parent.parent
        for source in built.rglob("*"):
            relative = source.relative_to(built)
            if (source.is_file() and source.suffix not in (".py", ".pyc", ".pyi")
                    and source.name != "py.typed" and "__pycache__" not in relative.parts):
                target = package / relative
                target.parent.mkdir(parents=True, exist_ok=True)
                shutil.copy2(source, target)
        if not Path(self.get_ext_fullpath(ext.name)).exists():
            raise RuntimeError(f"{built}: no {Path(self.get_ext_fullpath(ext.name)).name}: was "
                               f"{build_dir} configured for another Python than {sys.executable}?")

    def configure(self, build_dir):
        build_dir.mkdir(parents=True, exist_ok=True)
        command = ["cmake", "-S", str(ROOT), "-B", str(build_dir),
                   "-DCMAKE_BUILD_TYPE=Release",
                   "-DOSCILAB_BUILD_GUI=OFF",
                   "-DOSCILAB_BUILD_TESTS=OFF",
                   "-DOSCILAB_BUILD_PYTHON=ON",
                   "-DOSCILAB_UNITY_BUILD=ON",  # a one-off build: batches, about half the CPU
                   f"-DPython3_EXECUTABLE={sys.executable}"]
        if shutil.which("ninja"):
            command += ["-G", "Ninja"]
        self.announce("running " + " ".join(command), level=2)
        subprocess.run(command, check=True)

    @staticmethod
    def check_same_python(build_dir, python):
        """The extension of a reused build directory must be for this interpreter's version."""
        if not python:
            return
        probe = "import sys; print('%d.%d' % sys.version_info[:2])"
        theirs = subprocess.run([python, "-c", probe], capture_output=True,
                                text=True).stdout.strip()
        ours = "%d.%d" % sys.version_info[:2]
        if theirs and theirs != ours:
            raise RuntimeError(f"{build_dir}: configured for Python {theirs} ({python}), "
                               f"not {ours} ({sys.executable})")


# Not build/: that is the project's CMake build directory (egg_info wants its directory to exist).
(ROOT / "build-python-wheel").mkdir(exist_ok=True)

setup(
    version=project_version(),
    package_dir={"": "python"},
    packages=["oscilab", "oscilab._native"],
    package_data={"oscilab": ["py.typed", "*.pyi"]},
    include_package_data=False,
    ext_modules=[Extension("oscilab._native._oscilab", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": "build-python-wheel"},
             "egg_info": {"egg_base": "build-python-wheel"}},
    zip_safe=False,
)
