"""The benchmark's TensorFlow.js graph interpreter (bench/detector/tfjs_graph.py) on operations
NanoDet's graph uses, against numpy's closed forms, and NanoDet's box decoding (GFL) against
boxes built by hand."""
import json
import os
import sys

import numpy as np
import pytest

torch = pytest.importorskip("torch")
sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "bench", "detector"))
from bench_detector import gfl_boxes  # noqa: E402
from tfjs_graph import GraphModel  # noqa: E402


def const(name, dtype="DT_INT32"):
    return {"name": name, "op": "Const", "attr": {"dtype": {"type": dtype}}}


def node(name, op, inputs, **attr):
    return {"name": name, "op": op, "input": inputs, "attr": attr}


def write_model(folder, nodes, weights):
    """model.json and one shard holding `weights` (name -> int32 or float32 array)."""
    blob, manifest = b"", []
    for name, value in weights.items():
        dtype = "int32" if value.dtype == np.int32 else "float32"
        manifest.append({"name": name, "shape": list(value.shape), "dtype": dtype})
        blob += value.astype(np.int32 if dtype == "int32" else np.float32).tobytes()
    (folder / "w.bin").write_bytes(blob)
    model = {"format": "graph-model", "modelTopology": {"node": nodes},
             "weightsManifest": [{"paths": ["w.bin"], "weights": manifest}]}
    (folder / "model.json").write_text(json.dumps(model))
    return GraphModel(str(folder / "model.json"))


def test_pad_transpose_leaky_relu_split(tmp_path):
    x = np.arange(-6, 6, dtype=np.float32).reshape(1, 2, 2, 3)
    model = write_model(tmp_path, [
        {"name": "x", "op": "Placeholder"},
        const("pads"), const("pads2"), const("fill", "DT_FLOAT"), const("perm"), const("sizes"),
        const("axis"),
        node("pad", "Pad", ["x", "pads"]),
        node("pad2", "PadV2", ["x", "pads2", "fill"]),
        node("t", "Transpose", ["x", "perm"]),
        node("leaky", "LeakyRelu", ["x"], alpha={"f": 0.1}),
        node("split", "SplitV", ["x", "sizes", "axis"], num_split={"i": "2"}),
    ], {"pads": np.int32([[0, 0], [1, 0], [0, 2], [0, 0]]),
        "pads2": np.int32([[0, 0], [0, 0], [0, 0], [1, 1]]), "fill": np.float32(-9),
        "perm": np.int32([0, 3, 1, 2]), "sizes": np.int32([1, -1]), "axis": np.int32(3)})
    pad, pad2, t, leaky, first, rest = model.run(
        {"x": torch.from_numpy(x)}, ["pad", "pad2", "t", "leaky", "split", "split:1"])
    np.testing.assert_array_equal(pad.numpy(), np.pad(x, [(0, 0), (1, 0), (0, 2), (0, 0)]))
    np.testing.assert_array_equal(pad2.numpy(), np.pad(x, [(0, 0)] * 3 + [(1, 1)],
                                                       constant_values=-9))
    np.testing.assert_array_equal(t.numpy(), x.transpose(0, 3, 1, 2))
    np.testing.assert_allclose(leaky.numpy(), np.where(x > 0, x, 0.1 * x), rtol=1e-6)
    np.testing.assert_array_equal(first.numpy(), x[..., :1])
    np.testing.assert_array_equal(rest.numpy(), x[..., 1:])


def test_sparse_to_dense(tmp_path):
    model = write_model(tmp_path, [
        const("none"), const("some"), const("shape"), const("values"), const("zero"),
        node("empty", "SparseToDense", ["none", "shape", "values", "zero"]),
        node("filled", "SparseToDense", ["some", "shape", "values", "zero"]),
    ], {"none": np.zeros((0, 1), np.int32), "some": np.int32([[0], [2]]),
        "shape": np.int32([4]), "values": np.int32([5, 7]), "zero": np.int32(3)})
    empty, filled = model.run({}, ["empty", "filled"])
    assert empty.tolist() == [3, 3, 3, 3]
    assert filled.tolist() == [5, 3, 7, 3]


