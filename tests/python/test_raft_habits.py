"""RAFT habits on FlowScape datasets: `+` and `*`, the evaluation adapter (padding, list outputs),
augmentation with hand-derived flow (flips negate and mirror, a scale multiplies), crops that
resize, the pole and MAX_FLOW masks, cube faces as pinhole data."""
import os
import subprocess

import numpy as np
import pytest
import torch

import flowscape
from flowscape import augment

BIN = os.environ.get("FLOWSCAPE_BIN", "build/apps")


@pytest.fixture(scope="module")
def release(tmp_path_factory):
    out = tmp_path_factory.mktemp("raft")
    subprocess.run([f"{BIN}/gen_flowscape", "--maps", "1", "--sequences-per-map", "2", "--frames", "3",
                    "--resolution", "16", "--face-size", "8", "--spp", "1", "--vehicles", "4",
                    "--pedestrians", "2", "--weather", "sunny,rain", "--out", str(out)],
                   check=True, capture_output=True)
    subprocess.run([f"{BIN}/flowscape_split", str(out)], check=True, capture_output=True)
    return out


def affine_sample(h=24, w=40, seed=0):
    """Flow u = a + b x + c y, v = d + e x + f y (x, y pixel centres at integers)."""
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[0:h, 0:w].astype(np.float64)
    flow = np.stack([1.5 + 0.1 * x - 0.05 * y, -0.7 + 0.02 * x + 0.08 * y], axis=2)
    return {"img1": rng.uniform(0, 255, (h, w, 3)).astype(np.float32),
            "img2": rng.uniform(0, 255, (h, w, 3)).astype(np.float32),
            "flow": flow.astype(np.float32), "valid": np.ones((h, w), np.float32)}


def test_datasets_add_and_multiply_like_raft(release):
    train, test = flowscape.FlowScape(release, "train"), flowscape.FlowScape(release, "test")
    mix = 3 * train + test
    assert len(mix) == 3 * len(train) + len(test)
    assert torch.equal(mix[len(train)][2], train[0][2])  # the second copy starts again
    assert torch.equal(mix[3 * len(train)][2], test[0][2])
    assert len(2 * mix + train) == 2 * len(mix) + len(train)
    assert len(train * 2) == 2 * len(train)
    assert len(torch.utils.data.ConcatDataset([mix, test])) == len(mix) + len(test)


def test_the_raft_adapter_pads_to_eight_and_takes_the_last_prediction():
    seen = []

    class FakeRaft(torch.nn.Module):
        def forward(self, img1, img2, iters=12, test_mode=False):
            seen.append((img1.shape, iters, test_mode))
            flow = img1[:, :2] - img2[:, :2]
            return (flow * 0.125, flow) if test_mode else [flow * 0.5, flow]

    img1 = torch.arange(2 * 3 * 13 * 30, dtype=torch.float32).reshape(2, 3, 13, 30)
    img2 = torch.zeros_like(img1)
    flow = flowscape.RaftAdapter(FakeRaft(), iters=7)(img1, img2)
    assert seen[0] == ((2, 3, 16, 32), 7, True)
    assert torch.equal(flow, img1[:, :2])  # unpadded, the full-resolution prediction
    padded, = flowscape.InputPadder(img1.shape).pad(img1)
    # panoramas wrap: the column left of column 0 is the last column
    assert torch.equal(padded[..., 1:14, 0], img1[..., -1])
    assert torch.equal(padded[..., 0, 1:31], img1[..., 0, :])  # edge row repeated above
    train_mode = flowscape.RaftAdapter(FakeRaft(), test_mode=False)(img1, img2)
    assert torch.equal(train_mode, img1[:, :2])  # a list's last element


