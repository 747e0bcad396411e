"""FlowScape splits as a torch Dataset, from a release made by gen_flowscape / flowscape_split
(its splits over its sequences, found through the layout in manifest.json) or from the PanoFlow
tree (panoflow/<split>/<weather>/...)."""
import copy
import json
import os

import numpy as np

from .io import read_flow, read_image, UNKNOWN_FLOW
from .cameras import camera_record
from .layout import ReleaseLayout

SKY = 13
FACES = ("front", "right", "back", "left", "up", "down")


def pole_mask(height, degrees):
    """Per ERP row (height rows): True where the row centre lies more than `degrees` from both
    poles."""
    latitude = 90 - 180 * (np.arange(height) + 0.5) / height
    return np.abs(latitude) < 90 - degrees


def classic_flow(flow):
    """360-degree ERP flow (shortest way round) -> classic flow (the target's column in [0, W))."""
    width = flow.shape[1]
    x = np.arange(width, dtype=np.float32)[None, :]
    target = np.mod(x + flow[..., 0], width)
    out = flow.copy()
    out[..., 0] = target - x
    return out


def wrapped_flow(flow):
    """Classic ERP flow -> 360-degree flow (the shortest way round, u in (-W/2, W/2])."""
    width = flow.shape[1]
    out = flow.copy()
    out[..., 0] = flow[..., 0] - width * np.round(flow[..., 0] / width)
    out[..., 0] = np.where(out[..., 0] <= -width / 2, out[..., 0] + width, out[..., 0])
    return out


class Concat:
    """Datasets one after another, as RAFT builds its training mix (`100 * sintel + things`):
    supports len, indexing, `+` and `n *` like FlowScape itself."""

    def __init__(self, datasets):
        self.datasets = list(datasets)

    def __len__(self):
        return sum(len(d) for d in self.datasets)

    def __getitem__(self, index):
        if index < 0:
            index += len(self)
        for dataset in self.datasets:
            if index < len(dataset):
                return dataset[index]
            index -= len(dataset)
        raise IndexError("index out of range")

    def __add__(self, other):
        return Concat(self.datasets + [other])

    def __radd__(self, other):
        return Concat([other] + self.datasets)

    def __rmul__(self, times):
        return Concat(self.datasets * int(times))

    __mul__ = __rmul__


