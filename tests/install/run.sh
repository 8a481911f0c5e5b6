#!/usr/bin/env bash
# `cmake --install` into a temporary prefix, then use what was installed:
# the CLI, the library through find_package(deltamesh) from a separate
# project, and (when built) the Python module from the site directory.
# Usage: run.sh BUILD_DIR SOURCE_DIR [PYTHON PYTHON_INSTALL_DIR]
set -euo pipefail
build=$1 src=$2 python=${3:-} pydir=${4:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
prefix=$tmp/prefix
cmake --install "$build" --prefix "$prefix" >/dev/null
"$prefix/bin/deltamesh" --version
test -f "$prefix/include/deltamesh/deltamesh.hpp"
cmake -S "$src/tests/install" -B "$tmp/consumer" -DCMAKE_PREFIX_PATH="$prefix" \
  -DPLATE_SOURCE="$src/examples/plate.cpp" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$tmp/consumer" >/dev/null
(cd "$tmp" && "$tmp/consumer/plate" "$src/examples/plate.poly")
test -s "$tmp/plate.1.ele"
if [ -n "$python" ]; then
  # Only the installed copy is on the path (not the build tree's).
  (cd "$tmp" && PYTHONPATH="$prefix/$pydir" "$python" -c '
import deltamesh, sys
assert deltamesh.__file__.startswith(sys.argv[1]), deltamesh.__file__
m = deltamesh.triangulate(deltamesh.read(sys.argv[2]), "pq30")
deltamesh.validate(m)
print("python module:", deltamesh.__file__, len(m["triangles"]), "triangles")
' "$prefix" "$src/examples/plate.poly")
fi
echo "install: ok"