def test_a_horizontal_flip_negates_u_and_mirrors_the_field():
    sample = affine_sample()
    out = augment.flip(sample, horizontal=True)
    w = sample["flow"].shape[1]
    # hand-derived: the pixel at x shows what was at W-1-x, its vector mirrored
    assert np.array_equal(out["flow"][:, :, 0], -sample["flow"][:, ::-1, 0])
    assert np.array_equal(out["flow"][:, :, 1], sample["flow"][:, ::-1, 1])
    assert np.array_equal(out["img1"][:, 0], sample["img1"][:, w - 1])
    up = augment.flip(sample, horizontal=False)
    assert np.array_equal(up["flow"][:, :, 1], -sample["flow"][::-1, :, 1])
    assert np.array_equal(up["flow"][:, :, 0], sample["flow"][::-1, :, 0])


@pytest.mark.parametrize("sx,sy", [(2.0, 2.0), (0.5, 0.5), (1.5, 0.75)])
def test_a_scale_multiplies_the_flow_by_its_factor(sx, sy):
    sample = affine_sample()
    h, w = sample["flow"].shape[:2]
    out = augment.scale(sample, sx, sy)
    new_h, new_w = out["flow"].shape[:2]
    assert (new_h, new_w) == (round(h * sy), round(w * sx))
    ys, xs = np.mgrid[0:new_h, 0:new_w].astype(np.float64)
    x, y = (xs + 0.5) / sx - 0.5, (ys + 0.5) / sy - 0.5  # the pre-image of each new pixel
    inside = (x >= 0) & (x <= w - 1) & (y >= 0) & (y <= h - 1)
    u = 1.5 + 0.1 * x - 0.05 * y
    v = -0.7 + 0.02 * x + 0.08 * y
    assert np.abs(out["flow"][..., 0] - sx * u)[inside].max() < 0.02  # 1/32-px sampling steps
    assert np.abs(out["flow"][..., 1] - sy * v)[inside].max() < 0.02


def test_a_crop_larger_than_the_sample_scales_it_up_first():
    sample = affine_sample(24, 40)
    augmentation = flowscape.Augmentation(crop=(32, 48), jitter=False, shift=False, seed=1,
                                          panorama=False)
    out = augmentation(sample)
    assert out["flow"].shape == (32, 48, 2) and out["img1"].shape == (32, 48, 3)
    full = flowscape.Augmentation(crop=(24, 40), scale=(-0.2, 0.5), h_flip=0.5, v_flip=0.1,
                                  jitter=False, seed=3)
    for _ in range(5):
        assert full(affine_sample())["flow"].shape == (24, 40, 2)


def test_pole_and_max_flow_masks(release):
    plain = flowscape.FlowScape(release, "train")
    masked = flowscape.FlowScape(release, "train", exclude_poles=30, max_flow=2.0)
    _, _, flow, valid = plain[0]
    _, _, _, valid_masked = masked[0]
    h = valid.shape[0]
    rows = flowscape.pole_mask(h, 30)
    latitude = 90 - 180 * (np.arange(h) + 0.5) / h
    assert np.array_equal(rows, np.abs(latitude) < 60)
    expected = valid.numpy() * rows[:, None] * (flow.norm(dim=0).numpy() < 2.0)
    assert np.array_equal(valid_masked.numpy(), expected)


def test_cube_faces_are_pinhole_items(release):
    faces = flowscape.FlowScape(release, "train", faces=("front", "left"), extras=("meta",))
    panoramas = flowscape.FlowScape(release, "train")
    assert len(faces) == 2 * len(panoramas)
    img1, img2, flow, valid, extra = faces[1]
    assert img1.shape == (3, 8, 8) and flow.shape == (2, 8, 8)
    assert extra["meta"]["face"] == "left"
    layout = flowscape.ReleaseLayout(release)
    meta = extra["meta"]
    expected = flowscape.read_flo(layout.frame_file(meta["scene"], "flow", meta["frame"], "left"))
    known = valid.numpy() > 0
    assert np.array_equal(flow.numpy().transpose(1, 2, 0)[known], expected[known])
    with pytest.raises(ValueError, match="faces must be"):
        flowscape.FlowScape(release, "train", faces=("sideways",))
