"""The statistics of meta.json and manifest.json against numpy on a small release's files."""
import json
import math
import os
import subprocess

import numpy as np
import pytest

from flowscape import io

BIN = os.environ.get("FLOWSCAPE_BIN", "build/apps")
UNKNOWN = 1e9  # flow components above it are unknown


@pytest.fixture(scope="session")
def release(tmp_path_factory):
    out = tmp_path_factory.mktemp("statistics")
    subprocess.run([f"{BIN}/gen_flowscape", "--maps", "2", "--sequences-per-map", "3",
                    "--frames", "5", "--resolution", "32", "--face-size", "16", "--spp", "1",
                    "--vehicles", "30", "--pedestrians", "10", "--weather", "sunny,rain",
                    "--outputs", "none", "--out", str(out)], check=True, capture_output=True)
    return out


@pytest.fixture(scope="session")
def rig_release(tmp_path_factory):
    out = tmp_path_factory.mktemp("statistics_rig")
    subprocess.run([f"{BIN}/gen_flowscape", "--rig", "fisheye", "--maps", "1",
                    "--sequences-per-map", "1", "--frames", "3", "--resolution", "32", "--spp", "1",
                    "--outputs", "none", "--out", str(out)], check=True, capture_output=True)
    return out


def nearest_rank(values, percent):
    ordered = np.sort(np.asarray(values))
    return ordered[max((len(ordered) * percent + 99) // 100, 1) - 1]


def frame_files(seq, view, frame):
    def path(kind, ext):
        return seq / view / kind / f"{frame:06d}{ext}"
    return path


def numpy_frame(seq, view, frame, frames, edges):
    path = frame_files(seq, view, frame)
    semantic = io.read_png(path("semantic", ".png")).reshape(-1)
    instance = io.read_png(path("instance", ".png")).reshape(-1)
    result = {"classes": np.bincount(np.minimum(semantic, 22), minlength=23),
              "actors": int((instance > 0).sum()), "pixels": semantic.size}
    if frame + 1 == frames:
        return result
    flow = io.read_flo(path("flow", ".flo")).astype(np.float64)
    valid = io.read_png(path("valid", ".png")).reshape(-1)
    known = (np.abs(flow[..., 0]) < UNKNOWN) & (np.abs(flow[..., 1]) < UNKNOWN)
    magnitude = np.hypot(flow[..., 0], flow[..., 1])[known] * 1024 / flow.shape[1]
    bins = np.searchsorted(edges, magnitude, side="right") - 1
    result.update(histogram=np.bincount(bins, minlength=len(edges)), magnitude=magnitude,
                  valid=int((valid > 0).sum()))
    return result


def heading(pose):
    m = np.asarray(pose).reshape(3, 4)
    return math.atan2(m[1, 0], m[0, 0])


def check_sequence(seq, meta, view):
    s = meta["statistics"]
    assert s["view"] == view
    edges = np.array(s["flow_bin_edges"])
    assert edges[0] == 0 and edges[1] == 1 / 16 and edges[-1] == 1024
    assert np.allclose(edges[2:] / edges[1:-1], 2 ** (1 / 8))
    frames = meta["frames"]
    per_frame = [numpy_frame(seq, view, f, frames, edges) for f in range(frames)]
    with_flow = [f for f in per_frame if "histogram" in f]
    assert s["flow_histogram"] == sum(f["histogram"] for f in with_flow).tolist()
    assert math.isclose(s["flow_sum"], sum(f["magnitude"].sum() for f in with_flow), rel_tol=1e-9)
    assert s["class_pixels"] == sum(f["classes"] for f in per_frame).tolist()
    assert s["actor_pixels"] == sum(f["actors"] for f in per_frame)
    assert s["pixels"] == sum(f["pixels"] for f in per_frame)
    assert s["valid_pixels"] == sum(f["valid"] for f in with_flow)
    for f, numbers in enumerate(per_frame):
        if "magnitude" not in numbers:
            assert s["frames"]["flow_p50"][f] is None
            continue
        magnitude = numbers["magnitude"].astype(np.float32)
        for percent in (50, 90, 99):
            assert s["frames"][f"flow_p{percent}"][f] == pytest.approx(
                float(nearest_rank(magnitude, percent)), rel=1e-6)
        assert s["frames"]["actor_share"][f] == pytest.approx(numbers["actors"] / numbers["pixels"])
    poses = [np.asarray(p).reshape(3, 4) for p in meta["poses"]]
    speeds = [np.linalg.norm(b[:, 3] - a[:, 3]) * meta["fps"] for a, b in zip(poses, poses[1:])]
    turns = [math.remainder(heading(b) - heading(a), 2 * math.pi) * 180 / math.pi
             for a, b in zip(meta["poses"], meta["poses"][1:])]
    assert np.allclose(s["ego"]["speed"], speeds, rtol=1e-9)
    assert np.allclose(s["ego"]["yaw_rate"], np.array(turns) * meta["fps"], atol=1e-9)
    assert s["ego"]["yaw_change_degrees"] == pytest.approx(sum(turns), abs=1e-9)
    return per_frame


def histogram_percentile(histogram, edges, q):
    """The manifest's reading of a histogram (docs/release.md, "Statistics"), written again."""
    cumulative = np.cumsum(histogram)
    target = q * cumulative[-1]
    k = int(np.argmax((cumulative >= target) & (np.asarray(histogram) > 0)))
    before = cumulative[k] - histogram[k]
    share = (target - before) / histogram[k]
    if k + 1 == len(edges):
        return edges[k]
    lo, hi = edges[k], edges[k + 1]
    return lo + share * (hi - lo) if k == 0 else lo * (hi / lo) ** share


def test_sequence_and_release_statistics_match_numpy(release):
    manifest = json.loads((release / "manifest.json").read_text())
    stats = manifest["statistics"]
    edges = np.array(stats["flow_bin_edges"])
    groups = {}
    for seq in sorted((release / "sequences").iterdir()):
        meta = json.loads((seq / "meta.json").read_text())
        per_frame = check_sequence(seq, meta, "erp")
        weather = "rain" if meta["weather"].get("precipitation", 0) > 0 else "sunny"
        for group in ("all", "map " + meta["map_name"], weather):
            groups.setdefault(group, []).append((meta, per_frame))
    for name, members in groups.items():
        g = (stats["all"] if name == "all" else
             stats["maps"][name[4:]] if name.startswith("map ") else stats["weathers"][name])
        frames = [f for _, per_frame in members for f in per_frame]
        magnitudes = np.concatenate([f["magnitude"] for f in frames if "magnitude" in f])
        histogram = sum(f["histogram"] for f in frames if "histogram" in f)
        assert g["sequences"] == len(members)
        assert g["flow"]["histogram"] == histogram.tolist()
        assert g["flow"]["pixels"] == magnitudes.size
        assert g["flow"]["mean"] == pytest.approx(magnitudes.mean(), rel=1e-9)
        for percent in (10, 25, 50, 75, 90, 99):
            reported = g["flow"]["percentiles"][f"p{percent}"]
            assert reported == pytest.approx(histogram_percentile(histogram, edges, percent / 100),
                                             rel=1e-9)
            exact = np.percentile(magnitudes, percent)
            if exact > edges[1]:  # within the eighth octave around the exact value
                assert exact / 2 ** (1 / 8) <= reported <= exact * 2 ** (1 / 8)
        pixels = sum(f["pixels"] for f in frames)
        classes = sum(f["classes"] for f in frames)
        assert g["class_shares"]["Road"] == pytest.approx(classes[7] / pixels)
        assert g["class_shares"]["Vehicles"] == pytest.approx(classes[10] / pixels)
        assert g["actor_share"] == pytest.approx(sum(f["actors"] for f in frames) / pixels)
        flow_pixels = sum(f["pixels"] for f in frames if "valid" in f)
        assert g["valid_share"] == pytest.approx(sum(f["valid"] for f in frames if "valid" in f)
                                                 / flow_pixels)
        speeds = [v for meta, _ in members for v in meta["statistics"]["ego"]["speed"]]
        yaw_rates = [abs(v) for meta, _ in members for v in meta["statistics"]["ego"]["yaw_rate"]]
        assert g["ego_speed"]["mean"] == pytest.approx(np.mean(speeds))
        assert g["ego_speed"]["p50"] == nearest_rank(speeds, 50)
        assert g["ego_speed"]["p90"] == nearest_rank(speeds, 90)
        assert g["yaw_rate_abs"]["p99"] == nearest_rank(yaw_rates, 99)
        assert sum(g["ego_speed_histogram"]) == len(speeds)
        turning = sum(abs(meta["statistics"]["ego"]["yaw_change_degrees"]) >= 45
                      for meta, _ in members)
        assert g["turning_sequences"] == turning
    card = (release / "README.md").read_text()
    assert "## Statistics" in card and "card/statistics.svg" in card
    assert (release / "card" / "statistics.svg").read_text().startswith("<svg")


def test_a_rig_release_takes_its_first_camera(rig_release):
    seq = next((rig_release / "sequences").iterdir())
    meta = json.loads((seq / "meta.json").read_text())
    check_sequence(seq, meta, "cameras/" + meta["rig"]["cameras"][0]["name"])


def test_an_old_release_gets_the_same_statistics_from_its_files(release, tmp_path):
    """flowscape_explore computes what meta.json lacks from the files, with the same numbers."""
    old = tmp_path / "old"
    subprocess.run(["cp", "-r", str(release), str(old)], check=True)
    for meta_file in (old / "sequences").glob("*/meta.json"):
        meta = json.loads(meta_file.read_text())
        del meta["statistics"]
        meta_file.write_text(json.dumps(meta))
    run = subprocess.run([f"{BIN}/flowscape_explore", str(old)], check=True, capture_output=True,
                         text=True)
    data = (old / "explorer" / "data.js").read_text()
    recomputed = json.loads(data[data.index("=") + 1:data.rindex(";")])["statistics"]
    recorded = json.loads((release / "manifest.json").read_text())["statistics"]
    assert recomputed == recorded
    assert "flow p10" in run.stdout
