"""Compares two releases rendered with different Embree kernel families (tests/kernels_test.sh).

    compare_releases.py A B identical   every file the same byte for byte, but meta.json's record
                                        of the kernels (generator.kernels, .embree_config) and the
                                        manifest's sizes and hashes of the meta.json files
    compare_releases.py A B bounded     the same files; in sequences/, each kind's pixels the same
                                        but for the share docs/release.md allows beyond its
                                        tolerance, and meta.json the same but for its statistics

Prints, per kind, the largest difference and the share of values beyond the tolerance. Images are
read with OpenImageIO's Python module, .flo files with numpy: nothing of FlowScape's.
"""
import json
import sys
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

# kind (a frame file's folder) -> (tolerance, largest share of values beyond it). Hits of a
# different kernel family differ in the last bits of their distance and barycentrics (other
# rounding: FMA, 4/8/16-wide arithmetic), and rays that graze an edge may hit on one side and miss
# on the other: those change a pixel's class, colour or visibility outright.
RELATIVE = {"depth"}  # tolerance relative to the value
LIMITS = {
    "color": (0, 0.02), "final": (0, 0.02),
    "semantic": (0, 0.002), "instance": (0, 0.002), "valid": (0, 0.002), "lens_mask": (0, 0),
    "depth": (1e-5, 0.002), "flow": (1e-3, 0.002), "scene_flow": (1e-4, 0.002),
    "normal": (1e-4, 0.002), "normal_shading": (1e-4, 0.002), "time": (0, 0),
}


def kind_of(path):
    kind = path.parent.name
    for prefix in ("flow", "valid"):  # flow_backward, flow_gap2, valid_backward_gap2, ...
        if kind.startswith(prefix):
            return prefix
    return kind


def values(path):
    if path.suffix == ".flo":
        data = path.read_bytes()
        width, height = np.frombuffer(data[4:12], "<i4")
        flow = np.frombuffer(data[12:], "<f4").reshape(height, width, 2).astype(np.float64)
        flow[np.abs(flow) >= 1e9] = np.nan  # the unknown flow value
        return flow
    image = oiio.ImageInput.open(str(path))
    pixels = image.read_image(image.spec().format) if image else None  # in the file's own type
    if pixels is None:
        raise SystemExit(f"{path}: cannot read ({oiio.geterror()})")
    image.close()
    return pixels.astype(np.float64)


def beyond(a, b, tolerance, relative):
    known = np.isfinite(a) & np.isfinite(b)
    with np.errstate(invalid="ignore"):  # infinite depths: the sky
        difference = np.where(known, np.abs(a - b), 0)
    if relative:
        difference = difference / np.maximum(np.where(known, np.abs(a), 1), 1e-30)
    differs = (np.isfinite(a) != np.isfinite(b)) | (difference > tolerance)
    return float(difference.max(initial=0)), int(differs.sum()), differs.size


def kernel_free_meta(path, mode):
    meta = json.loads(path.read_text())
    for key in ("kernels", "embree_config"):
        meta.get("generator", {}).pop(key, None)
    if mode == "bounded":  # the statistics of images that may differ
        meta.pop("statistics", None)
    return meta


def kernel_free_manifest(path):
    manifest = json.loads(path.read_text())
    manifest["files"] = {k: v for k, v in manifest["files"].items() if not k.endswith("meta.json")}
    return manifest


def files(root):
    return sorted(p.relative_to(root) for p in root.rglob("*") if p.is_file())


def main(a, b, mode):
    a, b = Path(a), Path(b)
    if not (a / "manifest.json").is_file():
        sys.exit(f"{a}: not a finished release")
    if files(a) != files(b):
        sys.exit(f"{a} and {b} hold other files: {sorted(set(files(a)) ^ set(files(b)))[:5]}")
    failures, kinds = [], {}
    for rel in files(a):
        if mode == "bounded" and rel.parts[0] != "sequences":
            continue  # what is made from the sequences: manifest, card, explorer
        if rel.name == "meta.json":
            same = kernel_free_meta(a / rel, mode) == kernel_free_meta(b / rel, mode)
        elif rel.name == "manifest.json":
            same = kernel_free_manifest(a / rel) == kernel_free_manifest(b / rel)
        else:
            same = (a / rel).read_bytes() == (b / rel).read_bytes()
        if same:
            continue
        if mode == "identical" or rel.suffix == ".json":
            failures.append(f"{rel} differs")
            continue
        kind = kind_of(rel)
        tolerance, _ = LIMITS[kind]
        largest, differing, total = beyond(values(a / rel), values(b / rel), tolerance,
                                           kind in RELATIVE)
        seen = kinds.setdefault(kind, [0.0, 0, 0])
        seen[0], seen[1] = max(seen[0], largest), seen[1] + differing
    if mode == "bounded":
        for rel in files(a):  # every value of a kind, for its share
            if rel.parts[0] == "sequences" and rel.suffix != ".json" and kind_of(rel) in kinds:
                kinds[kind_of(rel)][2] += values(a / rel).size
    for kind, (largest, differing, total) in sorted(kinds.items()):
        share = differing / total
        print(f"{kind:15s} largest difference {largest:.3g}, {differing} of {total} values "
              f"({100 * share:.3f} %) beyond {LIMITS[kind][0]:g}")
        if share > LIMITS[kind][1]:
            failures.append(f"{kind}: {100 * share:.3f} % beyond its tolerance (at most "
                            f"{100 * LIMITS[kind][1]:g} %)")
    for failure in failures:
        print(f"{a} vs {b}: {failure}")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main(*sys.argv[1:])
