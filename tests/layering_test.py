"""No library includes a layer above it (docs/architecture.md, "Architecture: one home per
concept"): each library's link line in its CMakeLists.txt names the project libraries it may use;
every `#include "flowscape/<library>/..."` of its sources must name itself or one of those (and
theirs, transitively), and the links must form no cycle. Apps, benches, tests and the Python
extension may include any library.

    layering_test.py REPO_ROOT
"""
import re
import sys
from pathlib import Path

root = Path(sys.argv[1])

# library -> (its folder, the include prefix of its headers)
LIBRARIES = {
    "core": "core", "geometry": "stitcher/geometry", "stitcher": "stitcher",
    "formats": "dataset_tools/formats",
    "scenes": "scenes", "weather": "weather", "renderer": "renderer",
    "layout": "dataset_tools/layout", "release": "dataset_tools/release",
    "quality": "dataset_tools/quality",
}


def links():
    """Each library's project libraries, as its target_link_libraries lines name them."""
    graph = {}
    for name, folder in LIBRARIES.items():
        text = (root / folder / "CMakeLists.txt").read_text()
        used = set()
        for call in re.findall(r"target_link_libraries\(\s*flowscape_(\w+)(.*?)\)", text, re.S):
            if call[0] == name:
                used |= set(re.findall(r"\bflowscape_(\w+)", call[1]))
        graph[name] = used & set(LIBRARIES)
    return graph


def below(graph, name, seen=()):
    if name in seen:
        sys.exit(f"the libraries' links form a cycle: {' -> '.join(seen + (name,))}")
    reach = set()
    for used in graph[name]:
        reach |= {used} | below(graph, used, seen + (name,))
    return reach


def main():
    graph = links()
    problems = []
    for name, folder in LIBRARIES.items():
        allowed = {name} | below(graph, name)
        for source in sorted((root / folder).rglob("*")):
            if source.suffix not in (".cpp", ".h", ".in"):
                continue
            for number, line in enumerate(source.read_text().splitlines(), 1):
                included = re.match(r'\s*#\s*include\s+"flowscape/(\w+)/', line)
                if included and included.group(1) not in allowed:
                    problems.append(f"{source.relative_to(root)}:{number}: {name} includes "
                                    f"flowscape/{included.group(1)}/, a library it does not link "
                                    f"({', '.join(sorted(allowed - {name})) or 'none'})")
    for problem in problems:
        print(problem)
    print(f"{len(LIBRARIES)} libraries, {len(problems)} includes of a layer above")
    sys.exit(1 if problems else 0)


main()
