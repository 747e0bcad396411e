#!/usr/bin/env bash
# End-to-end: gen_flowscape makes a small release (2 maps x 8 sequences x 4 frames); its layout,
# counts and manifest hashes are checked by independent Python; flowscape_split's proportions and
# tree; a run killed half-way and rerun gives the same bytes as an uninterrupted one (with another
# thread count); bad input fails with one clear line; flowscape_preview writes sheets and videos.
set -u
bin=$1
source "$(dirname "$0")/shell_checks.sh"
small=(--maps 2 --frames 4 --resolution 24 --face-size 12 --spp 2 --vehicles 12 --pedestrians 6 --seed 5)

check "gen_flowscape makes a small release" "$bin/gen_flowscape" "${small[@]}" --threads 1 --out "$work/a"
check "layout, counts and manifest hashes" python3 - "$work/a" <<'PY'
import hashlib, json, os, sys
root = sys.argv[1]
manifest = json.load(open(os.path.join(root, "manifest.json")))
files = manifest["files"]
on_disk = set()
for folder, _, names in os.walk(root):
    for name in names:
        rel = os.path.relpath(os.path.join(folder, name), root)
        if rel != "manifest.json" and not rel.startswith("explorer/"):  # a view, not listed
            on_disk.add(rel)
assert on_disk == set(files), sorted(on_disk ^ set(files))[:5]
for rel, entry in files.items():
    data = open(os.path.join(root, rel), "rb").read()
    assert hashlib.sha256(data).hexdigest() == entry["sha256"], rel
    assert len(data) == entry["bytes"], rel
sequences = sorted(os.listdir(os.path.join(root, "sequences")))
assert sequences == [f"map{m:02d}_seq{s:02d}" for m in range(2) for s in range(8)], sequences
weathers = {}
faces = ["front", "right", "back", "left", "up", "down"]
for seq in sequences:
    meta = json.load(open(os.path.join(root, "sequences", seq, "meta.json")))
    weathers[meta["weather"]["preset"]] = weathers.get(meta["weather"]["preset"], 0) + 1
    assert len(meta["poses"]) == 4 and meta["frames"] == 4
    for prefix in ["erp"] + [f"cube/{f}" for f in faces]:
        base = os.path.join(root, "sequences", seq, prefix)
        for modality, count in [("color", 4), ("semantic", 4), ("instance", 4), ("depth", 4), ("flow", 3), ("valid", 3)]:
            assert len(os.listdir(os.path.join(base, modality))) == count, (seq, prefix, modality)
assert weathers == {"sunny": 10, "cloud": 2, "fog": 2, "rain": 2}, weathers
counts = manifest["counts"]
assert counts["sequences"] == 16 and counts["frames"] == 64 and counts["flow_pairs"] == 48, counts
flo = open(os.path.join(root, "sequences/map00_seq00/erp/flow/000000.flo"), "rb").read()
assert flo[:4] == b"PIEH" and int.from_bytes(flo[4:8], "little") == 48 and int.from_bytes(flo[8:12], "little") == 24
PY
check "dataset card with example images" test -s "$work/a/README.md" -a -s "$work/a/card/sunny.png" -a -s "$work/a/card/rain.png"

check "flowscape_split" "$bin/flowscape_split" "$work/a" --seed 3
check "splits by whole sequences, stratified by weather, PanoFlow tree" python3 - "$work/a" <<'PY'
import json, os, sys
root = sys.argv[1]
def scenes(name):
    lines = open(os.path.join(root, "splits", name)).read().split("\n")
    return [l.split()[0] for l in lines if l]
train, test = scenes("train.txt"), scenes("test.txt")
assert not set(train) & set(test)
assert len(set(train)) + len(set(test)) == 16 and len(train) + len(test) == 48
weather = {s: json.load(open(os.path.join(root, "sequences", s, "meta.json")))["weather"]["preset"] for s in set(train) | set(test)}
per = {}
for s in set(test):
    per[weather[s]] = per.get(weather[s], 0) + 1
assert per == {"sunny": 2, "cloud": 1, "fog": 1, "rain": 1}, per   # round(10 * 0.2), at least 1 of 2
for side, names in (("train", set(train)), ("test", set(test))):
    for s in names:
        base = os.path.join(root, "panoflow", side, weather[s])
        images = os.listdir(os.path.join(base, "img", s))
        flows = os.listdir(os.path.join(base, "flow", s))
        assert len(images) == len(flows) + 1 == 4, (s, images, flows)
        assert all(n.endswith(".jpg") for n in images)