class FlowScape:
    """A torch-style Dataset (len / getitem) of flow pairs.

    Each item is (img1, img2, flow, valid) as RAFT-style loops take them: float32 tensors
    3 x H x W (0-255), 3 x H x W, 2 x H x W (pixels) and H x W (1.0 where the flow is usable).
    With `extras`, a fifth element is a dict holding what was asked: 'semantic' (H x W int64,
    FlowScape layout only), 'meta' (scene, frame, weather, map), 'calibration' (a camera's or cube
    face's record from meta.json as JSON text, without poses: flowscape.camera_model(json.loads(
    ...)) projects with it; Augmentation's crops and scales keep it true for the image they make,
    flips and FDA refuse it; not for panoramas).

    outputs: more output kinds of the release to put in the extras dict under their names (numpy
    H x W x C before tensors, C x H x W tensors after): 'flow_backward' and 'valid_backward' (read
    at the pair's second frame: its flow back to the first), 'flow_gap2', 'scene_flow', 'normal',
    'normal_shading', ... as the release's manifest lists them (kinds of the backward direction
    are read at the second frame, every other kind at the first); only pairs that have every
    asked kind are items. Flow keeps the release's stored form (see the manifest's
    conventions); unknown flow values (1e10) are left in.

    pass_name: 'clean' (the path-traced colour, `color`) or 'final' (the final pass: motion
    blur, exposure, noise, lens; `gen_flowscape --outputs final`), as Sintel's passes; the flow
    and every other kind are the same for both.

    camera: a camera of the release's rig (gen_flowscape --rig; ReleaseLayout(root).cameras) to
    read instead of the ERP: its own image and flow (fisheye, PAL, ...; flowscape.camera_model
    projects and unprojects it); a rig without an ERP needs one.

    root: a release folder (or its panoflow/ folder); split: 'train' or 'test';
    weathers: None or a list such as ['fog', 'rain']; flow_mode: '360' or 'classic';
    exclude_sky: drop sky pixels from valid (needs semantics); exclude_poles: drop the rows within
    this many degrees of either pole (ERP), where flow grows without bound; max_flow: drop pixels
    whose flow is at least this long (RAFT's loaders use 400); faces: None for the panoramas, or
    cube faces ('front', 'right', 'back', 'left', 'up', 'down') to read their pinhole views (90
    degree field of view, pinhole flow; release layout only): each pair gives one item per face;
    transform: called on the sample dict {'img1', 'img2', 'flow', 'valid', ...} (numpy,
    H x W x C) before it becomes tensors.

    `n * dataset` repeats the items n times and `a + b` chains datasets, as in RAFT.
    """

    def __init__(self, root, split="train", weathers=None, flow_mode="360", exclude_sky=False,
                 extras=(), transform=None, as_tensors=True, exclude_poles=0.0, max_flow=None,
                 faces=None, outputs=(), camera=None, pass_name="clean"):
        if split not in ("train", "test", "val", "all"):
            raise ValueError(f"split must be 'train', 'test', 'val' or 'all', not {split!r}")
        if pass_name not in ("clean", "final"):
            raise ValueError(f"pass_name must be 'clean' or 'final', not {pass_name!r}")
        self.image_kind = "color" if pass_name == "clean" else "final"
        if flow_mode not in ("360", "classic"):
            raise ValueError(f"flow_mode must be '360' or 'classic', not {flow_mode!r}")
        self.root, self.flow_mode, self.exclude_sky = str(root), flow_mode, exclude_sky
        self.extras, self.transform, self.as_tensors = tuple(extras), transform, as_tensors
        self.exclude_poles, self.max_flow = float(exclude_poles), max_flow
        self.faces = None if faces is None else tuple(faces)
        self.outputs, self.camera = tuple(outputs), camera
        if camera is not None and faces is not None:
            raise ValueError("give faces or a camera, not both")
        # the stored flow's form and unknown marker: a release's manifest states them
        # (conventions); the PanoFlow tree's flow is read as it is stored
        self.stored_seam, self.unknown_flow = "360", UNKNOWN_FLOW
        self.panorama = self.faces is None  # a camera of a rig may say otherwise
        if not os.path.isdir(self.root):
            raise ValueError(f"{self.root}: no such folder (a FlowScape release or a PanoFlow tree)")
        if self.faces is not None and (set(self.faces) - set(FACES) or not self.faces):
            raise ValueError(f"faces must be some of {FACES}, not {faces!r}")
        if os.path.isfile(os.path.join(self.root, "manifest.json")):
            self.layout, self.items = "flowscape", self._release_items(split, weathers)
        else:
            self.layout, self.items = "panoflow", self._panoflow_items(split, weathers)
        if self.faces is not None and self.layout != "flowscape":
            raise ValueError(f"{self.root}: cube faces need the release layout")
        if pass_name == "final" and self.layout != "flowscape":
            raise ValueError(f"{self.root}: the final pass needs the release layout")
        if self.outputs and self.layout != "flowscape":
            raise ValueError(f"{self.root}: outputs need the release layout")
        if "calibration" in self.extras and self.layout != "flowscape":
            raise ValueError(f"{self.root}: calibration needs the release layout")
        if (exclude_sky or "semantic" in self.extras) and self.layout != "flowscape":
            raise ValueError(f"{self.root}: semantics (exclude_sky) need the release layout, "
                             "the PanoFlow tree has none")
        if not self.items:
            raise ValueError(f"{self.root}: no {split} pairs" + (f" for {weathers}" if weathers else ""))
        self._require_files()

    def _require_files(self):
        """Every file the items name is there: a missing one is named now, not mid-epoch."""
        missing = [path for item in self.items
                   for path in [item[k] for k in ("img1", "img2", "flow", "valid") if k in item]
                   + [path for path, _ in item.get("outputs", {}).values()]
                   if not os.path.isfile(path)]
        if missing:
            raise ValueError(f"{missing[0]}: missing" + (f" (and {len(missing) - 1} more files of the "
                             "split)" if len(missing) > 1 else "") + "; rerun the gen_flowscape "
                             "command that made the release to render them")

    def _release_items(self, split, weathers):
        layout = ReleaseLayout(self.root)
        self.stored_seam = layout.conventions["flow"]["erp_seam"]
        self.unknown_flow = float(layout.conventions["flow"].get("unknown_value", UNKNOWN_FLOW))
        # the class table's sky (carla-0.9.13: 13, carla-0.9.14: 11)
        self.sky = int(layout.conventions.get("semantic", {}).get("sky", SKY))
        if self.camera is None and layout.cameras and self.faces is None:
            raise ValueError(f"{self.root}: its rig has no ERP; pick a camera: "
                             f"{', '.join(layout.cameras)}")
        if self.faces is not None and (layout.cameras or not layout.layout.get("cube_faces", True)):
            raise ValueError(f"{self.root}: the release has no cube faces (" +
                             (f"its rig's cameras: {', '.join(layout.cameras)}; pick one with camera="
                              if layout.cameras else "made with --no-cube") + ")")
        if self.camera is not None and self.camera not in layout.cameras:
            raise ValueError(f"{self.root}: no camera {self.camera!r} (the rig has "
                             f"{', '.join(layout.cameras) or 'the ERP and the cube only'})")
        self.panorama = self.faces is None and layout.is_panorama(self.camera)
        if "calibration" in self.extras and self.panorama:
            raise ValueError(f"{self.root}: extras 'calibration' is for cameras and cube faces; a "
                             "panorama's crops and shifts are not a camera of its model")
        if self.image_kind not in layout.kinds:
            raise ValueError(f"{self.root}: the release has no final pass (gen_flowscape "
                             "--outputs final makes it)")
        missing = [kind for kind in self.outputs if kind not in layout.kinds]
        if missing:
            raise ValueError(f"{self.root}: the release has no {', '.join(missing)} (it holds "
                             f"{', '.join(layout.kinds)}; gen_flowscape --outputs makes more)")
        split_file = layout.split_file(split)
        if not os.path.isfile(split_file):
            if os.path.isfile(layout.split_file("all")):
                raise ValueError(f"{split_file}: missing: the release has one sequence, and train "
                                 "and test take whole ones; split='all' reads its pairs")
            raise ValueError(f"{split_file}: missing (run flowscape_split on the release)")
        weather_of, views_of, items = {}, {}, []
        for line in open(split_file):
            if not line.strip():
                continue
            scene, frame = line.split()
            frame = int(frame)
            if scene not in weather_of:
                meta = layout.meta(scene)
                weather_of[scene] = (meta["weather"]["preset"], meta["map_name"], meta["frames"])
                views_of[scene] = meta.get("views", {})
            weather, map_name, frames = weather_of[scene]
            at = {kind: frame + 1 if layout.step(kind) < 0 else frame for kind in self.outputs}
            if any(not layout.has_frame(kind, at[kind], frames) for kind in self.outputs):
                continue
            if weathers is None or weather in weathers:
                for face in self.faces or (None,):
                    def file(kind, at_frame):
                        return layout.frame_file(scene, kind, at_frame, face, self.camera)
                    item = {kind: file(kind, frame) for kind in ("flow", "valid", "semantic")}
                    item["outputs"] = {kind: (file(kind, at[kind]),
                                              layout.kinds[kind]["resampling"] == "flow")
                                       for kind in self.outputs}
                    item.update(img1=file(self.image_kind, frame),
                                img2=file(self.image_kind, frame + 1),
                                # strings and ints only ("" for no face, no camera): torch's
                                # default collate batches it
                                meta={"scene": scene, "frame": frame, "weather": weather,
                                      "map": map_name, "face": face or "",
                                      "camera": self.camera or ""})
                    if "calibration" in self.extras:
                        view = f"cameras/{self.camera}" if self.camera else f"cube/{face}"
                        item["calibration"] = json.dumps(camera_record(views_of[scene][view]))
                    items.append(item)
        return items

    def _panoflow_items(self, split, weathers):
        root = self.root if os.path.basename(self.root) == "panoflow" else os.path.join(self.root, "panoflow")
        side = os.path.join(root, split)
        if not os.path.isdir(side):
            raise ValueError(f"{self.root}: neither splits/{split}.txt nor panoflow/{split}/ "
                             "(run flowscape_split on the release)")
        items = []
        for weather in sorted(os.listdir(side)):
            if weathers is not None and weather not in weathers:
                continue
            for scene in sorted(os.listdir(os.path.join(side, weather, "img"))):
                images = sorted(os.listdir(os.path.join(side, weather, "img", scene)))
                for first, second in zip(images, images[1:]):
                    stem = first.rsplit(".", 1)[0]
                    items.append({"img1": os.path.join(side, weather, "img", scene, first),
                                  "img2": os.path.join(side, weather, "img", scene, second),
                                  "flow": os.path.join(side, weather, "flow", scene, stem + ".flo"),
                                  "meta": {"scene": scene, "frame": int(stem), "weather": weather,
                                           "map": "", "face": "", "camera": ""}})
        return items

    def __len__(self):
        return len(self.items)

    def __rmul__(self, times):
        repeated = copy.copy(self)
        repeated.items = self.items * int(times)
        return repeated

    __mul__ = __rmul__

    def __add__(self, other):
        return Concat([self, other])

    def __radd__(self, other):
        return Concat([other, self])

    def sample(self, index):
        """The item as numpy arrays (H x W x C), before the transform and tensors."""
        item = self.items[index]
        flow = read_flow(item["flow"])
        known = (np.abs(flow) < self.unknown_flow / 10).all(axis=2)
        flow = np.where(known[..., None], flow, 0).astype(np.float32)
        valid = known.copy()
        if "valid" in item:
            valid &= read_image(item["valid"])[..., 0] > 0
        panorama = self.panorama
        if panorama and self.exclude_poles > 0:
            valid &= pole_mask(valid.shape[0], self.exclude_poles)[:, None]
        if self.max_flow is not None:
            valid &= np.hypot(flow[..., 0], flow[..., 1]) < self.max_flow
        if panorama and self.flow_mode != self.stored_seam:
            flow = classic_flow(flow) if self.flow_mode == "classic" else wrapped_flow(flow)
        sample = {"img1": read_image(item["img1"])[..., :3].astype(np.float32),
                  "img2": read_image(item["img2"])[..., :3].astype(np.float32),
                  "flow": flow, "valid": valid.astype(np.float32), "meta": dict(item["meta"]),
                  "panorama": panorama}  # the view wraps round: what Augmentation shifts and crops
        for kind, (path, is_flow) in item.get("outputs", {}).items():
            sample[kind] = read_flow(path) if is_flow else read_image(path)
        if self.exclude_sky or "semantic" in self.extras:
            semantic = read_image(item["semantic"])[..., 0].astype(np.int64)
            if self.exclude_sky:
                sample["valid"] *= (semantic != self.sky)
            sample["semantic"] = semantic
        if "calibration" in self.extras:
            sample["calibration"] = item["calibration"]
        return sample

    def __getitem__(self, index):
        sample = self.sample(index)
        if self.transform is not None:
            sample = self.transform(sample)
        if not self.as_tensors:
            return sample
        import torch
        out = (torch.from_numpy(np.ascontiguousarray(sample["img1"].transpose(2, 0, 1))),
               torch.from_numpy(np.ascontiguousarray(sample["img2"].transpose(2, 0, 1))),
               torch.from_numpy(np.ascontiguousarray(sample["flow"].transpose(2, 0, 1))),
               torch.from_numpy(np.ascontiguousarray(sample["valid"])))
        if not self.extras and not self.outputs:
            return out
        extra = {}
        for kind in self.outputs:
            value = np.ascontiguousarray(sample[kind])
            extra[kind] = torch.from_numpy(value.transpose(2, 0, 1).copy() if value.shape[2] > 1
                                           else value[..., 0].copy())
        if "semantic" in self.extras:
            extra["semantic"] = torch.from_numpy(sample["semantic"])
        for key in ("meta", "calibration"):
            if key in self.extras:
                extra[key] = sample[key]
        return out + (extra,)
