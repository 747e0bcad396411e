#!/usr/bin/env bash
# End-to-end checks of stitch_erp, flowviz and city_preview as a user runs them: the demo, resume, and bad input
# (non-zero exit, one clear line naming the file, no damaged output).
set -u
bin=$1
version=$2  # the project version (CMakeLists.txt)
source "$(dirname "$0")/shell_checks.sh"

check "stitch_erp --help" "$bin/stitch_erp" --help
check "flowviz --help" "$bin/flowviz" --help
check "demo runs" "$bin/stitch_erp" --demo "$work/demo" --face-size 64 --height 64
demo_out=$("$bin/stitch_erp" --demo "$work/demo" --face-size 64 --height 64 2>/dev/null)
worst=$(sed -n 's/.*largest error \([0-9.e+-]*\) px/\1/p' <<<"$demo_out")
check "demo yaw flow is exact (largest error $worst px)" awk -v e="$worst" 'BEGIN { exit !(e != "" && e < 0.01) }'
for m in color/000000.png color/000001.png flow/000000.flo semantic/000000.png instance/000000.png depth/000000.exr valid/000000.png; do
  check "demo wrote erp/$m" test -s "$work/demo/erp/$m"
done
check "stitch a cubemap folder" "$bin/stitch_erp" "$work/demo/cube" -o "$work/erp" --height 64
check "rerun resumes (nothing left to do)" bash -c "'$bin/stitch_erp' '$work/demo/cube' -o '$work/erp' --height 64 2>&1 | grep -q 'nothing to do'"
rm "$work/erp/valid/000000.png"  # as if killed between the flow and its mask
check "rerun redoes a half-finished frame" "$bin/stitch_erp" "$work/demo/cube" -o "$work/erp" --height 64
check "the mask is back" test -s "$work/erp/valid/000000.png"
check "classic flow mode" "$bin/stitch_erp" "$work/demo/cube" -o "$work/erp_classic" --height 64 --flow-mode classic
check "flowviz writes a PNG" "$bin/flowviz" "$work/erp/flow/000000.flo" -o "$work/viz.png" --wheel middlebury
check "flowviz PNG exists" test -s "$work/viz.png"

check "flowviz: missing file" fails_clearly "missing.flo: file not found" "$bin/flowviz" "$work/missing.flo" -o "$work/missing.png"
check "flowviz: no output for a missing file" test ! -e "$work/missing.png"
head -c 100 "$work/erp/flow/000000.flo" >"$work/cut.flo"
check "flowviz: truncated .flo" fails_clearly "cut.flo: truncated .flo data" "$bin/flowviz" "$work/cut.flo" -o "$work/cut.png"
check "flowviz: no output for a truncated file" test ! -e "$work/cut.png"
check "flowviz: bad option value" bash -c "! '$bin/flowviz' '$work/erp/flow/000000.flo' --scale -3 2>/dev/null"
check "stitch_erp: missing folder" fails_clearly "cubemap folder not found" "$bin/stitch_erp" "$work/nope" -o "$work/x"
head -c 200 "$work/demo/cube/left/color/000001.png" >"$work/short.png"
mv "$work/short.png" "$work/demo/cube/left/color/000001.png"
check "stitch_erp: corrupt face names the file" fails_clearly "left/color/000001.png" "$bin/stitch_erp" "$work/demo/cube" -o "$work/erp3" --height 64
check "stitch_erp: no output for the corrupt frame" test ! -e "$work/erp3/color/000001.png"
check "stitch_erp: no partial files" bash -c "! find '$work/erp3' -name '.partial-*' | grep -q ."

check "city_preview renders a contact sheet and exports glTF" "$bin/city_preview" --maps 0 3 --height 24 --spp 1 --vehicles 10 --pedestrians 5 -o "$work/sheet.png" --gltf "$work/maps"
check "city_preview sheet exists" test -s "$work/sheet.png"
check "city_preview glTF and scene record" test -s "$work/maps/rural.gltf" -a -s "$work/maps/rural.json"
check "the scene record is JSON naming its map" python3 -c "import json,sys; assert json.load(open(sys.argv[1]))['map_name'] == 'rural'" "$work/maps/rural.json"
check "city_preview: map out of range" bash -c "! '$bin/city_preview' --maps 9 -o '$work/bad.png' 2>/dev/null"
check "city_preview: too many actors" fails_clearly "at most 200 vehicles and pedestrians" "$bin/city_preview" --maps 0 --vehicles 150 --pedestrians 100 -o "$work/bad.png"
check "city_preview: no sheet after an error" test ! -e "$work/bad.png"
check "city_preview renders weathers" "$bin/city_preview" --maps 1 --weathers sunny rain --height 24 --spp 1 --vehicles 5 --pedestrians 5 -o "$work/weathers.png"
check "city_preview: unknown weather" fails_clearly 'unknown weather preset "snow"' "$bin/city_preview" --weathers snow -o "$work/bad.png"

