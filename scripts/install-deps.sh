#!/usr/bin/env bash
# Installs the Debian packages deltamesh needs, only those that are missing.
# Usage: scripts/install-deps.sh [core|bench|fuzz|web|browser]...
# web: emscripten (make web); browser: chromium and npm (make test-web).
set -euo pipefail
want=(g++ make cmake libgtest-dev libgmock-dev libbenchmark-dev libgmp-dev libxml2-utils gmsh python3-meshio librsvg2-bin
      nlohmann-json3-dev  # JSON statistics (--stats=json)
      pybind11-dev python3-dev python3-numpy  # Python bindings (python/)
      python3-setuptools python3-wheel python3-build python3-venv python3-pip python3-matplotlib)  # the pip package and its test
for group in "$@"; do
  case "$group" in
    core) ;;
    bench) want+=(libcgal-dev) ;;
    fuzz) want+=(clang libclang-rt-14-dev) ;;
    web) want+=(emscripten) ;;
    # npm only when there is none: a node installed outside Debian brings its own.
    browser) want+=(chromium); command -v npm >/dev/null || want+=(npm) ;;
    *) echo "install-deps: unknown group '$group'" >&2; exit 2 ;;
  esac
done
missing=()
for pkg in "${want[@]}"; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || missing+=("$pkg")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
[ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
