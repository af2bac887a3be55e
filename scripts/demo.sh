#!/usr/bin/env bash
# Installs what is missing, builds softsub (Release) into build/ and runs the embedded
# default scene: two substances of different viscosity dropped into a container, 48
# frames written to ./softsub-demoSim/ (.sim, Maya .pdc and .ply per frame) and a
# picture of the last frame (softsub-demo.preview.png, drawn off-screen).
# Extra arguments go to `softsub run` (e.g. --frames 12, --out DIR).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

./scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build --target softsub -j2
if (($# == 0)); then
  build/src/app/softsub run --preview
else
  build/src/app/softsub run "$@"
fi

if (($# == 0)); then
  echo
  echo "demo: the frames are in $(pwd)/softsub-demoSim/"
  echo "  softsub-demo.NNNN.sim           one XML file per frame (positions per fluid)"
  echo "  pdc/<Fluid>Shape.<ticks>.pdc    Maya particle disk cache per fluid and frame"
  echo "  ply/softsub-demo.NNNN.ply       binary point cloud per frame (Houdini, Blender, ParaView)"
  echo "  softsub-demo.preview.png        a picture of the last frame"
  echo "demo: summary of the last frame: build/src/app/softsub info softsub-demoSim/softsub-demo.0048.sim"
  echo "demo: watch it live (needs a display): build/src/app/softsub view"
fi
