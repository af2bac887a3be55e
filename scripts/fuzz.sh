#!/usr/bin/env bash
# The libFuzzer targets (fuzz/, docs/robustness.md), built with clang in build-fuzz/ with
# -fsanitize=fuzzer,address,undefined. Replays every input of fuzz/regressions/<target>/,
# then runs each target for FUZZ_SECONDS (default 60) on seeds from examples/, tests/data
# and fuzz/seeds/. Fails on any crash, sanitizer report, leak or timeout; the input that
# did it is left as build-fuzz/findings/<target>/crash-* (copy it to fuzz/regressions/).
#   scripts/fuzz.sh                    all three targets, a minute each
#   FUZZ_SECONDS=600 scripts/fuzz.sh   longer
#   scripts/fuzz.sh scene_reader       one target
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

seconds=${FUZZ_SECONDS:-60}
targets=("$@")
((${#targets[@]})) || targets=(scene_reader mesh_loader frame_readers)

./scripts/install-deps.sh
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DSOFTSUB_FUZZ=ON -DSOFTSUB_WERROR=ON
cmake --build build-fuzz -j2

# Seeds: the corpus a target starts from (not committed: made from the repository's files).
# Only the chosen targets' folders are remade, so two runs of different targets can share
# build-fuzz/.
seeds=build-fuzz/seeds
for t in "${targets[@]}"; do
  rm -rf "${seeds:?}/$t"
  mkdir -p "$seeds/$t"
  n=0
  case $t in
    scene_reader)
      for s in examples/*.scene tests/data/scenes/good/*.scene tests/data/scenes/bad/*.scene tests/data/bad/*.scene; do
        cp "$s" "$seeds/$t/seed-$((n++))-$(basename "$s")"
      done ;;
    mesh_loader)  # the first byte picks the extension (0 .obj, 1 .ply, 2 .stl)
      for m in examples/*Geo/*.obj tests/data/scenes/good/*Geo/*.obj tests/data/bad/meshes/* fuzz/seeds/meshes/*; do
        case "${m,,}" in
          *.obj) prefix='\x00' ;; *.ply) prefix='\x01' ;; *.stl) prefix='\x02' ;; *) continue ;;
        esac
        { printf "$prefix"; cat "$m"; } > "$seeds/$t/seed-$((n++))"
      done ;;
    frame_readers) cp fuzz/seeds/frames/* "$seeds/$t/" ;;
    *) echo "fuzz: unknown target $t (scene_reader, mesh_loader, frame_readers)" >&2; exit 2 ;;
  esac
done

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/fuzz/lsan-suppressions.txt}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
status=0
for t in "${targets[@]}"; do
  bin=build-fuzz/fuzz/fuzz_$t
  regressions=fuzz/regressions/$t
  if compgen -G "$regressions/*" >/dev/null; then
    echo "fuzz: $t: replaying $(ls "$regressions" | wc -l) regression input(s)"
    "$bin" -rss_limit_mb=2048 -timeout=10 "$regressions"/* || { status=1; continue; }
  fi
  findings=build-fuzz/findings/$t
  work=build-fuzz/corpus/$t
  mkdir -p "$findings" "$work"
  echo "fuzz: $t: ${seconds} s"
  # -fork would use both cores, but keeps going past a crash; one process stops at it.
  if ! "$bin" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -max_len=65536 \
      -artifact_prefix="$findings/" -print_final_stats=1 "$work" "$seeds/$t" 2>&1 |
      tail -n 40; then
    echo "fuzz: $t FAILED: see $findings/" >&2
    status=1
  fi
done
exit $status