PY
check "the same seed gives the same split" bash -c "cp '$work/a/splits/test.txt' '$work/test1' && '$bin/flowscape_split' '$work/a' --seed 3 --no-panoflow >/dev/null && cmp '$work/test1' '$work/a/splits/test.txt'"

# kill a slower run half-way, then rerun: the same bytes as the uninterrupted run
"$bin/gen_flowscape" "${small[@]}" --threads 2 --out "$work/b" 2>/dev/null >/dev/null &
pid=$!
for _ in $(seq 1 400); do
  done_frames=$(find "$work/b" -path '*erp/color/*.png' 2>/dev/null | wc -l)
  [ "$done_frames" -ge 20 ] && break
  sleep 0.02
done
kill -9 $pid 2>/dev/null; wait $pid 2>/dev/null
check "the killed run stopped half-way (no manifest)" test ! -e "$work/b/manifest.json"
check "rerun finishes" "$bin/gen_flowscape" "${small[@]}" --threads 2 --out "$work/b"
check "no temporary files left" bash -c "! find '$work/b' -name '.partial-*' | grep -q ."
check "identical manifests" cmp "$work/a/manifest.json" "$work/b/manifest.json"
check "identical files" diff -r "$work/a/sequences" "$work/b/sequences"
check "a finished release is not redone" bash -c "'$bin/gen_flowscape' ${small[*]} --out '$work/b' 2>&1 | grep -q '64/64 frames'"

# temporal reconstruction: the ground truth untouched, the colour not; frames redone alone (their
# windows traced again) with another thread count give the same bytes; lens rigs; no --adaptive
temporal=(--maps 1 --sequences-per-map 1 --frames 6 --resolution 24 --face-size 12 --spp 2
  --vehicles 12 --pedestrians 6 --seed 5)
check "--temporal 0" "$bin/gen_flowscape" "${temporal[@]}" --out "$work/t0"
check "--temporal 2" "$bin/gen_flowscape" "${temporal[@]}" --temporal 2 --threads 1 --out "$work/t1"
seq0=sequences/map00_seq00
for kind in erp/flow erp/flow_backward erp/valid erp/depth cube/front/flow cube/front/instance; do
  check "--temporal 2: $kind as without it" diff -r "$work/t0/$seq0/$kind" "$work/t1/$seq0/$kind"
done
check "--temporal 2: other colour" bash -c "! cmp -s '$work/t0/$seq0/erp/color/000002.png' '$work/t1/$seq0/erp/color/000002.png'"
cp -r "$work/t1" "$work/t2"
rm "$work/t2/$seq0/erp/color/000003.png" "$work/t2/$seq0/cube/left/color/000000.png" \
  "$work/t2/manifest.json"
check "--temporal 2: frames redone" "$bin/gen_flowscape" "${temporal[@]}" --temporal 2 --threads 2 --out "$work/t2"
check "--temporal 2: the same bytes" diff -r "$work/t1" "$work/t2"
check "--temporal with a lens rig and the final pass" "$bin/gen_flowscape" --maps 1 \
  --sequences-per-map 1 --frames 3 --resolution 16 --spp 1 --rig fisheye --outputs final \
  --temporal 1 --out "$work/t3"
check "--temporal with --adaptive refused" fails_clearly "temporal and adaptive do not go together" \
  "$bin/gen_flowscape" "${temporal[@]}" --temporal 1 --adaptive 0.25 --out "$work/t4"

check "gen_flowscape --demo (the README's first command)" "$bin/gen_flowscape" --demo --out "$work/demo"
check "the demo release" test -s "$work/demo/manifest.json" -a -d "$work/demo/sequences/map00_seq01/cube/front/flow"
check "--no-cube writes ERP only" "$bin/gen_flowscape" --maps 1 --sequences-per-map 1 --frames 2 --resolution 16 --spp 1 --no-cube --out "$work/c"
check "no cube folder" test ! -e "$work/c/sequences/map00_seq00/cube"
echo '{"maps": 1, "sequences_per_map": 2, "frames": 2, "resolution": 16, "face_size": 8, "spp": 1, "weathers": ["rain"]}' >"$work/config.json"
check "--config file" "$bin/gen_flowscape" --config "$work/config.json" --out "$work/d"
check "the config's weather" grep -q '"preset":"rain"' "$work/d/sequences/map00_seq01/meta.json"
check "shards write their share" "$bin/gen_flowscape" --config "$work/config.json" --shard 1/2 --out "$work/e"
check "shard 1/2 has sequence 1 only" bash -c "[ -d '$work/e/sequences/map00_seq01' ] && [ ! -d '$work/e/sequences/map00_seq00' ] && [ -s '$work/e/manifests/shard-1-of-2.json' ]"
check "merge refuses a missing shard" fails_clearly "no manifest from shard(s) 0 of 2: rerun them" "$bin/flowscape_merge" "$work/e"
check "the other shard" "$bin/gen_flowscape" --config "$work/config.json" --shard 0/2 --out "$work/e"
check "flowscape_merge --verify" "$bin/flowscape_merge" "$work/e" --verify
check "merged shards = one process" diff -r "$work/d" "$work/e"