def test_gfl_boxes_decode_each_side_at_its_expected_bin():
    # a 2 x 2 grid on a 64-px input: stride 32, centres at 16 and 48
    scores = np.float32([[0.1], [0.2], [0.3], [0.4]])
    distances = np.full((4, 4, 11), -60.0, np.float32)
    bins = [[0, 1, 2, 3], [1, 1, 1, 1], [2, 0, 0, 2], [3, 2, 1, 0]]  # left, top, right, bottom
    for cell, sides in enumerate(bins):
        for side, b in enumerate(sides):
            distances[cell, side, b] = 60.0  # all the mass in bin b
    distances[3, 0] = -60.0
    distances[3, 0, 2:4] = 60.0  # half in bin 2, half in bin 3: expected 2.5
    _, boxes = gfl_boxes(scores, distances.reshape(4, 44), 64)
    centres = [(16, 16), (48, 16), (16, 48), (48, 48)]
    expected = [[cx - 32 * l, cy - 32 * t, cx + 32 * r, cy + 32 * b]
                for (cx, cy), (l, t, r, b) in zip(centres, bins)]
    expected[3][0] = 48 - 32 * 2.5
    np.testing.assert_allclose(boxes, expected, atol=1e-4)


def test_scoring_counts_misses_by_reason():
    from bench_detector import VEHICLE, Tally, score_image
    car = {"family": VEHICLE, "row": "car", "counted": True, "pixels": 900}
    objects = [dict(car, box=(0, 0, 10, 10)), dict(car, box=(20, 0, 30, 10)),
               dict(car, box=(40, 0, 50, 10)), dict(car, box=(60, 0, 70, 10)),
               dict(car, box=(80, 0, 90, 10), pixels=300)]
    dets = [(VEHICLE, 0.9, 0, 0, 10, 10),     # finds the first (IoU 1)
            (VEHICLE, 0.2, 20, 0, 30, 10),    # the second's box, scoring under 0.3
            (VEHICLE, 0.8, 40, 0, 54, 20)]    # the third's IoU 100 / 280: a box off
    tally = Tally()
    score_image(dets, objects, tally)
    assert tally.misses(["car"]) == [None, "under the score", "box off", "nothing"]
    assert tally.recall(["car"]) == (0.25, 4)
    assert tally.recall(["car"], 200) == (0.2, 5)
    assert tally.recall(["car"], 200, 500) == (0.0, 1)
    assert tally.false == 1  # the box off: 100 of its 280 px inside the third car


def test_objects_in_full_view_are_scored_on_their_own():
    from bench_detector import VEHICLE, Tally, render_objects, score_image
    instance = np.zeros((50, 50), np.uint16)
    depth = np.full((50, 50), 5000, np.uint16)  # the world 50 m away
    instance[5:15, 5:25], depth[5:15, 5:25] = 1, 2000    # in front of the world: in full view
    instance[20:40, 5:15], depth[20:40, 5:15] = 2, 2000
    instance[20:40, 15:20], depth[20:40, 15:20] = 3, 1000  # nearer, along its right side
    actors = {str(k): {"kind": "car"} for k in (1, 2, 3)}
    objects = render_objects(instance, actors, depth)
    # the second's outline: 56 pixels, the 20 of its right column bordered by the nearer one
    assert [o["hidden"] for o in objects] == [0.0, 20 / 56, 0.0]
    assert render_objects(instance, actors)[0]["hidden"] is None  # no depth image
    tally = Tally()
    score_image([(VEHICLE, 0.9, 5, 5, 25, 15)], objects, tally)
    assert tally.recall(["car"], 200) == (0.5, 2)  # the third has 100 px: not counted
    assert tally.recall(["car in full view"], 200) == (1.0, 1)
