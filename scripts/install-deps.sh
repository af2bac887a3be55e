#!/usr/bin/env bash
# Installs what softsub needs to build and test, from Debian 12 (bookworm) packages, and
# only what is missing: when everything is present it returns at once without apt-get.
# Runs apt-get as root, or through sudo when not root.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config  # compiler and build tools
  libeigen3-dev libpugixml-dev libfmt-dev libcli11-dev libassimp-dev  # libraries softsub links
  libgl-dev libegl-dev libpng-dev libglfw3-dev libimgui-dev  # renderer and viewer
  libegl-mesa0 libgl1-mesa-dri  # OpenGL without a GPU or display (Mesa's llvmpipe through EGL)
  googletest libgtest-dev libgmock-dev libbenchmark-dev  # tests and benchmarks
  xvfb xauth  # the viewer's test runs it in a virtual X display
  ffmpeg  # 'softsub render --movie' (optional for users; tested)
  blender python3  # the Blender add-on's tests run it headless (blender/, tests/blender/)
  libopenvdb-dev libtbb-dev libboost-dev  # surfaces (level sets, meshing, .vdb); OpenVDB's headers need Boost's but the package does not depend on it
  clang libclang-rt-14-dev  # the libFuzzer targets (scripts/test.sh --fuzz); the runtime is only "recommended" by clang
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages are installed"
  exit 0
fi

if [[ $(id -u) -eq 0 ]]; then
  as_root=()
elif command -v sudo >/dev/null 2>&1; then
  as_root=(sudo)
else
  echo "install-deps: missing ${missing[*]}; run this script as root (or install sudo)" >&2
  exit 1
fi

echo "install-deps: installing ${missing[*]}"
"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
