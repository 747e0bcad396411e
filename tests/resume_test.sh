#!/usr/bin/env bash
# Resume leaves no trace (docs/release.md, "Robustness"): each tool that resumes is killed
# (SIGKILL, through the LD_PRELOAD shim kill_preload.cpp) at each write of each file it makes
# outside sequences/ -- when the file's temporary is created, half written, and whole but not yet
# renamed -- then run again with the same command. The rerun's folder must be byte-identical to
# an uninterrupted run's, hold no temporary file, and its manifest must list none.
set -u
bin=$1
preload=$2
source "$(dirname "$0")/shell_checks.sh"
release=(--maps 1 --sequences-per-map 2 --frames 2 --resolution 16 --face-size 8 --spp 1
  --vehicles 4 --pedestrians 2 --weather sunny,rain --seed 5)
moments=(open write rename)

killed_at() {  # killed_at FILE MOMENT COMMAND...: the command must die by SIGKILL there
  local file=$1 moment=$2; shift 2
  { LD_PRELOAD=$preload FLOWSCAPE_KILL_FILE=$file FLOWSCAPE_KILL_AT=$moment "$@" >/dev/null; } 2>/dev/null
  [ $? -eq 137 ]
}
no_temporaries() {
  local found
  found=$(find "$1" -name '.partial-*')
  [ -z "$found" ] || { echo "left behind: $found"; return 1; }
}
manifest_lists_no_temporary() {
  python3 -c 'import json, sys
files = json.load(open(sys.argv[1]))["files"]
bad = [f for f in files if "/.partial-" in "/" + f]
sys.exit(print("listed:", bad) if bad else 0)' "$1/manifest.json"
}
quietly() { "$@" >/dev/null 2>&1; }
same_as() {  # same_as REFERENCE DIR: byte-identical, hidden files included
  diff -r "$1" "$2"
}

# ---- gen_flowscape: config.json, manifest.json, the card's README.md and images ----
check "an uninterrupted release" quietly "$bin/gen_flowscape" "${release[@]}" --out "$work/clean"
for file in config.json manifest.json README.md card/sunny.png card/rain.png; do
  for moment in "${moments[@]}"; do
    out=$work/gen-${file//\//-}-$moment
    what="gen_flowscape killed at $moment of $file"
    check "$what" killed_at "gen-${file//\//-}-$moment/$file" "$moment" \
      "$bin/gen_flowscape" "${release[@]}" --out "$out"
    check "$what: rerun" quietly "$bin/gen_flowscape" "${release[@]}" --out "$out"
    check "$what: rerun = uninterrupted run" same_as "$work/clean" "$out"
    check "$what: no temporary file" no_temporaries "$out"
    check "$what: none in the manifest" manifest_lists_no_temporary "$out"
  done
done
# a stale temporary the rerun did not make (another process's) goes too, and --check names it
touch "$work/clean/card/.partial-99999-sunny.png" "$work/clean/.partial-99999-manifest.json"
check "--check fails" bash -c '! "$@" 2>"'"$work/report"'"' - "$bin/gen_flowscape" "${release[@]}" --out "$work/clean" --check
check "--check names a stale temporary" grep -q "card/.partial-99999-sunny.png: temporary file of an interrupted run" "$work/report"
check "a rerun removes it" quietly "$bin/gen_flowscape" "${release[@]}" --out "$work/clean"
check "--check: clean" quietly "$bin/gen_flowscape" "${release[@]}" --out "$work/clean" --check

# ---- stitch_erp: each kind's file of a frame ----
cube=$work/clean/sequences/map00_seq00/cube
check "an uninterrupted stitch" "$bin/stitch_erp" "$cube" -o "$work/stitched" --height 16
for file in flow/000000.flo valid/000000.png color/000001.png depth/000000.exr; do
  for moment in "${moments[@]}"; do
    out=$work/stitch-${file//\//-}-$moment
    what="stitch_erp killed at $moment of $file"
    check "$what" killed_at "stitch-${file//\//-}-$moment/$file" "$moment" \
      "$bin/stitch_erp" "$cube" -o "$out" --height 16
    check "$what: rerun" quietly "$bin/stitch_erp" "$cube" -o "$out" --height 16
    check "$what: rerun = uninterrupted stitch" same_as "$work/stitched" "$out"
    check "$what: no temporary file" no_temporaries "$out"
  done
done

# ---- flowscape_split and flowscape_preview ----
cp -r "$work/clean" "$work/split-clean"
check "an uninterrupted split" quietly "$bin/flowscape_split" "$work/split-clean"
check "an uninterrupted preview" quietly "$bin/flowscape_preview" "$work/split-clean" --no-video
for file in splits/train.txt panoflow/flowscape.json panoflow/test/sunny/img/map00_seq00/000001.jpg \
  previews/map00_seq01.png; do
  moment=write
  out=$work/split-${file//\//-}
  cp -r "$work/clean" "$out"
  tool=flowscape_split
  [[ $file == previews/* ]] && { tool=flowscape_preview; "$bin/flowscape_split" "$out" >/dev/null 2>&1; }
  what="$tool killed at $moment of $file"
  args=("$out")
  [ $tool = flowscape_preview ] && args+=(--no-video)
  check "$what" killed_at "split-${file//\//-}/$file" "$moment" "$bin/$tool" "${args[@]}"
  check "$what: rerun" quietly "$bin/$tool" "${args[@]}"
  [ $tool = flowscape_preview ] || "$bin/flowscape_preview" "${args[@]}" --no-video >/dev/null 2>&1
  check "$what: rerun = uninterrupted run" same_as "$work/split-clean" "$out"
  check "$what: no temporary file" no_temporaries "$out"
done
finish
