#!/usr/bin/env bash
# Renders small releases of every configuration the project has (maps with every kind and flow
# gaps, every weather and time of day, a sky map, the final pass, each rig preset, a lens rig with
# a rolling shutter, adaptive sampling, the U-Net, every flow format, the other class table, legacy
# actors, the ERP alone, the example scenarios) with two builds and compares them file by file:
# what a refactoring must leave alone.
#
#   scripts/same_bytes.sh BASE_REV [BUILD]   BASE_REV (a commit) built into build-same-bytes/<rev>
#                                            (once; Release, tests off) against BUILD (default build/)
#   scripts/same_bytes.sh BASE_BUILD [BUILD] an already built tree as the base
#   SAME_BYTES_TREE=sequences scripts/same_bytes.sh ...
#                                            compares only that folder of each release: the
#                                            images, ground truth and meta.json, when a change adds
#                                            an option (its key then enters config.json, the card,
#                                            the manifest and the explorer's data)
#
# Prints one line per configuration and exits 1 if any file differs (its first differing files
# named). Both builds run on this machine, so they run the same Embree kernels.
set -euo pipefail
cd "$(dirname "$0")/.."
base=$1
build=${2:-build}
if [ ! -x "$base/apps/gen_flowscape" ]; then  # a revision: built once, beside the tree
  rev=$(git rev-parse --short "$base")
  tree=build-same-bytes/$rev
  if [ ! -x "$tree/build/apps/gen_flowscape" ]; then
    rm -rf "$tree" && mkdir -p build-same-bytes
    git worktree add --detach "$tree/src" "$rev" >/dev/null
    cmake -S "$tree/src" -B "$tree/build" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF \
      -DFLOWSCAPE_PYTHON_EXTENSION=OFF >/dev/null
    cmake --build "$tree/build" -j "$(nproc)" --target gen_flowscape >/dev/null
  fi
  base=$tree/build
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
tiny=(--sequences-per-map 2 --frames 3 --resolution 16 --face-size 8 --vehicles 8 --pedestrians 4
      --seed 11)
lenses=(--maps 1 --sequences-per-map 1 --frames 3 --spp 2 --vehicles 8 --pedestrians 4 --seed 11)
configs=(
  "maps:${tiny[*]} --maps 2 --spp 2"
  "every-kind:${tiny[*]} --maps 1 --spp 2 --outputs all --flow-gaps 1,2"
  "weathers:--maps 1 --sequences-per-map 4 --frames 3 --resolution 16 --face-size 8 --spp 2 --vehicles 8 --pedestrians 4 --seed 11 --weather cloud,fog,rain,sunny --time-of-day dusk,day,night,dawn --sky physical,park"
  "final:${tiny[*]} --maps 1 --spp 2 --outputs final --time-of-day day,night"
  "adaptive:${tiny[*]} --maps 1 --spp 4 --adaptive 0.25"
  "oidn:${tiny[*]} --maps 1 --spp 2 --denoise oidn"
  "no-denoiser:${tiny[*]} --maps 1 --spp 2 --denoise none"
  "kitti-png:${tiny[*]} --maps 1 --spp 2 --flow-format kitti-png --outputs flow_backward"
  "half-exr:${tiny[*]} --maps 1 --spp 2 --flow-format half-exr"
  "classes:${tiny[*]} --maps 1 --spp 2 --classes carla-0.9.14"
  "legacy:${tiny[*]} --maps 1 --spp 2 --actors legacy"
  "erp-only:${tiny[*]} --maps 1 --spp 2 --no-cube"
  "erp-final:${tiny[*]} --maps 1 --spp 2 --no-cube --outputs final --time-of-day night,day"
  "fisheye:${lenses[*]} --rig fisheye --resolution 24 --outputs final"
  "woodscape:${lenses[*]} --rig woodscape --resolution 16"
  "pal:${lenses[*]} --rig pal --resolution 24"
  "dual-fisheye:${lenses[*]} --rig dual-fisheye --resolution 16"
  "rolling:${lenses[*]} --rig tests/kernels/lens_rig.json --outputs all"
  "calibration:${lenses[*]} --rig-from docs/rigs/kalibr_stereo.yaml --rig-mount 0.5,0,0.3,0,-5,0 --scale 0.05"
  "scenarios:--scenario examples/scenarios/drone_junction.json examples/scenarios/lane_change_in_rain_at_dusk.json --frames 3 --resolution 16 --face-size 8 --spp 2"
  "own-world:--scenario examples/scenarios/user_world_square.json --frames 3 --resolution 16 --spp 2"
)
failed=0
for entry in "${configs[@]}"; do
  name=${entry%%:*}
  read -r -a options <<<"${entry#*:}"
  for side in base new; do
    bin=$base
    [ $side = new ] && bin=$build
    "$bin/apps/gen_flowscape" "${options[@]}" --threads 2 --out "$work/$side-$name" >"$work/$side-$name.log" 2>&1 ||
      { echo "$name: the $side build failed: $(tail -n 1 "$work/$side-$name.log")"; failed=1; continue 2; }
  done
  tree=${SAME_BYTES_TREE:-.}
  if differences=$(diff -rq "$work/base-$name/$tree" "$work/new-$name/$tree"); then
    echo "$name: the same bytes ($(find "$work/new-$name/$tree" -type f | wc -l) files in $tree)"
  else
    echo "$name: DIFFERS: $(echo "$differences" | head -n 3 | tr '\n' ' ')"
    failed=1
  fi
done
exit $failed