# a new user's slips (issue 35): misspelt options suggested, one exit status for usage errors,
# --version everywhere, chosen maps, options a rig cannot use refused, a file as --out
for app in flowviz stitch_erp flowscape_split flowscape_preview gt_quality gen_flowscape flowscape_merge flowscape_explore city_preview; do
  case $app in  # the apps that trace rays also name Embree and the kernel family they run
    gen_flowscape | city_preview) says="flowscape $version, Embree [0-9.]*, [a-z0-9.]* kernels" ;;
    *) says="flowscape $version" ;;
  esac
  check "$app --version says the toolkit's version" bash -c "'$bin/$app' --version | grep -qx '$says'"
  check "$app: an unknown option exits with status 2" bash -c "'$bin/$app' --no-such-option 2>/dev/null; [ \$? -eq 2 ]"
done
check "the Python package has the same version" grep -q "^version = \"$version\"" "$(dirname "$0")/../python/pyproject.toml"
check "gen_flowscape: a misspelt option gets the nearest one" fails_clearly 'did you mean "--frames"?' "$bin/gen_flowscape" --frame 4
check "gen_flowscape: --threads -1 names its range briefly" fails_clearly 'not in range 0 to 1024' "$bin/gen_flowscape" --threads -1
check "gen_flowscape: --maps 3,7 renders those two maps" bash -c "'$bin/gen_flowscape' --maps 3,7 --frames 2 --check --out '$work/m' | grep -q '^16 sequences'"
check "gen_flowscape: --maps 5, renders map 5 alone" bash -c "'$bin/gen_flowscape' --maps 5, --frames 2 --check --out '$work/m' | grep -q '^8 sequences'"
check "gen_flowscape: a map out of range" fails_clearly "map_list must hold different map numbers in 0..7" "$bin/gen_flowscape" --maps 8, --frames 2 --check --out "$work/m"
check "gen_flowscape: an unknown flow format names the three" fails_clearly 'flow format must be flo, kitti-png or half-exr, not "kitti"' "$bin/gen_flowscape" --flow-format kitti --check --out "$work/m"
check "gen_flowscape: --no-cube with a lens rig" fails_clearly '--no-cube: only the flowscape rig has cube faces' "$bin/gen_flowscape" --rig fisheye --no-cube --check --out "$work/m"
cat >"$work/rig.json" <<'JSON'
{"name": "one", "cameras": [{"name": "front", "model": "pinhole",
  "parameters": {"width": 32, "height": 24, "K": [[16, 0, 15.5], [0, 16, 11.5], [0, 0, 1]]},
  "mount": {"position": [0, 0, 0], "yaw_pitch_roll_degrees": [0, 0, 0]}}]}
