#!/usr/bin/env bash
# Installs what is missing, builds softsub (Release) into build/ and runs the embedded
# default scene: two substances of different viscosity dropped into a container, 48
# frames written to ./softsub-demoSim/ (.sim, Maya .pdc and .ply per frame).
# Extra arguments go to `softsub run` (e.g. --frames 12, --out DIR).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

./scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build --target softsub -j2
build/src/app/softsub run "$@"

if (($# == 0)); then
  echo
  echo "demo: the frames are in $(pwd)/softsub-demoSim/"
  echo "  softsub-demo.NNNN.sim           one XML file per frame (positions per fluid)"
  echo "  pdc/<Fluid>Shape.<ticks>.pdc    Maya particle disk cache per fluid and frame"
  echo "  ply/softsub-demo.NNNN.ply       binary point cloud per frame (Houdini, Blender, ParaView)"
  echo "demo: summary of the last frame: build/src/app/softsub info softsub-demoSim/softsub-demo.0048.sim"
fi
