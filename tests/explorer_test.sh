#!/usr/bin/env bash
# The release explorer in headless Chromium (Debian's chromium): the page of a small FlowScape
# release (every kind, two flow gaps, cube faces shown) and of a dual-fisheye rig release opens
# from the folder with no server; its self-test (#selftest) loads every preview of every sequence,
# view, frame and kind and scrubs every sequence frame by frame; no console error; the images it
# loaded are every file of previews/; a screenshot of a scrubbed sequence is saved.
# Usage: explorer_test.sh BIN_DIR SCREENSHOT
set -u
bin=$1 screenshot=$2
source "$(dirname "$0")/shell_checks.sh"
browser=$(command -v chromium || command -v chromium-browser) || {
  echo "FAILED: no chromium (scripts/install_deps.sh installs Debian's)"; exit 1; }
chrome() { "$browser" --headless --no-sandbox --disable-gpu --allow-file-access-from-files \
  --hide-scrollbars --enable-logging=stderr --v=0 "$@"; }
small=(--maps 1 --sequences-per-map 2 --frames 5 --resolution 32 --spp 1
       --vehicles 12 --pedestrians 6 --weather sunny,rain)

check "gen_flowscape writes the explorer with the release" \
  "$bin/gen_flowscape" "${small[@]}" --face-size 16 --outputs all --flow-gaps 1,2 --out "$work/a"
check "the default page is there" test -s "$work/a/explorer/index.html" -a -s "$work/a/explorer/data.js"
check "gt_quality --sample scores 1 pair per weather" \
  "$bin/gt_quality" "$work/a" --sample 1 --json "$work/a/quality.json" -q
check "flowscape_explore rewrites it with the faces and the scores" \
  "$bin/flowscape_explore" "$work/a" --faces --frames 3
check "a rig release" "$bin/gen_flowscape" "${small[@]}" --rig dual-fisheye --out "$work/b"

selftest() {  # selftest RELEASE: the page's own check, then what Chromium logged
  local page=$1/explorer/index.html
  chrome --virtual-time-budget=60000 --dump-dom "file://$page#selftest" >"$work/dom" 2>"$work/log"
  python3 - "$work/dom" "$work/log" "$1/explorer" <<'PY'
import html, json, os, re, sys
dom, log, explorer = open(sys.argv[1]).read(), open(sys.argv[2]).read(), sys.argv[3]
found = re.search(r'<pre id="selftest-result">([^<]*)</pre>', dom)
assert found, "no self-test result in the page"
result = json.loads(html.unescape(found.group(1)))
assert result["ok"], result["problems"][:5]
previews = sum(len(files) for _, _, files in os.walk(os.path.join(explorer, "previews")))
assert result["images"] == previews > 0, (result["images"], previews)
data = open(os.path.join(explorer, "data.js")).read()
release = json.loads(data[data.index("=") + 1:data.rindex(";")])
assert result["sequences"] == len(release["sequences"]) > 0
assert result["scrubbed"] == sum(len(s["sampled_frames"]) for s in release["sequences"])
console = [line for line in log.splitlines() if "CONSOLE" in line or "Uncaught" in line]
assert not console, console[:3]
print("self-test:", result["images"], "images,", result["scrubbed"], "frames scrubbed")
PY
}
check "every sequence, frame and kind of the release loads; scrubbing works" selftest "$work/a"
check "the same for the rig release" selftest "$work/b"
check "the quality scores and statistics are in the page's data" \
  grep -q '"quality":{"layout":"flowscape"' "$work/a/explorer/data.js"
shoot() { chrome --virtual-time-budget=5000 --window-size=1280,760 --screenshot="$screenshot" \
  "file://$work/a/explorer/index.html#sequence=map00_seq00&position=1" 2>"$work/log"; }
check "a screenshot of a scrubbed sequence" shoot
check "the screenshot is a PNG" python3 -c "import sys; assert open(sys.argv[1],'rb').read(8) == b'\x89PNG\r\n\x1a\n'" "$screenshot"

check "an old release (no statistics in meta.json) gets its page from the files" bash -c "
  cp -r '$work/b' '$work/c' && rm -rf '$work/c/explorer' &&
  python3 -c \"import json,glob
for p in glob.glob('$work/c/sequences/*/meta.json'):
    m = json.load(open(p)); del m['statistics']; json.dump(m, open(p, 'w'))\" &&
  '$bin/flowscape_explore' '$work/c' >/dev/null 2>&1 &&
  cmp '$work/b/explorer/data.js' '$work/c/explorer/data.js'"
wrong_size() {  # a mask of another size in a release: named, no page
  cp -r "$work/c" "$work/d" && rm -rf "$work/d/explorer"
  local mask=$(ls "$work"/d/sequences/map00_seq00/cameras/*/valid/000000.png | head -1)
  oiiotool --create 4x4 1 -d uint8 -o "$mask" && fails_clearly "$mask" "$bin/flowscape_explore" "$work/d" &&
    [ ! -e "$work/d/explorer/index.html" ]
}
check "a mask of another size is named and no page is written" wrong_size
bad_record() {  # a statistics record cut short in one meta.json: named, no page
  cp -r "$work/b" "$work/e" && rm -rf "$work/e/explorer"
  local meta=$work/e/sequences/map00_seq01/meta.json
  python3 -c "import json,sys; m=json.load(open(sys.argv[1])); m['statistics']['flow_histogram']=[1]
json.dump(m, open(sys.argv[1], 'w'))" "$meta" &&
    fails_clearly "$meta: statistics" "$bin/flowscape_explore" "$work/e" && [ ! -e "$work/e/explorer/index.html" ]
}
check "a bad statistics record is named and no page is written" bad_record
check "a missing release is named" fails_clearly "not a FlowScape release" "$bin/flowscape_explore" "$work/none"
finish
