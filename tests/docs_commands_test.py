"""Runs every command of the ```sh blocks of README.md and docs/*.md, as a user would from the
repository root, in a scratch folder holding links to build/, python/ and scripts/.

The scaling rule (so CI stays fast; README "A first hour" states it): a release command without --demo
runs as written with --check (options validated, the plan printed), then with its sizes swapped
for a tiny release (1 map, 3 frames, 16 x 32 ERP, 8-pixel faces, 1 sample; a rig file's or
calibration's cameras at --scale 1/16, the rig an option's or its --scenario file's; 6 sequences for dataset/ and 4 for small/, which later
commands preview, split and train on, else 2), so the commands after it have a dataset; city_preview runs
with few actors, 32-pixel images and one sample per pixel, and exports one map's glTF; a training
run takes 20 steps. The files the docs
name by example are made here: dataset folders (CUBE, frames/, flows/, seq/, flow/) from the tiny
release, my_rig.json from docs/cameras.md's example, camchain.yaml (docs/rigs/kalibr_stereo.yaml) and
opencv.yml as OpenCV writes it; a shell prompt (`machine-a$`) is dropped, absolute example folders (/shared,
/scratch/$USER) are made under the scratch folder and `[--option]` means the option is left out.
What cannot run in CI is listed with the reason (NOT_RUN); a VAR=value prefix stays in front of each run. `python3` is Debian's (/usr/bin first
on the PATH). Usage: docs_commands_test.py REPO_ROOT BUILD_DIR"""
import glob
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

root, build = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
SIZE_OPTIONS = {"--maps", "--frames", "--resolution", "--face-size", "--spp", "--sequences-per-map",
                "--indirect-spp", "--scale"}
TINY = ["--maps", "1", "--frames", "3", "--resolution", "16",
        "--face-size", "8", "--spp", "1", "--vehicles", "4", "--pedestrians", "2"]
PREVIEW_OPTIONS = {"--height", "--spp", "--vehicles", "--pedestrians"}
TINY_PREVIEW = ["--height", "32", "--spp", "1", "--vehicles", "8", "--pedestrians", "4"]
# program or command start -> why it does not run here
NOT_RUN = {
    "build.sh": "CI runs it (the README's first command)",
    "run_tests.sh": "CI runs it (the README's second command)",
    "submit.sh": "needs a Slurm cluster; tests/slurm_test.sh runs it on a local Slurm when there is one",
    "scancel": "needs a Slurm cluster and a job",
    "cmake --install": "installs into the system; tests/install_test.sh checks the install parts",
    "pip install": "installs into the system (Debian refuses it outside a venv); tests/install_test.sh "
                   "builds the wheel",
    "gt_quality MPI-Sintel-complete/": "a public dataset CI does not have (its reader is tested on "
                                       "a synthetic copy, tests/quality)",
    "gt_quality data_scene_flow/": "likewise (KITTI)",
    "gt_quality FlyingChairs_release/": "likewise (FlyingChairs)",
}
OPENCV = """%YAML:1.0
---
image_width: 640
image_height: 480
camera_matrix: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 500., 0., 319.5, 0., 500., 239.5, 0., 0., 1. ]
distortion_coefficients: !!opencv-matrix
   rows: 5
   cols: 1
   dt: d
   data: [ -0.1, 0.01, 0., 0., 0. ]
"""


def documented_commands():
    # docs/tools.md first after the README: its release (dataset/) is what later pages read
    first = [os.path.join(root, "README.md"), os.path.join(root, "docs", "tools.md")]
    rest = sorted(p for p in glob.glob(os.path.join(root, "docs", "*.md")) if p not in first)
    for path in first + rest:
        for block in re.findall(r"```sh\n(.*?)```", open(path).read(), re.S):
            for line in block.replace("\\\n", " ").splitlines():
                line = line.split("  #")[0].strip()
                if line and not line.startswith("#"):
                    yield os.path.relpath(path, root), line


def scenario_rig(words):
    """The rig a --scenario file names (a preset, or a file relative to the scenario's folder)."""
    if "--scenario" not in words:
        return "flowscape"
    return json.load(open(os.path.join(root, words[words.index("--scenario") + 1]))).get("rig", "flowscape")


def tiny(words, options=SIZE_OPTIONS, sizes=TINY):
    rig = next((words[k + 1] for k, w in enumerate(words) if w in ("--rig", "--rig-from")),
               scenario_rig(words))
    if rig != "flowscape":  # no faces; a rig file or calibration sets its own image sizes
        user_file = rig.endswith((".json", ".yaml", ".yml", ".xml"))
        dropped = {"--face-size"} | ({"--resolution"} if user_file else set())
        sizes = [w for k, w in enumerate(sizes)
                 if w not in dropped and (k == 0 or sizes[k - 1] not in dropped)]
        sizes += ["--scale", "0.0625"] if user_file else []
    out, skip = [], False
    for word in words:
        if skip:
            skip = False
        elif word in options:
            skip = True
        else:
            out.append(word)
    return out + sizes


