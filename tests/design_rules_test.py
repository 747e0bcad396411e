"""The homes of docs/architecture.md stay the only homes: a camera's kind is asked only of the camera
(projection.h/.cpp), a denoiser's name compared only in its factory (denoiser.cpp), a material's
kind never in the bounce loop (path_tracer.cpp), no code outside the rig tests a rig for having no
cameras (the flowscape rig is seven cameras), and no production code names the benchmarks'
baseline switches outside renderer.h / renderer.cpp (TracingBaseline). Comments are not code.

    design_rules_test.py REPO_ROOT
"""
import re
import sys
from pathlib import Path

root = Path(sys.argv[1])
PRODUCTION = ["core", "stitcher", "scenes", "weather", "renderer", "dataset_tools", "apps"]

# (what, pattern, the files allowed to hold it)
RULES = [
    ("a camera's kind", r"Projection::Kind|Kind::(Equirectangular|Pinhole|Lens)\b",
     {"renderer/src/camera/projection.cpp", "renderer/include/flowscape/renderer/projection.h"}),
    ("a denoiser's name compared", r'(==|!=)\s*"(atrous|oidn)"|"(atrous|oidn)"\s*(==|!=)',
     {"renderer/src/post/denoiser.cpp"}),
    ("a material's kind in the bounce loop", r"Material::Kind|\.kind\s*==", set()),
    ("a rig tested for no cameras", r"rig\w*\.cameras\.empty\(\)", {"renderer/src/camera/rig.cpp"}),
    ("the benchmarks' baseline switches", r"\bsingle_rays\b|\bfull_sky_when_scattered\b",
     {"renderer/src/render/renderer.cpp", "renderer/include/flowscape/renderer/renderer.h"}),
]
BOUNCE_LOOP = {"renderer/src/render/path_tracer.cpp"}


def code_of(line):
    """The line without its // comment (string literals holding // are not in these files)."""
    return line.split("//", 1)[0]


def main():
    problems = []
    for folder in PRODUCTION:
        for source in sorted((root / folder).rglob("*")):
            if source.suffix not in (".cpp", ".h") or "build" in source.parts:
                continue
            name = source.relative_to(root).as_posix()
            for number, line in enumerate(source.read_text().splitlines(), 1):
                code = code_of(line)
                for what, pattern, allowed in RULES:
                    in_scope = name in BOUNCE_LOOP if what.endswith("bounce loop") else True
                    if in_scope and name not in allowed and re.search(pattern, code):
                        problems.append(f"{name}:{number}: {what} outside its home: {line.strip()}")
    for problem in problems:
        print(problem)
    print(f"{len(RULES)} rules, {len(problems)} places that break them")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
