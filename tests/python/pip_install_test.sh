#!/usr/bin/env bash
# CTest python/pip_install (Release run only: the Python module is not built under the
# sanitizers): README.md's offline install command, read from README.md, run as it stands in a copy
# of the packaging files, with its `python3` the interpreter the module was built for and its venv
# V in WORK_DIR; then the module imported from that venv and a tiny compute certified.
# IGM_CMAKE_BUILD_DIR=BUILD_DIR lets setup.py reuse this CMake build (only the target igm_python)
# instead of configuring and building the library again (minutes); the command is the same.
# Usage: pip_install_test.sh SOURCE_DIR BUILD_DIR WORK_DIR PYTHON
set -euo pipefail
src="$1" build="$2" work="$3" py="$4"
line=$(grep -E '^    python3 -m venv --system-site-packages V && V/bin/pip install --no-build-isolation --no-index \.$' \
  "$src/README.md" || true)
if [ -z "$line" ]; then
  echo "pip_install_test: README.md has no line '    python3 -m venv --system-site-packages V && V/bin/pip install --no-build-isolation --no-index .'" >&2
  exit 1
fi
rm -rf "$work"
mkdir -p "$work/src"
cp -r "$src/pyproject.toml" "$src/setup.py" "$src/README.md" "$src/LICENSE" "$src/python" "$work/src/"
# The line with V in WORK_DIR and python3 the build's interpreter.
cmd=$(printf '%s\n' "${line#    }" | sed -e "s|^python3 |\"$py\" |" -e "s| V && V/bin/pip | \"$work/V\" \&\& \"$work/V/bin/pip\" |")
echo "pip_install_test: $cmd"
(cd "$work/src" && export IGM_CMAKE_BUILD_DIR="$build" && eval "$cmd")
cd "$work"
"$work/V/bin/python" - <<PYEOF
import igm
assert igm.__file__.startswith("$work/V/"), igm.__file__
V, F = igm.generate(1, 200)
r = igm.compute(V, F, quads=50, quality=False)
assert r["certified"], r["certificate"]
print("pip-installed igm", igm.__version__, "from", igm.__file__, ": certified")
PYEOF
