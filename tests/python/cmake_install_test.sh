#!/usr/bin/env bash
# The set-up's install path of the Python package: `cmake --install BUILD_DIR --component python`
# (what scripts/setup.sh runs into /usr/local) into a temporary prefix, then the package imported
# from there, away from the build tree: the extension, Oscilab's modules, the stubs and py.typed.
#
#   cmake_install_test.sh BUILD_DIR PYTHON
set -euo pipefail
build_dir=$1
python=$2

prefix=$(mktemp -d)
trap 'rm -rf "$prefix"' EXIT
cmake --install "$build_dir" --component python --prefix "$prefix" >/dev/null
install_dir=$(sed -n 's/^OSCILAB_PYTHON_INSTALL_DIR:STRING=//p' "$build_dir/CMakeCache.txt")
cd "$prefix"
PYTHONPATH="$prefix/$install_dir" PYTHONNOUSERSITE=1 "$python" - "$prefix" <<'PY'
import pathlib
import sys

import oscilab

prefix = pathlib.Path(sys.argv[1]).resolve()
package = pathlib.Path(oscilab.__file__).resolve().parent
assert prefix in package.parents, f"imported {package}, not the installed package"
for name in ("py.typed", "__init__.pyi", "_signatures.py", "lib/oscilab/liboscilab_cmaes.so",
             "lib/oscilab/oscilab_hdf5_module.so", "lib/oscilab/oscilab_png_module.so"):
    assert (package / name).is_file(), f"{name} is not installed"
assert oscilab.Model.paper().summary()["mass_kg"] > 0
print("cmake --install: oscilab", oscilab.__version__, "in", package)
PY
