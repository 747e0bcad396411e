#!/usr/bin/env bash
# Nothing lost, nothing mixed, nothing unbounded (docs/release.md, "Robustness"): a release on a
# disk that fills up (an LD_PRELOAD shim makes write(2) fail with ENOSPC after a byte budget) stops
# with the failing file named and leaves no file under its final name that does not decode; the
# rerun gives the bytes of a clean run; damaged files are redone on resume; a changed config is
# refused; hostile files and numbers give one line naming the file, within a memory limit.
set -u
bin=$1
preload=$2
source "$(dirname "$0")/shell_checks.sh"
base=(--maps 1 --sequences-per-map 2 --frames 3 --resolution 16 --face-size 8 --vehicles 4 --pedestrians 2)
small=("${base[@]}" --spp 1 --seed 3)
on_full_disk() {  # on_full_disk BYTES COMMAND...: the command on a disk with BYTES of room
  local bytes=$1; shift
  LD_PRELOAD=$preload FLOWSCAPE_DISK_BYTES=$bytes "$@"
}
with_memory_limit() {  # the command may use at most 1.5 GB of address space
  (ulimit -v 1500000 && "$@")
}
# Decodes every image fully (oiiotool, independent of our readers) and checks every .flo's length
# against its header; no temporary file may be left.
all_files_whole() {
  local dir=$1 file
  while IFS= read -r -d '' file; do
    case $file in
      */.partial-*) echo "temporary left: $file"; return 1 ;;
      *.png | *.exr) oiiotool "$file" --printstats >/dev/null 2>&1 || { echo "broken: $file"; return 1; } ;;
      *.flo) python3 -c 'import struct, sys, os
b = open(sys.argv[1], "rb").read(12); w, h = struct.unpack("<ii", b[4:12])
sys.exit(os.path.getsize(sys.argv[1]) != 12 + 8 * w * h)' "$file" || { echo "broken: $file"; return 1; } ;;
      *.json) python3 -c 'import json, sys; json.load(open(sys.argv[1]))' "$file" || return 1 ;;
    esac
  done < <(find "$dir" -type f -print0)
}

# ---- a disk that fills up, then resume ----
check "a clean release" "$bin/gen_flowscape" "${small[@]}" --out "$work/clean"
check "full disk: one line naming the file and ENOSPC" \
  fails_clearly "No space left on device" on_full_disk 30000 "$bin/gen_flowscape" "${small[@]}" --out "$work/full"
check "full disk: the message names a file of the release" grep -q "$work/full/" "$work/err"
check "full disk: every file under its final name decodes" all_files_whole "$work/full"
check "full disk: no manifest" test ! -e "$work/full/manifest.json"
check "split refuses the unfinished release" \
  fails_clearly "manifest.json: missing: the release is unfinished" "$bin/flowscape_split" "$work/full"
check "rerun with room" "$bin/gen_flowscape" "${small[@]}" --out "$work/full"
check "rerun = clean run, byte for byte" diff -r "$work/clean" "$work/full"

seq=$work/full/sequences/map00_seq01
truncate -s 100 "$seq/erp/color/000001.png"
: >"$seq/erp/flow/000000.flo"
truncate -s 200 "$seq/cube/front/depth/000002.exr"
head -c 20 "$work/clean/sequences/map00_seq01/meta.json" >"$seq/meta.json"
check "damaged files: resume redoes them" "$bin/gen_flowscape" "${small[@]}" --out "$work/full"
check "damaged files: = clean run" diff -r "$work/clean" "$work/full"

# ---- another config into the same folder ----
check "changed config refused, keys named" \
  fails_clearly "config.json: this release was made with another config (seed: 3 recorded, 4 now; spp: 1 recorded, 2 now)" \
  "$bin/gen_flowscape" "${base[@]}" --spp 2 --seed 4 --out "$work/full"
