#!/usr/bin/env bash
# Installs the Debian 12 packages rastercheck builds with (and, with --test, what the test
# suite also uses: Chromium for the HTML report test, clang for fuzzing). As root it installs what is missing;
# otherwise it names the missing packages and exits 1.
set -euo pipefail

packages=(
  g++ cmake make                 # toolchain (C++20, g++ 12)
  libembree-dev libtbb-dev       # the reference (Embree 3 and its tasking system)
  libopenexr-dev                 # EXR input and output (OpenEXR 3)
  libglm-dev                     # vector math
  libcli11-dev                   # the command line
  nlohmann-json3-dev             # JSON reports and scene files
  libtinyobjloader-dev           # OBJ meshes
  libtinygltf-dev                # glTF 2.0 scenes
  libpng-dev                     # PNG images for people
  libfreetype-dev fonts-dejavu-core  # legend text in PNG heatmaps
  libgtest-dev                   # the test suite
)

if [[ "${1:-}" == "--test" ]]; then
  packages+=(chromium)           # opens the HTML report headless in the tests
  packages+=(clang libclang-rt-14-dev)  # libFuzzer and its sanitizer runtimes (scripts/fuzz.sh)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "setup: all ${#packages[@]} packages are installed"
  exit 0
fi
if [[ $(id -u) -ne 0 ]]; then
  echo "setup: missing Debian packages: ${missing[*]}" >&2
  echo "setup: run this script as root, or: sudo apt-get install ${missing[*]}" >&2
  exit 1
fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
