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
  libmeshoptimizer-dev           # glTF buffers compressed with EXT_meshopt_compression (gltfpack -c)
  libpng-dev                     # PNG images for people
  libfreetype-dev fonts-dejavu-core  # text in PNG heatmap legends and bench charts
  libgtest-dev                   # the test suite
  libgmp-dev                     # exact rationals: coverage without snapping (rasterizer/orientation.cpp), the tests' oracle
  libbenchmark-dev               # Google Benchmark microbenchmarks of the kernels (bench/)
)

if [[ "${1:-}" == "--test" ]]; then
  packages+=(chromium)           # opens the HTML report headless in the tests
  packages+=(gltfpack)           # writes quantised and meshopt-compressed glTF for the loader tests
  packages+=(clang libclang-rt-14-dev)  # libFuzzer and its sanitizer runtimes (scripts/fuzz.sh)
  packages+=(locales util-linux)  # a comma-decimal locale and a pseudo-terminal for the CLI tests
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

# With --test, as root: generate the de_DE.UTF-8 locale the locale test runs under.
ensure_test_locale() {
  if [[ "${1:-}" == "--test" && $(id -u) -eq 0 ]] && ! locale -a 2>/dev/null | grep -qi '^de_DE.utf8$'; then
    sed -i 's/^# *de_DE.UTF-8 UTF-8/de_DE.UTF-8 UTF-8/' /etc/locale.gen
    grep -q '^de_DE.UTF-8 UTF-8' /etc/locale.gen || echo 'de_DE.UTF-8 UTF-8' >> /etc/locale.gen
    locale-gen > /dev/null
  fi
}

if ((${#missing[@]} == 0)); then
  echo "setup: all ${#packages[@]} packages are installed"
  ensure_test_locale "${1:-}"
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
ensure_test_locale "${1:-}"