check "refused: nothing changed" diff -r "$work/clean" "$work/full"
echo "mine" >"$work/full/notes.txt"
check "--force starts over" "$bin/gen_flowscape" "${base[@]}" --spp 2 --seed 3 --out "$work/full" --force
check "--force: the new config" grep -q '"spp": 2' "$work/full/manifest.json"
check "--force: other files kept" grep -q mine "$work/full/notes.txt"

# ---- other tools on a full disk ----
flo=$work/clean/sequences/map00_seq00/erp/flow/000000.flo
check "flowviz on a full disk" fails_clearly "v.png: cannot write: No space left on device" on_full_disk 100 "$bin/flowviz" "$flo" -o "$work/v.png"
check "flowviz: no output" test ! -e "$work/v.png"
cube=$work/clean/sequences/map00_seq00/cube
check "stitch_erp on a full disk" fails_clearly "No space left on device" on_full_disk 3000 "$bin/stitch_erp" "$cube" -o "$work/st" --height 16
check "stitch_erp: what is there decodes" all_files_whole "$work/st"
check "stitch_erp: rerun with room" "$bin/stitch_erp" "$cube" -o "$work/st" --height 16
check "stitch_erp: resumed = clean" bash -c "'$bin/stitch_erp' '$cube' -o '$work/st2' --height 16 && diff -r '$work/st' '$work/st2'"
check "gt_quality --error-images on a full disk" \
  fails_clearly "No space left on device" on_full_disk 500 "$bin/gt_quality" -q "$work/clean" --error-images "$work/errors"
cp -r "$cube" "$work/oddcube"
for face in front right back left up down; do
  oiiotool "$work/oddcube/$face/instance/000000.png" --resize 4x4 -o "$work/oddcube/$face/instance/000000.png"
done
check "stitch_erp: an instance image of another size names its file" \
  fails_clearly "oddcube/front/instance/000000.png: cube face is 4x4, the cube's other files have 8x8 faces" \
  "$bin/stitch_erp" "$work/oddcube" -o "$work/odd" --height 16
mkdir -p "$work/emptycube"
check "stitch_erp of an empty cubemap folder" \
  fails_clearly "emptycube: no cubemap frames found" "$bin/stitch_erp" "$work/emptycube" -o "$work/x"

# ---- hostile files, within a memory limit ----
python3 - "$work" <<'PY'
import struct, sys
w = sys.argv[1]
open(f"{w}/big.flo", "wb").write(struct.pack("<fii", 202021.25, 16384, 16384))
open(f"{w}/huge.flo", "wb").write(struct.pack("<fii", 202021.25, 65536, 65536))
PY
oiiotool --pattern constant:color=1 4x4 1 -d float -o "$work/small.exr"
python3 - "$work" <<'PY'
import struct, sys
w = sys.argv[1]
data = bytearray(open(f"{w}/small.exr", "rb").read())
at = data.index(b"dataWindow\0box2i\0") + len("dataWindow\0box2i\0") + 4
data[at:at + 16] = struct.pack("<4i", 0, 0, 2491138, 768)
open(f"{w}/window.exr", "wb").write(data)
PY
mkdir -p "$work/folder.flo"
check "a 12-byte .flo claiming 16384^2" fails_clearly "big.flo: truncated .flo data: the header's 16384x16384 needs 2147483648 bytes, the file has 0" with_memory_limit "$bin/flowviz" "$work/big.flo"
check "a 12-byte .flo claiming 65536^2" fails_clearly "huge.flo: truncated .flo data: the header's 65536x65536 needs" with_memory_limit "$bin/flowviz" "$work/huge.flo"
check "an EXR claiming a 2491139 x 769 data window" fails_clearly "window.exr: EXR header: data window 2491139x769 is empty or over the limit" with_memory_limit "$bin/flowviz" "$work/window.exr"
check "a folder where a file was expected" fails_clearly "folder.flo: is a folder, expected a file" "$bin/flowviz" "$work/folder.flo"
cp -r "$work/clean" "$work/hostile"
cp "$work/big.flo" "$work/hostile/sequences/map00_seq01/erp/flow/000001.flo"
check "gt_quality: a hostile .flo in a release (parallel reads)" fails_clearly "000001.flo: truncated .flo data" with_memory_limit "$bin/gt_quality" -q "$work/hostile"