def as_written(line, scratch):
    """The command's words: a prompt dropped, [--optional] words left out, example folders made."""
    line = re.sub(r"^[\w-]+\$\s+", "", line)
    line = re.sub(r"\s\[[^\]]*\]", "", line)
    line = line.replace("/scratch/$USER/", scratch + "/scratch/").replace("/shared/", scratch + "/shared/")
    return line


def make_example_inputs(scratch):
    if not os.path.exists(os.path.join(scratch, "my_rig.json")):
        text = open(os.path.join(root, "docs", "cameras.md")).read()
        rig = re.search(r"A rig file \(`--rig FILE.json`.*?```json\n(.*?)```", text, re.S).group(1)
        open(os.path.join(scratch, "my_rig.json"), "w").write(rig)
        shutil.copy(os.path.join(root, "docs", "rigs", "kalibr_stereo.yaml"),
                    os.path.join(scratch, "camchain.yaml"))
        open(os.path.join(scratch, "opencv.yml"), "w").write(OPENCV)
    sequence = os.path.join(scratch, "dataset", "sequences", "map00_seq00")
    if os.path.isdir(sequence) and not os.path.exists(os.path.join(scratch, "CUBE")):
        os.symlink(os.path.join(sequence, "cube"), os.path.join(scratch, "CUBE"))
        os.symlink(os.path.join(scratch, "dataset", "sequences"), os.path.join(scratch, "sequences"))
        for kind, folders in (("color", ("frames", "seq")), ("flow", ("flows", "flow"))):
            for folder in folders:
                shutil.copytree(os.path.join(sequence, "erp", kind), os.path.join(scratch, folder))


def run(words, scratch):
    environment = dict(os.environ, PATH="/usr/bin:" + os.environ.get("PATH", ""))
    while words and "=" in words[0] and not words[0].startswith("-"):  # VAR=value command
        name, value = words.pop(0).split("=", 1)
        environment[name] = value
    done = subprocess.run(words, cwd=scratch, env=environment, capture_output=True, text=True)
    return done.returncode, (done.stderr or done.stdout).strip().splitlines()[-1:]


def split_environment(part):
    """VAR=value words before the program, and the command's words."""
    words = shlex.split(part)
    at = next(k for k, word in enumerate(words) if "=" not in word or word.startswith("-"))
    return words[:at], words[at:]


def not_run(part):
    words = split_environment(part)[1]
    program = " ".join([os.path.basename(words[0])] + words[1:2])
    for start, reason in NOT_RUN.items():
        if program.startswith(start) or os.path.basename(words[0]) == start:
            return reason
    return None


def runs_of(line, scratch):
    runs = []
    for part in as_written(line, scratch).split("&&"):
        reason = not_run(part)
        if reason:
            print(f"not run ({reason}): {part.strip()}")
            continue
        environment, words = split_environment(part)  # kept in front of every run
        runs += [environment + scaled for scaled in scaled_runs(words)]
    return runs


def scaled_runs(words):
    """A command's runs by the scaling rule (module docstring)."""
    program = os.path.basename(words[0])
    if program == "gen_flowscape" and "--demo" not in words:
        out = words[words.index("--out") + 1].rstrip("/") if "--out" in words else "dataset"
        # the README previews map00_seq05; small/ is split and trained on
        sequences = {"dataset": "6", "small": "4"}.get(out, "2")
        if "--scenario" in words:  # the scenarios are the sequences
            sized = tiny(words)
            at = sized.index("--maps")
            return [words + ["--check"], sized[:at] + sized[at + 2:]]
        return [words + ["--check"], tiny(words) + ["--sequences-per-map", sequences]]
    if program == "city_preview":
        one_map = ["--maps", "0"] if "--gltf" in words and "--maps" not in words else []
        return [tiny(words, PREVIEW_OPTIONS, TINY_PREVIEW) + one_map]
    if "--steps" in words:
        return [tiny(words, {"--steps"}, ["--steps", "20"])]
    return [words]


def main():
    scratch = tempfile.mkdtemp(prefix="flowscape-docs-")
    failures = 0
    try:
        os.symlink(build, os.path.join(scratch, "build"))
        for folder in ("python", "scripts", "docs", "examples"):
            os.symlink(os.path.join(root, folder), os.path.join(scratch, folder))
        for source, line in documented_commands():
            for words in runs_of(line, scratch):
                make_example_inputs(scratch)
                started = time.monotonic()
                code, tail = run(list(words), scratch)
                print(f"{'ok' if code == 0 else 'FAILED'} ({source}, {time.monotonic() - started:.1f} s): "
                      f"{shlex.join(words)}"
                      + ("" if code == 0 else f"  ({' '.join(tail)})"))
                failures += code != 0
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    print(f"{failures} failed")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
