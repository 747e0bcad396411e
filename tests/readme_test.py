"""Runs every command of the README's ```sh blocks, as a user would from the repository root, in a
scratch folder holding links to build/, python/ and scripts/. Adaptations, so CI stays fast: the
two commands of the first block are what CI itself runs (so only its `gen_flowscape --demo` part
runs here); a release command without --demo runs as written with --check (options validated, the
plan printed), then with its sizes swapped for a tiny release (1 map, 6 sequences, 3 frames, 16 x 32)
so the commands after it have a dataset; city_preview runs with few actors, small images and one
sample per pixel; Slurm is tested by slurm_test.sh; the folders the README
names by example (CUBE, frames/, flows/) are made from that dataset; `python3` is Debian's (/usr/bin first on the
PATH, as on a fresh machine). Usage: readme_test.py REPO_ROOT BUILD_DIR"""
import glob
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile

root, build = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
SIZE_OPTIONS = {"--maps", "--frames", "--resolution", "--face-size", "--spp", "--sequences-per-map",
                "--indirect-spp"}
TINY = ["--maps", "1", "--sequences-per-map", "6", "--frames", "3", "--resolution", "16",
        "--face-size", "8", "--spp", "1", "--vehicles", "4", "--pedestrians", "2"]
PREVIEW_OPTIONS = {"--height", "--spp", "--vehicles", "--pedestrians"}
TINY_PREVIEW = ["--height", "32", "--spp", "1", "--vehicles", "8", "--pedestrians", "4"]


def readme_commands():
    text = open(os.path.join(root, "README.md")).read()
    for block in re.findall(r"```sh\n(.*?)```", text, re.S):
        for line in block.splitlines():
            line = line.split("  #")[0].strip()
            if line and not line.startswith("#"):
                yield line


def tiny(words, options=SIZE_OPTIONS, sizes=TINY):
    rig = words[words.index("--rig") + 1] if "--rig" in words else "flowscape"
    if rig != "flowscape":  # no faces; a rig file sets its own image sizes
        dropped = {"--face-size"} | ({"--resolution"} if rig.endswith(".json") else set())
        sizes = [w for k, w in enumerate(sizes)
                 if w not in dropped and (k == 0 or sizes[k - 1] not in dropped)]
    out, skip = [], False
    for word in words:
        if skip:
            skip = False
        elif word in options:
            skip = True
        else:
            out.append(word)
    return out + sizes


def make_example_inputs(scratch):
    sequence = os.path.join(scratch, "dataset", "sequences", "map00_seq00")
    if os.path.isdir(sequence) and not os.path.exists(os.path.join(scratch, "CUBE")):
        os.symlink(os.path.join(sequence, "cube"), os.path.join(scratch, "CUBE"))
        os.symlink(os.path.join(scratch, "dataset", "sequences"), os.path.join(scratch, "sequences"))
        for kind, folder in (("color", "frames"), ("flow", "flows")):
            shutil.copytree(os.path.join(sequence, "erp", kind), os.path.join(scratch, folder))


def run(words, scratch):
    environment = dict(os.environ, PATH="/usr/bin:" + os.environ.get("PATH", ""))
    while words and "=" in words[0] and not words[0].startswith("-"):  # VAR=value command
        name, value = words.pop(0).split("=", 1)
        environment[name] = value
    done = subprocess.run(words, cwd=scratch, env=environment, capture_output=True, text=True)
    return done.returncode, (done.stderr or done.stdout).strip().splitlines()[-1:]


def main():
    scratch = tempfile.mkdtemp(prefix="flowscape-readme-")
    failures = 0
    try:
        os.symlink(build, os.path.join(scratch, "build"))
        for folder in ("python", "scripts"):
            os.symlink(os.path.join(root, folder), os.path.join(scratch, folder))
        for line in readme_commands():
            runs = []
            for part in line.split("&&"):
                words = shlex.split(part)
                program = os.path.basename(words[0])
                if program in ("build.sh", "run_tests.sh", "submit.sh"):
                    print(f"skipped (run by CI or slurm_test.sh): {part.strip()}")
                    continue
                if program == "gen_flowscape" and "--demo" not in words:
                    runs += [words + ["--check"], tiny(words)]
                elif program == "city_preview":
                    runs.append(tiny(words, PREVIEW_OPTIONS, TINY_PREVIEW))
                else:
                    runs.append(words)
            for words in runs:
                make_example_inputs(scratch)
                code, tail = run(list(words), scratch)
                print(f"{'ok' if code == 0 else 'FAILED'}: {shlex.join(words)}"
                      + ("" if code == 0 else f"  ({' '.join(tail)})"))
                failures += code != 0
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    print(f"{failures} failed")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
