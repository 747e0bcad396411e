#!/usr/bin/env bash
# Install without root (issue 35, point 13): a configure with every optional part off looks for
# none of their libraries and builds the denoiser's absence; pip builds the plugin's extension
# (a plugin-only CMake build) and the wheel it makes reads images natively.
set -u
source_dir=$1
source "$(dirname "$0")/shell_checks.sh"

off="$work/off"
check "configure with the optional parts off" cmake -S "$source_dir" -B "$off" -DCMAKE_BUILD_TYPE=Release \
  -DFLOWSCAPE_DENOISER=OFF -DFLOWSCAPE_PYTHON_EXTENSION=OFF -DBUILD_TESTING=OFF
for package in dnnl pybind11 Catch2 OpenMP_CXX_FLAGS; do
  check "$package not looked for" bash -c "! grep -q '^${package}[_A-Z]*:' '$off/CMakeCache.txt'"
done
check "gen_flowscape links no oneDNN" bash -c "! grep -q dnnl '$off/apps/CMakeFiles/gen_flowscape.dir/link.txt'"
check "no Python extension target" bash -c "! grep -rq flowscape_native '$off/Makefile'"
check "the denoiser's absence compiles" make -s -C "$off/renderer" src/post/unet_absent.cpp.o

wheel="$work/wheel"
check "pip builds a wheel with the extension" env FLOWSCAPE_REQUIRE_EXTENSION=1 /usr/bin/python3 -m pip wheel \
  --no-deps --no-build-isolation --no-cache-dir -q -w "$wheel" "$source_dir/python"
check "the wheel holds flowscape_native" bash -c "/usr/bin/python3 -m zipfile -l '$wheel'/flowscape-*.whl | grep -q 'flowscape_native.*\.so'"
/usr/bin/python3 -m zipfile -e "$wheel"/flowscape-*.whl "$work/site"
check "the installed plugin reads images natively" env PYTHONPATH="$work/site" /usr/bin/python3 -c "
import numpy as np, flowscape_native
from flowscape import io
assert io.native_available()
assert flowscape_native.__file__.startswith('$work/site'), flowscape_native.__file__
"
finish
