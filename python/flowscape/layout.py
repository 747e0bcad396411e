"""Where the files of a FlowScape release are: read from the "layout" that gen_flowscape writes
into manifest.json (the C++ table of output kinds, dataset_tools/layout/layout.h), so the plugin
spells no path of its own."""
import json
import os

# What releases from before manifest.json stated its conventions hold (flowscape 0.7).
FLOWSCAPE_CONVENTIONS = {
    "frame_rate": 30,
    "flow": {"value": "target - source", "units": "pixels", "u": "right", "v": "down",
             "erp_seam": "360", "unknown_value": 1e10},
}


class ReleaseLayout:
    """The layout of the release at `root`; raises ValueError naming the file when it has none."""

    def __init__(self, root):
        self.root = str(root)
        manifest = os.path.join(self.root, "manifest.json")
        if not os.path.isfile(manifest):
            raise ValueError(f"{manifest}: missing (not a finished FlowScape release)")
        try:
            with open(manifest) as f:
                self.layout = json.load(f)["layout"]
        except (ValueError, KeyError) as error:
            raise ValueError(f"{manifest}: no layout ({error}); rerun the gen_flowscape command "
                             "that made the release to rewrite its manifest") from None
        self.kinds = {kind["name"]: kind for kind in self.layout["kinds"]}
        with open(manifest) as f:
            self.conventions = json.load(f).get("conventions", FLOWSCAPE_CONVENTIONS)
        flow = self.conventions.get("flow", {})
        wanted = {"value": "target - source", "units": "pixels", "u": "right", "v": "down"}
        if any(flow.get(key) != value for key, value in wanted.items()) or \
                flow.get("erp_seam") not in ("360", "classic"):
            raise ValueError(f"{manifest}: conventions: flow is not target - source in pixels "
                             f"with u right, v down and a 360 or classic seam ({flow})")

    def step(self, kind):
        """The frame a kind of frame F connects to is F + step (0: the frame alone)."""
        row = self.kinds[kind]
        if "step" in row:
            return row["step"]
        return 1 if row.get("pairs_only") else 0

    def has_frame(self, kind, frame, frames):
        """Whether a sequence of `frames` frames has the kind at `frame` (both ends inside it)."""
        return 0 <= frame < frames and 0 <= frame + self.step(kind) < frames

    def sequence_dir(self, sequence):
        return os.path.join(self.root, self.layout["sequence_dir"].format(sequence=sequence))

    @property
    def cameras(self):
        """The cameras of a rig other than flowscape (names), [] for the ERP and its cube."""
        return [camera["name"] for camera in self.layout.get("cameras", [])]

    def is_panorama(self, camera=None):
        """Whether a view's image wraps round horizontally (the ERP, an equirectangular camera)."""
        if camera is None:
            return True
        return any(c["name"] == camera and c.get("panorama") for c in self.layout.get("cameras", []))

    def frame_file(self, sequence, kind, frame, face=None, camera=None):
        """The file of output kind `kind` ('color', 'flow', ...) of a frame: the ERP, one cube face,
        or one camera of another rig."""
        row = self.kinds[kind]
        views = self.layout["views"]
        if camera is not None:
            view = views["camera"].format(camera=camera)
        else:
            view = views["erp"] if face is None else views["cube"].format(face=face)
        name = self.layout["frame_file"].format(view=view, folder=row["folder"], frame=int(frame),
                                                extension=row["extension"])
        return os.path.join(self.sequence_dir(sequence), name)

    def split_file(self, split):
        return os.path.join(self.root, self.layout["split_file"].format(split=split))

    def meta(self, sequence):
        """The sequence's meta.json as a dict."""
        path = os.path.join(self.sequence_dir(sequence), self.layout["meta"])
        try:
            with open(path) as f:
                return json.load(f)
        except (OSError, ValueError) as error:
            raise ValueError(f"{path}: {error}") from None
