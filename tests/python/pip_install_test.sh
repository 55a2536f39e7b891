#!/usr/bin/env bash
# CTest python/pip_install: `pip install` of the package igm into a fresh venv (made with
# --system-site-packages from Debian's python3: pip, numpy, setuptools and wheel come from there),
# offline (--no-index --no-build-isolation), reusing the CMake build BUILD (IGM_CMAKE_BUILD_DIR),
# from a copy of the packaging files; then import it from the venv and compute.
# Usage: pip_install_test.sh SOURCE_DIR BUILD_DIR WORK_DIR PYTHON
set -euo pipefail
src="$1" build="$2" work="$3" py="$4"
rm -rf "$work"
mkdir -p "$work/src"
cp -r "$src/pyproject.toml" "$src/setup.py" "$src/README.md" "$src/LICENSE" "$src/python" "$work/src/"
# --without-pip: the venv runs Debian's pip from the system site-packages (6 s less than ensurepip).
"$py" -m venv --system-site-packages --without-pip "$work/venv"
IGM_CMAKE_BUILD_DIR="$build" "$work/venv/bin/python" -m pip install --quiet --no-index --no-build-isolation "$work/src"
cd "$work"
"$work/venv/bin/python" - <<PYEOF
import igm
assert igm.__file__.startswith("$work/venv/"), igm.__file__
V, F = igm.generate(1, 200)
r = igm.compute(V, F)
assert r["certified"], r["certificate"]
print("pip-installed igm", igm.__version__, "from", igm.__file__, ": certified")
PYEOF
