#!/usr/bin/env bash
# The pip package end to end: builds a wheel from the checkout with Debian's
# tools (python3 -m build --wheel --no-isolation), checks its metadata,
# installs it into a fresh virtual environment (--system-site-packages, for
# Debian's numpy and matplotlib) and runs the Python test suites against the
# installed package, from outside the build tree.
#
#   wheel_test.sh PYTHON SOURCE_DIR [BUILD_DIR]
#
# With BUILD_DIR the wheel reuses that CMake tree (DELTAMESH_BUILD_DIR: the
# extension is up to date, nothing is recompiled); without it setup.py
# configures and compiles a fresh Release tree, as `pip install .` does for a
# user (minutes: the ctest label `long`). Exit 77 (skipped) when the tools
# are missing (scripts/install-deps.sh installs them).
set -euo pipefail
python=$1 src=$(cd "$2" && pwd) build=${3:-}
for mod in build setuptools wheel venv ensurepip; do
  "$python" -c "import $mod" 2>/dev/null || { echo "wheel_test: python module '$mod' missing: skipped"; exit 77; }
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"  # not in the checkout: its build/ directory would shadow the 'build' module
if [ -n "$build" ]; then export DELTAMESH_BUILD_DIR=$build; fi
export DELTAMESH_JOBS=${DELTAMESH_JOBS:-2} PYTHONDONTWRITEBYTECODE=1
unset PYTHONPATH
"$python" -m build --wheel --no-isolation --outdir "$tmp/dist" "$src" > "$tmp/build.log" 2>&1 || {
  cat "$tmp/build.log"; exit 1; }
wheel=$(ls "$tmp"/dist/deltamesh-*.whl)
echo "wheel_test: built $(basename "$wheel")"

# The metadata: name, the project's version, licence, numpy, optional matplotlib.
version=$(sed -n 's/^project(deltamesh VERSION \([0-9.]*\).*/\1/p' "$src/CMakeLists.txt")
"$python" - "$wheel" "$version" <<'PY'
import re, sys, zipfile
wheel, version = sys.argv[1:]
with zipfile.ZipFile(wheel) as z:
    names = z.namelist()
    meta = z.read(next(n for n in names if n.endswith(".dist-info/METADATA"))).decode()
fields = [line.split(": ", 1) for line in meta.splitlines() if ": " in line and not line.startswith(" ")]
get = lambda k: [v for f, v in fields if f == k]
problems = []
if get("Name") != ["deltamesh"]: problems.append(f"Name {get('Name')}")
if get("Version") != [version]: problems.append(f"Version {get('Version')} (CMakeLists.txt: {version})")
if not get("License") or not get("License")[0].strip(): problems.append("no License")
if not any(r.startswith("numpy") for r in get("Requires-Dist")): problems.append("numpy not required")
if "plot" not in get("Provides-Extra"): problems.append("no 'plot' extra")
if not any(r.startswith("matplotlib") and re.search(r"extra == ['\"]plot['\"]", r) for r in get("Requires-Dist")):
    problems.append("matplotlib not in the 'plot' extra")
for want in ("deltamesh/__init__.py", "deltamesh/data.py", "deltamesh/plot.py", "deltamesh/data/ell.1.node"):
    if want not in names: problems.append(f"{want} not in the wheel")
if not any(n.startswith("deltamesh/_deltamesh") and n.endswith(".so") for n in names):
    problems.append("the extension is not in the wheel")
if problems:
    sys.exit("wheel_test: metadata: " + "; ".join(problems))
print("wheel_test: metadata complete:", ", ".join(f"{k}={get(k)[0]}" for k in ("Name", "Version", "License")))
PY

"$python" -m venv --system-site-packages "$tmp/venv"
"$tmp/venv/bin/python" -m pip install --no-index --no-deps --quiet "$wheel"
cd "$src/python/tests"  # the tests' own directory: it holds no package named deltamesh
"$tmp/venv/bin/python" -c "
import sys, deltamesh
assert deltamesh.__file__.startswith(sys.prefix), deltamesh.__file__
print('wheel_test: testing', deltamesh.__file__)"
MPLBACKEND=Agg "$tmp/venv/bin/python" -m unittest test_triangle_compat test_deltamesh test_deltamesh_io