mkdir -p "$work/shards/manifests" "$work/shards/sequences"
python3 -c 'import json, sys; m = json.load(open(sys.argv[1])); print(json.dumps({"config": m["config"], "shard": 0, "shards": 0, "files": {}}))' \
  "$work/clean/manifest.json" >"$work/shards/manifests/shard-0-of-0.json"
check "merge: a shard manifest with \"shards\": 0" fails_clearly 'shard-0-of-0.json: bad shard manifest: "shards" 0 is out of range (1..1048576)' "$bin/flowscape_merge" "$work/shards"

python3 - "$work" "$(dirname "$0")/fuzz/corpus/model/triangle.gltf" <<'PY'
import json, sys
gltf = json.loads(open(sys.argv[2], "rb").read()[1:])
gltf["scene"] = 5
open(f"{sys.argv[1]}/scene5.gltf", "w").write(json.dumps(gltf))
PY
check "a glTF model naming scene 5 of 1" fails_clearly 'scene5.gltf: "scene": 5 names a scene the file lacks (it has 1)' \
  "$bin/gen_flowscape" "${small[@]}" --model "car=$work/scene5.gltf" --out "$work/m"
echo '{"maps": 4294967297}' >"$work/wrap.json"
check "config: maps 2^32 + 1" fails_clearly 'wrap.json: release config: "maps" 4294967297 is out of range' "$bin/gen_flowscape" --config "$work/wrap.json" --check
echo '{"frames": 4.7}' >"$work/frac.json"
check "config: frames 4.7" fails_clearly '"frames" must be an integer (got 4.7)' "$bin/gen_flowscape" --config "$work/frac.json" --check
check "--seed -1" fails_clearly "--seed: must be a whole number >= 0" "$bin/gen_flowscape" --seed -1 --check
check "--shard 1/2x" fails_clearly "--shard wants K/N with whole numbers" "$bin/gen_flowscape" --shard 1/2x --check

# ---- hostile files a user brings: one line naming file and key, nothing written ----
refuses() {  # refuses EXPECTED_TEXT OUT COMMAND...: one line, non-zero exit, no OUT
  local expected=$1 out=$2; shift 2
  fails_clearly "$expected" "$@" && [ ! -e "$out" ]
}
python3 - "$work" <<'PY'
import json, struct, sys
w = sys.argv[1]
open(f"{w}/deep.yaml", "w").write("cam0: " + "[" * 60000 + "]" * 60000 + "\n")
open(f"{w}/deep.xml", "w").write('<?xml version="1.0"?>\n<opencv_storage>' + "<a>" * 30000)
open(f"{w}/many.yaml", "w").write("".join(
    f"cam{n}: {{camera_model: pinhole, intrinsics: [1, 1, 1, 1], resolution: [4, 4]}}\n" for n in range(100)))
json.dump({"name": "r", "cameras": [{"name": "front", "model": "pinhole", "parameters": {"width": "wide"},
           "mount": {"position": [0, 0, 0], "yaw_pitch_roll_degrees": [0, 0, 0]}}]}, open(f"{w}/typed.json", "w"))
for name, change in [("frames", {"frames": 2.9}), ("wrap", {"frames": 2**32 + 2}),
                     ("vehicles", {"traffic": {"vehicles": 2**32 + 1}}),
                     ("seed", {"world": {"map": 0, "seed": -1}}),
                     ("folder", {"motion": {"pose_file": "poses"}}),
                     ("device", {"motion": {"pose_file": "/dev/zero"}})]:
    json.dump(dict({"flowscape_scenario": 1}, **change), open(f"{w}/{name}.json", "w"))
