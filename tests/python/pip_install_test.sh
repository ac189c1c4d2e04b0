#!/usr/bin/env bash
# The wheel's install path: `pip install SOURCE_DIR` into a fresh venv, offline (no index, no build
# isolation: the backend is Debian's setuptools), then the installed package is imported from
# elsewhere and its metadata checked: importlib.metadata.version, `pip show`, __version__, all the
# project's one version number (CMakeLists.txt), and the extension and its modules in the venv.
#
#   pip_install_test.sh SOURCE_DIR BUILD_DIR PYTHON
#
# BUILD_DIR (already built: ctest runs after the build) is handed to the backend as
# OSCILAB_CMAKE_BUILD_DIR, so the test costs a venv, a no-op build and a copy, not a compilation.
set -euo pipefail
source_dir=$1
build_dir=$2
python=$3

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$python" -m venv --system-site-packages "$work/venv"
venv_python="$work/venv/bin/python"

OSCILAB_CMAKE_BUILD_DIR="$build_dir" PIP_NO_INDEX=1 PIP_DISABLE_PIP_VERSION_CHECK=1 \
  "$venv_python" -m pip install --no-build-isolation --quiet "$source_dir"

expected=$(sed -n 's/^project(Oscilab VERSION \([0-9.]*\).*/\1/p' "$source_dir/CMakeLists.txt")
cd "$work"  # not the source tree: the installed package must be the one imported
"$venv_python" - "$expected" "$work/venv" <<'PY'
import importlib.metadata
import pathlib
import sys

import oscilab

expected, venv = sys.argv[1], pathlib.Path(sys.argv[2]).resolve()
package = pathlib.Path(oscilab.__file__).resolve().parent
assert venv in package.parents, f"imported {package}, not the venv's package"
assert importlib.metadata.version("oscilab") == expected, importlib.metadata.version("oscilab")
assert oscilab.__version__ == expected, oscilab.__version__
files = {str(f) for f in importlib.metadata.files("oscilab")}
for module in ("liboscilab_cmaes.so", "oscilab_hdf5_module.so", "oscilab_png_module.so"):
    assert any(f.endswith("/" + module) for f in files), f"{module} is not in the wheel: {files}"
assert any(f.startswith("oscilab/_native/_oscilab.") for f in files), files
for typed in ("oscilab/py.typed", "oscilab/__init__.pyi", "oscilab/_signatures.py"):
    assert typed in files, f"{typed} is not in the wheel"
assert oscilab.Model.paper().summary()["mass_kg"] > 0
print("installed oscilab", oscilab.__version__, "in", package)
PY
shown=$("$venv_python" -m pip show oscilab)
grep -x "Name: oscilab" <<<"$shown"
grep -x "Version: $expected" <<<"$shown"
