"""The panoflow/ tree as the public PanoFlow code reads it. The loader below is written from the
public description of its Flow360 dataset (not copied): for each split it lists the four weather
folders cloud, fog, rain and sunny unconditionally, pairs consecutive images of each scene
(<weather>/img/<scene>/*.jpg, sorted) with the sorted flow files (<weather>/flow/<scene>/*.flo),
and, as RAFT's dense loaders, counts a pixel valid where |u| < 1000 and |v| < 1000."""
import json
import os
import struct
import subprocess

import numpy as np
import pytest

from flowscape import io
from flowscape.layout import ReleaseLayout

BIN = os.environ.get("FLOWSCAPE_BIN", "build/apps")
PUBLIC_WEATHERS = ("cloud", "fog", "rain", "sunny")


def flow360_pairs(root, split):
    """(image1, image2, flow) paths, as the public loader finds them; raises on a missing folder."""
    pairs = []
    for weather in PUBLIC_WEATHERS:
        image_root = os.path.join(root, split, weather, "img")
        flow_root = os.path.join(root, split, weather, "flow")
        for scene in sorted(os.listdir(image_root)):
            images = sorted(os.listdir(os.path.join(image_root, scene)))
            flows = sorted(os.listdir(os.path.join(flow_root, scene)))
            for k in range(len(images) - 1):
                pairs.append((os.path.join(image_root, scene, images[k]),
                              os.path.join(image_root, scene, images[k + 1]),
                              os.path.join(flow_root, scene, flows[k])))
    return pairs


def read_flo(path):
    data = open(path, "rb").read()
    magic, width, height = struct.unpack("<fii", data[:12])
    assert magic == 202021.25
    return np.frombuffer(data[12:], np.float32).reshape(height, width, 2)


def make_release(out, *options):
    subprocess.run([f"{BIN}/gen_flowscape", "--maps", "1", "--frames", "3", "--resolution", "16",
                    "--face-size", "8", "--spp", "1", "--vehicles", "4", "--pedestrians", "2",
                    *options, "--out", str(out)], check=True, capture_output=True)
    return subprocess.run([f"{BIN}/flowscape_split", str(out)], check=True, capture_output=True,
                          text=True)


@pytest.mark.parametrize("weathers,sequences", [("sunny,rain", 2),
                                                 ("sunny,cloud,fog,rain,hard_rain,clear_sunset", 6)])
def test_the_public_loader_finds_every_pair_with_sky_invalid_and_classic_flow(tmp_path, weathers,
                                                                             sequences):
    split = make_release(tmp_path, "--sequences-per-map", str(sequences), "--weather", weathers)
    layout = ReleaseLayout(tmp_path)
    expected = {}
    for side in ("train", "test"):
        for line in open(layout.split_file(side)):
            scene, frame = line.split()
            expected.setdefault(side, []).append((scene, int(frame)))
    assert expected["train"] and expected["test"]  # never an empty split
    if sequences == 2:  # one sunny and one rain: the cloud and fog folders are empty, with warnings
        assert "warning: panoflow/train/cloud is empty" in split.stderr
    for side in ("train", "test"):
        pairs = flow360_pairs(tmp_path / "panoflow", side)
        assert len(pairs) == len(expected[side])  # every pair found, no missing folder
        by_scene_and_frame = sorted(pairs, key=lambda p: p[2].split(os.sep)[-2:])
        for (image1, image2, flow_file), (scene, frame) in zip(by_scene_and_frame,
                                                               sorted(expected[side])):
            assert f"/{scene}/" in flow_file and flow_file.endswith(f"{frame:06d}.flo")
            weather = json.load(open(os.path.join(layout.sequence_dir(scene), "meta.json")))["weather"]
            folder = flow_file.split(os.sep)[-4]
            base = ("rain" if weather["precipitation"] > 0 else "fog" if weather["fog_density"] >= 0.01
                    else "cloud" if weather["cloudiness"] >= 0.5 else "sunny")
            assert folder == base  # hard_rain under rain, clear_sunset under sunny
            flow = read_flo(flow_file)
            valid = (np.abs(flow[..., 0]) < 1000) & (np.abs(flow[..., 1]) < 1000)
            release_flow = read_flo(layout.frame_file(scene, "flow", frame))
            depth = io.read_image(layout.frame_file(scene, "depth", frame))[..., 0]
            sky = np.isinf(depth)
            assert sky.any() and not valid[sky].any()  # the sky is invalid
            width = flow.shape[1]
            x = np.arange(width)[None, :] + 0.5
            classic_u = np.mod(x + release_flow[..., 0], width) - x  # the target column in [0, W)
            assert np.abs(flow[..., 0] - classic_u)[valid].max() < 1e-3
            assert np.array_equal(flow[..., 1][valid], release_flow[..., 1][valid])
            assert valid.sum() == (~sky).sum()  # every non-sky pixel kept (occluded kept)


def test_occluded_pixels_on_request_and_360_flow_rewrite_the_tree(tmp_path):
    make_release(tmp_path, "--sequences-per-map", "2", "--weather", "sunny,rain")
    subprocess.run([f"{BIN}/flowscape_split", str(tmp_path), "--occluded", "invalid", "--flow", "360"],
                   check=True, capture_output=True)
    layout = ReleaseLayout(tmp_path)
    conventions = json.load(open(tmp_path / "panoflow" / "flowscape.json"))
    assert conventions == {"flow": "360", "sky": "invalid", "occluded": "invalid"}
    for image1, image2, flow_file in flow360_pairs(tmp_path / "panoflow", "train"):
        scene, frame = flow_file.split(os.sep)[-2], int(os.path.basename(flow_file)[:6])
        flow = read_flo(flow_file)
        valid = (np.abs(flow[..., 0]) < 1000) & (np.abs(flow[..., 1]) < 1000)
        visible = io.read_image(layout.frame_file(scene, "valid", frame))[..., 0] > 0
        sky = np.isinf(io.read_image(layout.frame_file(scene, "depth", frame))[..., 0])
        assert np.array_equal(valid, visible & ~sky)
        assert np.array_equal(flow[valid], read_flo(layout.frame_file(scene, "flow", frame))[valid])