PY
mkdir -p "$work/poses"
python3 - "$work" "$(dirname "$0")/fuzz/corpus/model/triangle.gltf" <<'PY'
import json, sys
w = sys.argv[1]
gltf = json.loads(open(sys.argv[2], "rb").read()[1:])
gltf["nodes"] = [{"children": [n + 1]} for n in range(19999)] + [{"mesh": 0}]
json.dump(gltf, open(f"{w}/chain.gltf", "w"))
json.dump({"flowscape_scenario": 1, "world": {"file": "chain.gltf", "units": "metres", "up": "y",
           "classes": [["*", "Road"]]}, "motion": {"waypoints": [{"position": [0, 0, 1], "time": 0},
           {"position": [1, 0, 1], "time": 1}]}, "frames": 2}, open(f"{w}/chain.json", "w"))
header = (b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
          b"property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n")
open(f"{w}/cut.ply", "wb").write(header + bytes(20))
PY
check "calibration: a YAML flow 60,000 deep" \
  refuses "deep.yaml: nested more than 64 levels deep" "$work/o1" "$bin/gen_flowscape" "${small[@]}" --rig-from "$work/deep.yaml" --rig-mount 0,0,0,0,0,0 --out "$work/o1"
check "calibration: an XML 30,000 deep" \
  refuses "deep.xml: nested more than 64 levels deep" "$work/o2" "$bin/gen_flowscape" "${small[@]}" --rig-from "$work/deep.xml" --rig-mount 0,0,0,0,0,0 --out "$work/o2"
check "calibration: 100 cameras" \
  refuses "many.yaml: holds 100 cameras; a rig takes at most 16" "$work/o3" "$bin/gen_flowscape" "${small[@]}" --rig-from "$work/many.yaml" --rig-mount 0,0,0,0,0,0 --out "$work/o3"
check "rig file: a key of the wrong type names the file and key" \
  refuses "typed.json: rig: camera \"front\": lens parameter \"width\"" "$work/o4" "$bin/gen_flowscape" --maps 1 --sequences-per-map 1 --frames 2 --rig "$work/typed.json" --out "$work/o4"
for case in "frames:\"frames\" must be an integer (got 2.9)" "wrap:\"frames\" 4294967298 is out of range" \
            "vehicles:\"vehicles\" 4294967297 is out of range" "seed:\"seed\" -1 is out of range" \
            "folder:poses: is a folder, expected a pose file" "device:/dev/zero: not a regular file, expected a pose file"; do
  name=${case%%:*}
  check "scenario: $name" refuses "${case#*:}" "$work/s-$name" "$bin/gen_flowscape" --scenario "$work/$name.json" --out "$work/s-$name"
done
check "world: a glTF node chain 20,000 deep" \
  refuses "chain.gltf: nodes nest more than 256 levels deep" "$work/o5" "$bin/gen_flowscape" --scenario "$work/chain.json" --resolution 8 --face-size 4 --spp 1 --out "$work/o5"
check "model: a truncated PLY (assimp aborted on it)" \
  refuses "cut.ply: its header declares elements of at least 37 bytes, the file holds 20" "$work/o6" "$bin/gen_flowscape" "${small[@]}" --model "car=$work/cut.ply" --out "$work/o6"
mkdir -p "$work/skies"
python3 - "$work/skies" <<'PY'
import hashlib, sys
d = sys.argv[1]
data = bytearray(b"v2/\x01" + bytes(4000))  # not a real map: its hash is all that is checked first
open(f"{d}/park.exr", "wb").write(data)
pinned = hashlib.sha256(bytes(data)).hexdigest()
data[2000] ^= 1
open(f"{d}/park.exr", "wb").write(data)
open(f"{d}/SHA256SUMS", "w").write(f"{pinned}  park.exr\n")
PY
check "sky map: one flipped bit since it was fetched" \
  refuses "park.exr: sha256 " "$work/o7" env FLOWSCAPE_SKY_MAPS="$work/skies" "$bin/gen_flowscape" "${small[@]}" --sky park --out "$work/o7"

finish
