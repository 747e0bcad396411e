#!/usr/bin/env bash
# Fetches the real HDR skies (opt-in: weather.h's sky_map_names()): CC0 Poly Haven panoramas that
# the npm package @pmndrs/assets ships as base64 EXR (DWAB, 512 x 256) in hdri/<name>.exr.js,
# version pinned, the tarball's and every file's sha256 checked, decoded into
#   ${FLOWSCAPE_SKY_MAPS:-${XDG_CACHE_HOME:-$HOME/.cache}/flowscape/pmndrs-assets-1.7.0}/<name>.exr
# (each decoded file's sha256 checked too), with the package's CC0 licence. Nothing is committed;
# rerunning with the files in place and whole does nothing. Without them a release renders the
# physical sky (one warning per map).
set -euo pipefail
source "$(dirname "$0")/npm_fetch.sh"
dir=${FLOWSCAPE_SKY_MAPS:-${XDG_CACHE_HOME:-$HOME/.cache}/flowscape/pmndrs-assets-1.7.0}
declare -A exr_sha256=(
  [sky]=a72412700b91a49080a582420476d2ab9a1e8fd181031f4ae7ec5e2596addc2a
  [park]=00e78fd8fe0ac81f73eb3682b1a4e2e1b909148f1b06d1e52e771d4fec3d02a1
  [sunrise]=d48b92f8fd8d1e8eb111d90284a007f811a4d57abe4fa6faf10165287a3fe9c2
  [dawn]=02529d0a04dbc6e761adb9b4f6bcb07b0ef3931b218b394ee6be68b1fe39ce79
  [venice]=8200c809a7032efaa7d9fa3a5c64939d7f07d26478bc2418af624150af90dac9
)
npm_fetch fetch_sky_maps @pmndrs/assets@1.7.0 \
  152bd218a3390703f184f0c6ce16e73c8f0a87f32d38530d418a09d33d8208dc "$dir/npm" \
  hdri/sky.exr.js=62744ec42116f896c2d5959365c9be75589ca09d81ecdd99052c3307ec44ce62 \
  hdri/park.exr.js=88947c10444e0c5f0e51018e5b69af9a7489baab9e8034b0044686c2d8fd7a8c \
  hdri/sunrise.exr.js=36c7e652f58293b59a235add4b9399d450a24ea79b78709bcd1198246b08a68f \
  hdri/dawn.exr.js=455ea02a016b2d177faa501e812ea993b43f223480fe3fe6abded88c5f242cf2 \
  hdri/venice.exr.js=08d9d3255f50ffba3a2aa37a95abbcd0944282b90101877b5d0abf340ee0642a \
  LICENSE=a2010f343487d3f7618affe54f789f5487602331c0a8d03f49e9a7c547cf0499
names=(sky park sunrise dawn venice)
for name in "${names[@]}"; do
  exr=$dir/$name.exr
  [ -f "$exr" ] && [ "$(sha256sum "$exr" | cut -d' ' -f1)" = "${exr_sha256[$name]}" ] && continue
  partial=$dir/.partial-$$-$name.exr
  sed -e "s|^export default 'data:application/exr;base64,||" -e "s|'[; ]*$||" \
    "$dir/npm/$name.exr.js" | base64 -d >"$partial"
  [ "$(sha256sum "$partial" | cut -d' ' -f1)" = "${exr_sha256[$name]}" ] ||
    { rm -f "$partial"; echo "fetch_sky_maps: $name.exr: sha256 differs from the pinned one" >&2; exit 1; }
  mv "$partial" "$exr"
done
pins=()
for name in "${names[@]}"; do pins+=("$name.exr=${exr_sha256[$name]}"); done
write_pins "$dir" "${pins[@]}"
echo "fetch_sky_maps: sky maps ${names[*]} and their CC0 licence in $dir"