JSON
check "gen_flowscape: --resolution with a rig file" fails_clearly "sets its cameras' image sizes (--scale scales them)" "$bin/gen_flowscape" --rig "$work/rig.json" --resolution 64 --check --out "$work/m"
# a calibration as the rig (--rig-from): its mount asked for, then rendered small with --scale
camchain="$(dirname "$0")/../docs/rigs/kalibr_stereo.yaml"  # Kalibr's camchain, as docs/cameras.md shows
check "gen_flowscape --rig-from: a calibration's mount is asked for" fails_clearly "kalibr_stereo.yaml: a calibration has no place on the vehicle: give the first camera's mount with --rig-mount" "$bin/gen_flowscape" --rig-from "$camchain" --check --out "$work/m"
check "gen_flowscape --rig-mount: six numbers" fails_clearly "--rig-mount wants x,y,z,yaw,pitch,roll" "$bin/gen_flowscape" --rig-from "$camchain" --rig-mount 1,2,3 --check --out "$work/m"
check "gen_flowscape --scale: not for presets" fails_clearly "scale is for a rig file or calibration: the fisheye rig is sized by resolution" "$bin/gen_flowscape" --rig fisheye --scale 0.5 --check --out "$work/m"
check "gen_flowscape --rig-from renders a calibration, scaled" "$bin/gen_flowscape" --rig-from "$camchain" --rig-mount 0.5,0,0.3,0,-5,0 --scale 0.0625 --maps 0, --sequences-per-map 1 --frames 2 --spp 1 --outputs none --out "$work/calib"
meta=$(ls "$work"/calib/sequences/*/meta.json | head -1)
check "its meta.json holds cam1 at 47 x 30 with K scaled (fx 457.587 x 47/752)" /usr/bin/python3 -c "
import json, sys
v = json.load(open('$meta'))['views']['cameras/cam1']
K = v['parameters']['K']
assert (v['width'], v['height']) == (47, 30), (v['width'], v['height'])
assert abs(K[0][0] - 457.587 * 47 / 752) < 1e-9 and abs(K[0][2] - ((379.999 + 0.5) * 47 / 752 - 0.5)) < 1e-9, K
"
# scenarios (issue 36): bad ones get one line naming the file
examples="$(dirname "$0")/../examples/scenarios"
check "gen_flowscape --scenario --check plans one sequence per file" bash -c "'$bin/gen_flowscape' --scenario '$examples/drone_junction.json' '$examples/turn_in_rain_at_dusk.json' --check --out '$work/s' | grep -q '^2 sequences'"
echo '{"flowscape_scenario": 1, "wether": "rain"}' >"$work/typo.json"
check "gen_flowscape --scenario: a misspelt key" fails_clearly 'typo.json: scenario: unknown key "wether" (did you mean "weather"?)' "$bin/gen_flowscape" --scenario "$work/typo.json" --check --out "$work/s"
check "gen_flowscape --scenario: a missing file" fails_clearly "nothing.json" "$bin/gen_flowscape" --scenario "$work/nothing.json" --check --out "$work/s"
printf '{"flowscape_scenario": 1, "motion": {"pose_file": "walk.txt"}}' >"$work/walk.json"
printf '0 0 0 1.6 0 0 0 1\n0.1 1 x 1.6 0 0 0 1\n' >"$work/walk.txt"
check "gen_flowscape --scenario: a bad pose file line" fails_clearly "walk.txt: line 2: a TUM pose is" "$bin/gen_flowscape" --scenario "$work/walk.json" --frames 2 --resolution 16 --face-size 8 --spp 1 --out "$work/walked"
check "and nothing written" test ! -e "$work/walked"
check "gen_flowscape --scenario: --maps refused" fails_clearly "--maps: the scenarios say which sequences the release holds" "$bin/gen_flowscape" --scenario "$examples/drone_junction.json" --maps 2 --check --out "$work/s"
# city_preview --from-release exports a release's sequence as its meta.json recorded the city, and
# the record passes a further Python check on `recorded`
exports_as_recorded() {  # RELEASE SEQUENCE CHECK
  local release="$1" seq="$2"
  check "city_preview --from-release $seq exports its scene" "$bin/city_preview" --from-release "$release/sequences/$seq" --time 0.034 --height 16 --spp 1 --gltf "$release.exported" -o "$release.png"
  check "the exported scene record of $seq is the one meta.json recorded" /usr/bin/python3 -c "
import json
exported = json.load(open('$release.exported/$seq.json'))
recorded = json.load(open('$release/sequences/$seq/meta.json'))['city']
assert exported == recorded, [k for k in recorded if exported.get(k) != recorded[k]]
$3"
}
# mixed ego routes: one drives, one turns
check "a release of a driving and a turning sequence" "$bin/gen_flowscape" --maps 1 --sequences-per-map 2 --turn-share 0.5 --frames 3 --resolution 16 --face-size 8 --spp 1 --vehicles 2 --pedestrians 2 --out "$work/mixed"
exports_as_recorded "$work/mixed" map00_seq00 "assert recorded['ego_route'] == 'drive'"
exports_as_recorded "$work/mixed" map00_seq01 "assert recorded['ego_route'] == 'turn'"
check "and the two drive different routes" bash -c "! cmp -s '$work/mixed.exported/map00_seq00.json' '$work/mixed.exported/map00_seq01.json'"
check "city_preview --scenario renders a scenario file" "$bin/city_preview" --scenario "$examples/turn_in_rain_at_dusk.json" --time 0.5 --height 16 --spp 1 -o "$work/scenario.png"
# a user's world with scripted actors, and the lane change
check "a release of the user-world and lane-change examples" "$bin/gen_flowscape" --scenario "$examples/user_world_square.json" "$examples/lane_change_in_rain_at_dusk.json" --rig flowscape --frames 3 --resolution 16 --face-size 8 --spp 1 --out "$work/own"
exports_as_recorded "$work/own" map08_seq00 "assert recorded['world']['up'] == 'y', recorded.get('world')"
exports_as_recorded "$work/own" map02_seq00 "assert recorded['ego_route'] == 'lane_change', recorded['ego_route']"
printf '{"flowscape_scenario": 1, "world": {"file": "%s", "units": "metres", "up": "y", "classes": [["road*", "Road"]]}, "motion": {"waypoints": [{"position": [0, 9, 1.6]}, {"position": [5, 9, 1.6], "time": 9}]}}' "$(cd "$examples/../worlds" && pwd)/square.gltf" >"$work/unlabelled.json"
check "gen_flowscape --scenario: a world part no pattern labels" fails_clearly 'square.gltf: its part "sidewalk_south" matches no class pattern (road*)' "$bin/gen_flowscape" --scenario "$work/unlabelled.json" --frames 2 --resolution 16 --face-size 8 --spp 1 --out "$work/unlabelled"
touch "$work/a_file"
check "gen_flowscape --check: --out a file" fails_clearly "a_file: is a file, not a folder" "$bin/gen_flowscape" --frames 2 --check --out "$work/a_file"
check "gen_flowscape: --out a file" fails_clearly "a_file: is a file, not a folder" "$bin/gen_flowscape" --maps 1 --sequences-per-map 1 --frames 2 --resolution 32 --face-size 16 --spp 1 --out "$work/a_file"

finish
