#!/usr/bin/env bash
# Every Embree kernel family this CPU runs (FLOWSCAPE_EMBREE_CONFIG=isa=...): a small release of
# every kind (the flowscape rig's ERP and faces with the final pass; a lens rig with a fisheye and
# a rolling-shutter pinhole) renders under each without an abort; families of the same arithmetic
# (sse2, sse4.2) give the same bytes, the others the same files within docs/release.md's bounds.
set -u
bin=$1
python=$2
here=$(dirname "$0")
source "$here/shell_checks.sh"
small=(--maps 1 --frames 3 --resolution 16 --face-size 8 --spp 2 --vehicles 12 --pedestrians 6 --seed 2)
flowscape=("${small[@]}" --sequences-per-map 1 --outputs all --flow-gaps 1,2)
lenses=(--rig "$here/kernels/lens_rig.json" --maps 1 --sequences-per-map 1 --frames 3 --spp 2
        --vehicles 12 --pedestrians 6 --outputs all --seed 2)
families=()
for family in sse2 sse4.2 avx avx2 avx512; do  # those this CPU runs
  FLOWSCAPE_EMBREE_CONFIG=isa=$family "$bin/gen_flowscape" --version >/dev/null 2>&1 && families+=("$family")
done
echo "kernel families here: ${families[*]}"
check "at least sse2 and sse4.2" test "${#families[@]}" -ge 2
for family in "${families[@]}"; do
  for rig in flowscape lenses; do
    declare -n options=$rig
    check "$rig under $family kernels" env FLOWSCAPE_EMBREE_CONFIG=isa=$family \
      "$bin/gen_flowscape" "${options[@]}" --out "$work/$rig-$family"
    check "$rig under $family: meta.json names the kernels" \
      grep -q "\"kernels\":\"$family\"" "$work/$rig-$family/sequences/map00_seq00/meta.json"
  done
done
compare() { "$python" "$here/kernels/compare_releases.py" "$@"; }
for rig in flowscape lenses; do
  check "$rig: sse2 and sse4.2 (the same arithmetic) give the same bytes" \
    compare "$work/$rig-sse2" "$work/$rig-sse4.2" identical
  for family in "${families[@]:2}"; do
    check "$rig: $family within the bounds of sse4.2's" \
      compare "$work/$rig-sse4.2" "$work/$rig-$family" bounded
  done
done
best=${families[-1]}
# the other libraries that pick kernels at run time: OpenCV's SIMD dispatch (the final pass's blurs
# and resampling) changes no byte; oneDNN's (--denoise oidn) a few colour values
check "OpenCV's dispatch held to its SSE2 baseline: the same bytes" env FLOWSCAPE_EMBREE_CONFIG=isa=$best \
  OPENCV_CPU_DISABLE=SSE3,SSSE3,SSE4.1,SSE4.2,POPCNT,FP16,AVX,AVX2,FMA3,AVX512F,AVX512BW,AVX512CD,AVX512DQ,AVX512VL,AVX512-SKX \
  "$bin/gen_flowscape" "${flowscape[@]}" --out "$work/opencv-sse2"
check "OpenCV's SSE2 baseline = its best dispatch, byte for byte" \
  compare "$work/flowscape-$best" "$work/opencv-sse2" identical
if "$bin/gen_flowscape" --denoise oidn --check >/dev/null 2>&1; then
  for isa in AVX2 DEFAULT; do
    check "the U-Net under oneDNN's $isa kernels" env ONEDNN_MAX_CPU_ISA=$isa \
      "$bin/gen_flowscape" "${small[@]}" --sequences-per-map 1 --outputs none --denoise oidn \
      --out "$work/onednn-$isa"
  done
  check "oneDNN's AVX2 and best kernels: the colour within bounds" \
    compare "$work/onednn-AVX2" "$work/onednn-DEFAULT" bounded
fi

for shard in 0 1; do
  family=$([ $shard = 0 ] && echo sse4.2 || echo "$best")
  FLOWSCAPE_EMBREE_CONFIG=isa=$family "$bin/gen_flowscape" "${small[@]}" --sequences-per-map 2 \
    --shard $shard/2 --out "$work/mixed" >/dev/null 2>&1
done
check "shards of sse4.2 and $best merge, with one line saying the families differ" \
  bash -c "'$bin/flowscape_merge' '$work/mixed' 2>'$work/merge_err' >/dev/null &&
           grep -q 'different Embree kernel families ($best 1, sse4.2 1 sequences)' '$work/merge_err'"
check "a misspelt instruction set is refused before anything is written" \
  fails_clearly 'FLOWSCAPE_EMBREE_CONFIG="isa=avx3": unknown instruction set "avx3"' \
  env FLOWSCAPE_EMBREE_CONFIG=isa=avx3 "$bin/gen_flowscape" "${flowscape[@]}" --out "$work/misspelt"
check "refused: no folder" test ! -e "$work/misspelt"
finish
