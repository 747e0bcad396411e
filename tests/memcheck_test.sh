#!/usr/bin/env bash
# Tiny releases under valgrind's memcheck (docs/release.md, "Determinism"): no byte that was never
# written reaches Embree (every lane of every ray and packet, checked at the call by the LD_PRELOAD
# shim defined_rays_preload.cpp), the encoders or the files (memcheck's own checks of what a
# library branches on and of write(2)). The flowscape rig with every kind and the final pass in a
# city map; a fisheye and a rolling-shutter pinhole (whose lens circle leaves packets part empty)
# in the example user world, denoised by the U-Net (oneDNN) where the build has it; the plugin's
# extension reading and remapping their files. About two minutes: valgrind runs the renderer some
# 40 times slower.
set -u
bin=$1
preload=$2
python=$3
extension_dir=$4  # where the plugin's flowscape_native lives (none: a build without it)
here=$(dirname "$0")
source "$here/shell_checks.sh"
command -v valgrind >/dev/null || { echo "valgrind is missing (scripts/install_deps.sh installs it)"; exit 1; }
# valgrind must be able to run this CPU's code at all: where it cannot decode an instruction a
# library runs while it loads (libhwy's rdtscp on a CPU without it, under valgrind 3.19) the test is
# reported skipped (CTest's SKIP_RETURN_CODE 77), naming the instruction's place
if ! valgrind -q "$bin/gen_flowscape" --version >/dev/null 2>"${TMPDIR:-/tmp}/memcheck-probe.$$"; then
  if grep -q "Illegal opcode" "${TMPDIR:-/tmp}/memcheck-probe.$$"; then
    echo "SKIPPED: valgrind cannot run this CPU's code: $(grep -m1 ' at 0x' "${TMPDIR:-/tmp}/memcheck-probe.$$")"
    rm -f "${TMPDIR:-/tmp}/memcheck-probe.$$"
    exit 77
  fi
fi
rm -f "${TMPDIR:-/tmp}/memcheck-probe.$$"
memcheck() {
  LD_PRELOAD=$preload valgrind -q --error-exitcode=1 --num-callers=24 "$@" >"$work/out" 2>"$work/err" ||
    { tail -n 60 "$work/err" >&2; return 1; }
}
python_memcheck() {  # Python's own allocator and start-up, as valgrind's Debian suppressions know them
  PYTHONMALLOC=malloc PYTHONPATH=$extension_dir memcheck --suppressions=/usr/lib/valgrind/python3.supp "$python" "$@"
}
tiny=(--frames 2 --spp 2 --threads 2 --seed 1)
check "memcheck: the flowscape rig, every kind, the final pass" \
  memcheck "$bin/gen_flowscape" "${tiny[@]}" --maps 1 --sequences-per-map 1 --vehicles 2 --pedestrians 1 \
  --resolution 8 --face-size 4 --outputs all --out "$work/flowscape"
denoise=atrous
"$bin/gen_flowscape" --denoise oidn --check >/dev/null 2>&1 && denoise=oidn
check "memcheck: a fisheye and a rolling-shutter pinhole, denoised by $denoise" \
  memcheck "$bin/gen_flowscape" "${tiny[@]}" --scenario "$here/../examples/scenarios/user_world_square.json" \
  --rig "$here/kernels/lens_rig.json" --scale 0.5 --outputs flow_backward,final --denoise $denoise --out "$work/lenses"
if ls "$extension_dir"/flowscape_native*.so >/dev/null 2>&1; then
  seq=$work/flowscape/sequences/map00_seq00
  check "memcheck: the plugin's extension hands Python only written bytes" \
    python_memcheck "$here/python/memcheck_native.py" "$work/arrays.npz" "$seq/erp/color/000000.png" \
    "$seq/erp/depth/000000.exr" "$seq/cube/front/instance/000001.png" "$seq/erp/normal/000000.exr"
fi
finish