box=/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf
check "--model: a textured glTF car" "$bin/gen_flowscape" --maps 1 --sequences-per-map 1 --frames 2 --resolution 16 --face-size 8 --spp 1 --vehicles 8 --pedestrians 2 --model "car=$box" --out "$work/m"
check "the release records its models" grep -q "\"car\": \"$box\"" "$work/m/manifest.json"
check "--model without a kind" fails_clearly "--model wants KIND=FILE" "$bin/gen_flowscape" --model "$box" --out "$work/x"
check "--model of a missing file" fails_clearly "nope.glb: no such model file" "$bin/gen_flowscape" --model car=nope.glb --out "$work/x"
check "bad shard" fails_clearly "shard K/N needs 0 <= K < N" "$bin/gen_flowscape" --shard 3/2 --out "$work/x"
check "unknown weather" fails_clearly 'unknown weather preset "snow"' "$bin/gen_flowscape" --weather sunny,snow --out "$work/x"
check "missing config" fails_clearly "nope.json: file not found" "$bin/gen_flowscape" --config "$work/nope.json" --out "$work/x"
echo '{"frams": 3}' >"$work/typo.json"
check "typo in config" fails_clearly 'typo.json: release config: unknown key "frams"' "$bin/gen_flowscape" --config "$work/typo.json" --out "$work/x"
check "no output after bad input" test ! -e "$work/x"
check "split of a folder that is no release" fails_clearly "not a FlowScape release" "$bin/flowscape_split" "$work/x"

check "gt_quality on the release, with JSON and CSV" "$bin/gt_quality" "$work/a" -q --json "$work/q.json" --csv "$work/q.csv" --error-images "$work/errors"
check "gt_quality rows" python3 - "$work/q.json" "$work/q.csv" <<'PY'
import json, sys
report = json.load(open(sys.argv[1]))
assert report["layout"] == "flowscape"
rows = {r["name"]: r for r in report["rows"]}
assert rows["all"]["pairs"] == 48 and "wpe_noc" in rows["all"]
assert {"weather=sunny", "weather=cloud", "weather=fog", "weather=rain"} <= set(rows)
assert sum(1 for n in rows if n.startswith("sequence=")) == 16
assert rows["all"]["quality"] in ("high", "medium/low")
assert open(sys.argv[2]).readline().startswith("name,pairs,pe,wpe,diff_percent")
PY
check "gt_quality error images" test -s "$work/errors/sunny_map00_seq00_000000.png"
check "gt_quality on the PanoFlow tree" bash -c "'$bin/gt_quality' '$work/a/panoflow' -q | grep -q '^panoflow'"
check "gt_quality with globs" bash -c "'$bin/gt_quality' -q --panorama --images '$work/a/sequences/map00_seq00/erp/color/*.png' --flows '$work/a/sequences/map00_seq00/erp/flow/*.flo' | grep -qE '^all +3 '"
check "gt_quality: not a dataset" fails_clearly "not a known flow dataset layout" "$bin/gt_quality" "$work/a/card"
mkdir -p "$work/br/sequences" && cp -r "$work/a/sequences/map00_seq00" "$work/br/sequences/"
head -c 50 "$work/a/sequences/map00_seq00/erp/flow/000001.flo" >"$work/br/sequences/map00_seq00/erp/flow/000001.flo"
check "gt_quality: a corrupt flow file is named" fails_clearly "000001.flo: truncated" "$bin/gt_quality" "$work/br" -q
check "flowscape_preview" "$bin/flowscape_preview" "$work/a" --sequences map00_seq05 --width 48 -o "$work/previews"
check "preview sheet and video" test -s "$work/previews/map00_seq05.png" -a -s "$work/previews/map00_seq05.mp4"
check "the video is H.264 (x264), which browsers play" grep -aq "x264 - core" "$work/previews/map00_seq05.mp4"

finish
