"""Tests of the Python plugin (run by CTest with PYTHONPATH=python:build/python)."""
import json
import math
import os
import subprocess

import numpy as np
import pytest
import torch

import flowscape
from flowscape import augment, io

BIN = os.environ.get("FLOWSCAPE_BIN", "build/apps")
YAW = os.environ.get("FLOWSCAPE_YAW_RELEASE", "build/tests/yaw_release")


@pytest.fixture(scope="session")
def yaw_release(tmp_path_factory):
    out = tmp_path_factory.mktemp("yaw")
    subprocess.run([YAW, str(out)], check=True, capture_output=True)
    return out


@pytest.fixture(scope="session")
def tiny_release(tmp_path_factory):
    out = tmp_path_factory.mktemp("release")
    subprocess.run([f"{BIN}/gen_flowscape", "--maps", "1", "--frames", "3", "--resolution", "32",
                    "--face-size", "16", "--spp", "1", "--vehicles", "10", "--pedestrians", "5",
                    "--out", str(out)], check=True, capture_output=True)
    subprocess.run([f"{BIN}/flowscape_split", str(out)], check=True, capture_output=True)
    return out


def test_a_pure_yaw_pair_loads_with_the_known_flow(yaw_release):
    img1, img2, flow, valid = flowscape.FlowScape(yaw_release, "train")[0]
    assert img1.shape == img2.shape == (3, 32, 64) and flow.shape == (2, 32, 64)
    assert img1.dtype == torch.float32 and float(img1.max()) <= 255
    u = 64 * 3 / 360  # turning left by 3 deg moves everything right by W * 3 / 360 px
    assert np.abs(flow[0].numpy() - u).max() < 1e-3
    assert np.abs(flow[1].numpy()).max() < 1e-3
    assert float(valid.mean()) > 0.95
    classic = flowscape.FlowScape(yaw_release, "train", flow_mode="classic")[0][2][0].numpy()
    x = np.arange(64)[None, :]
    expected = np.where(x + u >= 64, u - 64, u)  # the target's column kept inside the image
    assert np.abs(classic - expected).max() < 1e-3
    no_sky = flowscape.FlowScape(yaw_release, "train", exclude_sky=True, extras=("semantic", "meta"))
    _, _, _, valid_ground, extra = no_sky[0]
    assert extra["meta"]["weather"] == "sunny"
    assert (valid_ground.numpy()[extra["semantic"].numpy() == 13] == 0).all()
    assert float(valid_ground.sum()) < float(valid.sum())


def _pinhole_sample(h=48, w=64, seed=1):
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[0:h, 0:w].astype(np.float64)
    flow = np.stack([0.3 + 0.01 * x, -0.2 + 0.005 * y], axis=2).astype(np.float32)  # affine
    images = [rng.uniform(0, 255, (h, w, 3)).astype(np.float32) for _ in range(2)]
    return {"img1": images[0], "img2": images[1], "flow": flow,
            "valid": np.ones((h, w), np.float32)}


def _affine_flow(px, py):
    return 0.3 + 0.01 * px, -0.2 + 0.005 * py


def test_fda_e_flow_equals_projecting_both_ends_through_the_distortion():
    h, w, ty, tz, fh, fv = 48, 64, 1.1, 0.7, 1.6, 1.3
    out = augment.fda_e(_pinhole_sample(h, w), np.random.default_rng(0), theta_y=ty, theta_z=tz,
                        fov_h=fh, fov_v=fv)
    cy, sy, cz, sz = math.cos(ty), math.sin(ty), math.cos(tz), math.sin(tz)
    rot = [[cz * cy, -sz, cz * sy], [sz * cy, cz, sz * sy], [-sy, 0, cy]]  # R_z R_y by hand
    fx, fy = w / (2 * math.tan(fh / 2)), h / (2 * math.tan(fv / 2))
    checked = 0
    for ye in range(h):
        for xe in range(w):
            if out["valid"][ye, xe] == 0:
                continue
            polar, azimuth = math.pi * (ye + 0.5) / h, 2 * math.pi * (xe + 0.5) / w
            s = [math.sin(polar) * math.cos(azimuth), math.sin(polar) * math.sin(azimuth),
                 math.cos(polar)]
            p = [sum(rot[i][j] * s[j] for j in range(3)) for i in range(3)]
            px = fx * p[1] / p[0] + w / 2 - 0.5  # start, source index coordinates
            py = fy * p[2] / p[0] + h / 2 - 0.5
            du, dv = _affine_flow(px, py)
            ex, ey = px + du + 0.5, py + dv + 0.5  # end, continuous coordinates
            ray = [1, (ex - w / 2) / fx, (ey - h / 2) / fy]
            back = [sum(rot[j][i] * ray[j] for j in range(3)) for i in range(3)]  # R^T ray
            norm = math.sqrt(sum(c * c for c in back))
            end_y = h * math.acos(back[2] / norm) / math.pi
            end_x = (w * math.atan2(back[1], back[0]) / (2 * math.pi)) % w
            u = (end_x - (xe + 0.5) + w / 2) % w - w / 2
            assert abs(out["flow"][ye, xe, 0] - u) < 0.02
            assert abs(out["flow"][ye, xe, 1] - (end_y - (ye + 0.5))) < 0.02
            checked += 1
    assert checked > 100


def test_fda_r_flow_equals_distorting_both_ends():
    h, w, k2, k4 = 48, 64, 8e-5, 2e-9
    out = augment.fda_r(_pinhole_sample(h, w), np.random.default_rng(0), k2=k2, k4=k4)
    xc, yc = (w - 1) / 2, (h - 1) / 2

    def distort(x, y):
        r2 = (x - xc) ** 2 + (y - yc) ** 2
        s = 1 + k2 * r2 + k4 * r2 * r2
        return xc + (x - xc) * s, yc + (y - yc) * s

    checked = 0
    for yd in range(0, h, 3):
        for xd in range(0, w, 3):
            if out["valid"][yd, xd] == 0:
                continue
            lo, hi = 0.0, 2.0  # the undistorted point on the ray from the centre, by bisection
            for _ in range(60):
                mid = (lo + hi) / 2
                x, y = distort(xc + (xd - xc) * mid, yc + (yd - yc) * mid)
                if math.hypot(x - xc, y - yc) < math.hypot(xd - xc, yd - yc):
                    lo = mid
                else:
                    hi = mid
            xu, yu = xc + (xd - xc) * lo, yc + (yd - yc) * lo
            du, dv = _affine_flow(xu, yu)
            ex, ey = distort(xu + du, yu + dv)
            assert abs(out["flow"][yd, xd, 0] - (ex - xd)) < 0.02
            assert abs(out["flow"][yd, xd, 1] - (ey - yd)) < 0.02
            checked += 1
    assert checked > 100


def test_numpy_and_cpp_paths_agree(tiny_release, monkeypatch):
    assert io.native_available(), "build the flowscape_native extension (CMake) for this test"
    rng = np.random.default_rng(3)
    image = rng.uniform(0, 255, (40, 50, 3)).astype(np.float32)
    mx = rng.uniform(-3, 53, (30, 20)).astype(np.float32)
    my = rng.uniform(0, 39, (30, 20)).astype(np.float32)
    for wrap in (False, True):
        native = augment.remap(image, mx, my, wrap)
        numpy_path = augment._remap_numpy(image, mx, my, wrap)
        assert np.abs(native - numpy_path).max() < 1e-3
    png = next((tiny_release / "sequences" / "map00_seq00" / "erp" / "color").iterdir())
    assert (io.read_png(png) == flowscape.read_image(png)).all()
    sample = _pinhole_sample()
    with_cpp = augment.fda_e(sample, np.random.default_rng(5))
    monkeypatch.setattr(io, "_native", None)
    with_numpy = augment.fda_e(sample, np.random.default_rng(5))
    assert (with_cpp["valid"] == with_numpy["valid"]).all()
    assert np.abs(with_cpp["flow"] - with_numpy["flow"]).max() < 1e-3
    assert np.abs(with_cpp["img1"] - with_numpy["img1"]).max() < 1e-2


def test_a_dataloader_with_workers_iterates_a_tiny_release(tiny_release):
    dataset = flowscape.FlowScape(tiny_release, "train",
                                  transform=flowscape.Augmentation(fda="e", crop=(24, 48)))
    loader = torch.utils.data.DataLoader(dataset, batch_size=2, num_workers=2, shuffle=True)
    batches = 0
    for img1, img2, flow, valid in loader:
        assert img1.shape[1:] == (3, 24, 48) and flow.shape[1:] == (2, 24, 48)
        assert torch.isfinite(flow).all() and valid.max() <= 1
        batches += 1
    assert batches == math.ceil(len(dataset) / 2)
    test = flowscape.FlowScape(tiny_release, "test")
    train_scenes = {i["meta"]["scene"] for i in dataset.items}
    assert not train_scenes & {i["meta"]["scene"] for i in test.items}
    fog = flowscape.FlowScape(tiny_release, "train", weathers=["fog"], extras=("meta",))
    assert all(item[4]["meta"]["weather"] == "fog" for item in fog)
    tree = flowscape.FlowScape(tiny_release / "panoflow", "test")  # JPEG images
    assert len(tree) == len(test) and tree[0][0].shape == (3, 32, 64)


def test_a_panorama_shift_and_a_cyclic_crop_keep_the_flow_right(yaw_release):
    sample = flowscape.FlowScape(yaw_release, "train").sample(0)
    shifted = augment.horizontal_shift(sample, 17)
    assert (shifted["flow"] == np.roll(sample["flow"], 17, axis=1)).all()
    crop = augment.cyclic_crop(sample, 16, 40, np.random.default_rng(2))
    assert crop["img1"].shape == (16, 40, 3)
    u = 64 * 3 / 360
    assert np.abs(crop["flow"][..., 0] - u).max() < 1e-3
    jittered = augment.photometric_jitter(sample, np.random.default_rng(1))
    assert jittered["img1"].shape == sample["img1"].shape
    assert (jittered["flow"] == sample["flow"]).all()


def test_epe_statistics_and_weather_rows(yaw_release):
    gt = np.zeros((2, 4, 4), np.float32)
    pred = gt.copy()
    pred[0, 0, :] = 2  # four pixels 2 px off, twelve exact
    stats = flowscape.epe_stats(pred, gt)
    assert stats["epe"] == pytest.approx(0.5) and stats["px1"] == pytest.approx(0.75)
    assert stats["px3"] == 1.0 and stats["pixels"] == 16
    dataset = flowscape.FlowScape(yaw_release, "test", extras=("meta",))
    u = 64 * 3 / 360

    def model(img1, img2):  # a perfect "network" for a pure yaw
        return torch.stack([torch.full(img1.shape[2:], u), torch.zeros(img1.shape[2:])])[None].repeat(img1.shape[0], 1, 1, 1)

    rows = flowscape.evaluate_by_weather(model, dataset)
    assert rows["all"]["epe"] < 1e-3 and rows["sunny"]["px1"] == 1.0
    cyclic = flowscape.evaluate_by_weather(model, dataset, cyclic=True)
    assert cyclic["all"]["epe"] < 1e-3


def test_bad_input_is_named(tmp_path, yaw_release):
    with pytest.raises(ValueError, match="splits/train.txt nor panoflow"):
        flowscape.FlowScape(tmp_path, "train")
    with pytest.raises(ValueError, match="split must be"):
        flowscape.FlowScape(yaw_release, "validation")
    with pytest.raises(ValueError, match="splits/val.txt: missing"):  # no hash split made
        flowscape.FlowScape(yaw_release, "val")
    bad = tmp_path / "cut.flo"
    bad.write_bytes((yaw_release / "sequences/map00_seq00/erp/flow/000000.flo").read_bytes()[:100])
    with pytest.raises(ValueError, match="cut.flo: truncated"):
        flowscape.read_flo(bad)
    with pytest.raises(ValueError, match="not a PNG"):
        io.read_png(bad)


def test_the_package_installs_offline_and_reads_a_release_without_the_extension(tmp_path,
                                                                              tiny_release):
    source = os.path.join(os.path.dirname(__file__), "..", "..", "python")
    venv = tmp_path / "venv"
    subprocess.run(["/usr/bin/python3", "-m", "venv", "--system-site-packages", str(venv)], check=True)
    subprocess.run([str(venv / "bin" / "pip"), "install", "-q", "--no-build-isolation", "--no-index",
                    os.path.abspath(source)], check=True, capture_output=True, cwd=tmp_path,
                   env=dict(os.environ, FLOWSCAPE_PURE_PYTHON="1"))  # the numpy fallback alone
    script = """import sys, flowscape
print(flowscape.__file__)
assert not flowscape.native_available()
tree = flowscape.FlowScape(sys.argv[1] + "/panoflow", "train")   # JPEG images
release = flowscape.FlowScape(sys.argv[1], "train", exclude_sky=True)   # PNG images
img1, img2, flow, valid = tree[0]
assert img1.shape[0] == 3 and float(img1.max()) > 0
assert release[0][0].shape == img1.shape
layout = flowscape.ReleaseLayout(sys.argv[1])
depth = flowscape.read_image(layout.frame_file("map00_seq00", "depth", 0))   # EXR
assert depth.dtype.name == "float32" and depth.shape[2] == 1
"""
    found = subprocess.run([str(venv / "bin" / "python"), "-c", script, str(tiny_release)],
                           capture_output=True, text=True, cwd=tmp_path,
                           env={"PATH": os.environ.get("PATH", "")})
    assert found.returncode == 0, found.stderr
    assert str(venv) in found.stdout


def test_pillow_and_openimageio_read_what_the_extension_reads(tiny_release, monkeypatch):
    pytest.importorskip("PIL")
    pytest.importorskip("OpenImageIO")
    layout = flowscape.ReleaseLayout(tiny_release)
    files = [layout.frame_file("map00_seq00", kind, 0) for kind in ("color", "instance", "valid")]
    files.append(str(tiny_release / "panoflow/train") + "/" + next(
        os.path.join(w, "img", s, f) for w in os.listdir(tiny_release / "panoflow/train")
        for s in os.listdir(tiny_release / "panoflow/train" / w / "img")
        for f in sorted(os.listdir(tiny_release / "panoflow/train" / w / "img" / s))))
    expected = [flowscape.read_image(f) for f in files]
    monkeypatch.setattr(io, "_native", None)
    for f, e in zip(files, expected):
        assert np.array_equal(io.read_image(f), e)  # python3-openimageio
    monkeypatch.setitem(__import__("sys").modules, "OpenImageIO", None)
    for f, e in zip(files, expected):
        got = io.read_image(f)  # Pillow
        assert got.dtype == e.dtype and got.shape == e.shape
        if not f.endswith(".jpg"):  # JPEG decoders may round differently
            assert np.array_equal(got, e)


def test_the_layout_in_the_manifest_finds_every_file_of_a_release(tiny_release):
    layout = flowscape.ReleaseLayout(tiny_release)
    faces = layout.layout["faces"]
    assert faces == ["front", "right", "back", "left", "up", "down"]
    found = set()
    for kind in layout.kinds:
        for frame in filter(lambda f: layout.has_frame(kind, f, 3), range(3)):
            for face in [None] + faces:
                path = layout.frame_file("map00_seq00", kind, frame, face)
                assert os.path.isfile(path), path
                found.add(os.path.relpath(path, tiny_release))
    manifest = json.load(open(tiny_release / "manifest.json"))
    listed = {p for p in manifest["files"] if p.startswith("sequences/map00_seq00/")
              and not p.endswith("meta.json")}
    assert found == listed  # the layout names exactly the files the release has
    assert layout.meta("map00_seq00")["frames"] == 3


def test_a_release_without_a_layout_is_named(tmp_path, yaw_release):
    with pytest.raises(ValueError, match="manifest.json: missing"):
        flowscape.ReleaseLayout(tmp_path)
    (tmp_path / "manifest.json").write_text('{"generator": "flowscape 0.6", "files": {}}')
    with pytest.raises(ValueError, match="manifest.json: no layout"):
        flowscape.FlowScape(tmp_path, "train")


@pytest.fixture(scope="session")
def all_kinds_release(tmp_path_factory):
    # 128 high: bilinear sampling of the backward flow at the forward targets (the agreement test)
    # errs by about 1/height of the flow's curvature; at 32 rows the ego's 11 m/s made it 1e-3 px
    out = tmp_path_factory.mktemp("all_kinds")
    subprocess.run([f"{BIN}/gen_flowscape", "--maps", "1", "--sequences-per-map", "2",
                    "--frames", "4", "--resolution", "128", "--face-size", "64", "--spp", "1",
                    "--vehicles", "30", "--pedestrians", "10", "--outputs", "all",
                    "--flow-gaps", "1,2", "--out", str(out)], check=True, capture_output=True)
    subprocess.run([f"{BIN}/flowscape_split", str(out)], check=True, capture_output=True)
    return out


def _bilinear(image, x, y, wrap):
    """image H x W x C at continuous (x, y), pixel centres at +0.5; columns wrap on a panorama."""
    h, w = image.shape[:2]
    x, y = x - 0.5, np.clip(y - 0.5, 0, h - 1)
    x0, y0 = np.floor(x).astype(int), np.minimum(y.astype(int), h - 1)
    fx, fy = (x - x0)[..., None], (y - y0)[..., None]
    y1 = np.minimum(y0 + 1, h - 1)
    col = (lambda c: c % w) if wrap else (lambda c: np.clip(c, 0, w - 1))
    return ((1 - fy) * ((1 - fx) * image[y0, col(x0)] + fx * image[y0, col(x0 + 1)])
            + fy * ((1 - fx) * image[y1, col(x0)] + fx * image[y1, col(x0 + 1)]))


def test_every_kind_of_the_layout_is_there_as_its_row_says(all_kinds_release):
    layout = flowscape.ReleaseLayout(all_kinds_release)
    assert layout.conventions["flow"]["value"] == "target - source"
    assert {"flow_backward_gap2", "valid_gap2", "scene_flow", "normal", "normal_shading"} <= \
        set(layout.kinds)
    for kind, row in layout.kinds.items():
        for frame in range(4):
            path = layout.frame_file("map00_seq00", kind, frame)
            assert os.path.isfile(path) == layout.has_frame(kind, frame, 4), path
            if not os.path.isfile(path):
                continue
            data = io.read_flo(path) if row["resampling"] == "flow" else io.read_image(path)
            assert data.shape == (128, 256, row["channels"]), kind
    depth = io.read_image(layout.frame_file("map00_seq00", "depth", 1))[..., 0]
    sky = np.isinf(depth)
    assert sky.any() and not sky.all()
    for kind in ("normal", "normal_shading", "scene_flow"):
        value = io.read_image(layout.frame_file("map00_seq00", kind, 1))
        assert np.isnan(value[sky]).all() and np.isfinite(value[~sky]).all(), kind
    normal = io.read_image(layout.frame_file("map00_seq00", "normal", 1))[~sky]
    assert np.abs(np.linalg.norm(normal, axis=1) - 1).max() < 1e-5
    # the ERP camera frame is the front face's (x right, y down, z forward): the ground below the
    # rig faces up, -y; and a normal faces the camera: against the pixel's ray
    h, w = depth.shape
    y, x = np.mgrid[0:h, 0:w] + 0.5
    phi, theta = 2 * np.pi * x / w - np.pi, np.pi * y / h - np.pi / 2
    ray = np.stack([np.cos(theta) * np.sin(phi), np.sin(theta), np.cos(theta) * np.cos(phi)], 2)
    assert (np.einsum("ij,ij->i", normal, ray[~sky]) <= 1e-6).all()
    bottom = io.read_image(layout.frame_file("map00_seq00", "normal", 1))[-1]
    assert np.median(bottom[:, 1]) < -0.99
    # the shading normal: unit length too, bent away from the geometric one by smoothing and the
    # textures' bumps on some surfaces, equal to it on flat untextured ones
    shading = io.read_image(layout.frame_file("map00_seq00", "normal_shading", 1))[~sky]
    assert np.abs(np.linalg.norm(shading, axis=1) - 1).max() < 1e-5
    bent = np.linalg.norm(shading - normal, axis=1) > 1e-3
    assert 0 < bent.mean() < 1


def test_forward_and_backward_flow_of_a_release_agree(all_kinds_release):
    layout = flowscape.ReleaseLayout(all_kinds_release)
    for gap, back_kind, valid_kind in ((1, "flow_backward", "valid_backward"),
                                       (2, "flow_backward_gap2", "valid_backward_gap2")):
        forward = io.read_flo(layout.frame_file("map00_seq00", "flow" if gap == 1 else "flow_gap2", 0))
        visible = io.read_image(layout.frame_file("map00_seq00", "valid" if gap == 1 else "valid_gap2", 0))[..., 0]
        backward = io.read_flo(layout.frame_file("map00_seq00", back_kind, gap))
        visible_back = io.read_image(layout.frame_file("map00_seq00", valid_kind, gap))[..., 0]
        h, w = visible.shape
        y, x = np.mgrid[0:h, 0:w] + 0.5
        qx, qy = np.mod(x + forward[..., 0], w), y + forward[..., 1]
        inside = (qy >= 0) & (qy < h)
        both = (visible > 0) & inside
        both[both] &= visible_back[np.minimum(qy[both].astype(int), h - 1), qx[both].astype(int)] > 0
        back = _bilinear(backward, qx, qy, True)
        du = forward[..., 0] + back[..., 0]
        du -= w * np.round(du / w)
        error = np.hypot(du, forward[..., 1] + back[..., 1])[both]
        assert both.sum() > 0.5 * h * w
        assert np.median(error) < 1e-3  # exact away from edges (bilinear sampling of B)


def test_the_plugin_hands_out_the_kinds_asked_for(all_kinds_release):
    data = flowscape.FlowScape(all_kinds_release, "train", outputs=("flow_backward", "normal"))
    plain = flowscape.FlowScape(all_kinds_release, "train")
    img1, img2, flow, valid, extra = data[0]
    assert flow.shape == plain[0][2].shape  # the RAFT tuple is unchanged
    assert extra["flow_backward"].shape == (2, 128, 256) and extra["normal"].shape == (3, 128, 256)
    meta = data.sample(0)["meta"]
    layout = flowscape.ReleaseLayout(all_kinds_release)
    expected = io.read_flo(layout.frame_file(meta["scene"], "flow_backward", meta["frame"] + 1))
    assert np.array_equal(extra["flow_backward"].numpy(), expected.transpose(2, 0, 1))
    # a gap-2 flow exists for frames 0 and 1 of 4 only: fewer items
    gap = flowscape.FlowScape(all_kinds_release, "train", outputs=("flow_gap2",))
    assert 0 < len(gap) < len(plain)
    with pytest.raises(ValueError, match="the release has no flow_gap4"):
        flowscape.FlowScape(all_kinds_release, "train", outputs=("flow_gap4",))


def test_the_plugin_reads_the_final_pass_as_sintel_passes_are_read(all_kinds_release,
                                                                    tiny_release):
    clean = flowscape.FlowScape(all_kinds_release, "train")
    final = flowscape.FlowScape(all_kinds_release, "train", pass_name="final")
    assert len(final) == len(clean)
    c, f = clean.sample(0), final.sample(0)
    assert f["img1"].shape == c["img1"].shape and not np.array_equal(f["img1"], c["img1"])
    assert np.array_equal(f["flow"], c["flow"]) and np.array_equal(f["valid"], c["valid"])
    with pytest.raises(ValueError, match="no final pass"):
        flowscape.FlowScape(tiny_release, "train", pass_name="final")
    # gt_quality scores either pass; the PanoFlow tree takes either
    scored = subprocess.run([f"{BIN}/gt_quality", str(all_kinds_release), "-q", "--pass", "final"],
                            check=True, capture_output=True, text=True).stdout
    assert any(line.split()[:2] == ["all", "4"] or line.startswith("all ") for line in scored.splitlines())
    refused = subprocess.run([f"{BIN}/gt_quality", str(tiny_release), "-q", "--pass", "final"],
                             capture_output=True, text=True)
    assert refused.returncode == 1 and "no final pass" in refused.stderr
    subprocess.run([f"{BIN}/flowscape_split", str(all_kinds_release), "--pass", "final"],
                   check=True, capture_output=True)
    tree = json.load(open(os.path.join(all_kinds_release, "panoflow", "flowscape.json")))
    assert tree["pass"] == "final"
    subprocess.run([f"{BIN}/flowscape_split", str(all_kinds_release)], check=True,
                   capture_output=True)  # back to the clean tree the other tests read

    with pytest.raises(ValueError, match="pass_name must be"):
        flowscape.FlowScape(all_kinds_release, "train", pass_name="albedo")


def _boxes_by_numpy(ids, panorama):
    """[id, x0, y0, x1, y1] per instance, x1/y1 exclusive; on a panorama the fewest columns."""
    boxes = []
    w = ids.shape[1]
    for value in np.unique(ids):
        if value == 0:
            continue
        rows, cols = np.nonzero(ids == value)
        used = np.zeros(w, bool)
        used[cols] = True
        x0, x1 = int(cols.min()), int(cols.max()) + 1
        if panorama and not used.all():
            # the longest run of empty columns round the circle is left out
            empty = ~np.concatenate([used, used])
            best, start = (0, 0), None
            for i, e in enumerate(empty):
                if e and start is None:
                    start = i
                if (not e or i == len(empty) - 1) and start is not None:
                    end = i if not e else i + 1
                    if end - start > best[1] - best[0] and end - start <= w:
                        best = (start, end)
                    start = None
            x0, x1 = best[1] % w, best[0] % w or w
        elif panorama:
            x0, x1 = 0, w
        boxes.append([int(value), x0, int(rows.min()), x1, int(rows.max()) + 1])
    return boxes


def test_meta_json_boxes_and_actors_match_the_files(all_kinds_release):
    layout = flowscape.ReleaseLayout(all_kinds_release)
    for scene in ("map00_seq00", "map00_seq01"):
        meta = layout.meta(scene)
        for view, face in [("erp", None)] + [(f"cube/{f}", f) for f in layout.layout["faces"]]:
            for frame in range(4):
                ids = io.read_image(layout.frame_file(scene, "instance", frame, face))[..., 0]
                assert meta["boxes_2d"][view][frame] == _boxes_by_numpy(ids, face is None)
        poses = [np.vstack([np.array(p).reshape(3, 4), [0, 0, 0, 1]]) for p in meta["poses"]]
        # 20 vehicles, 20 pedestrians, and the riders and parked cars the city made
        assert len(meta["actors"]) == len(meta["city"]["actors"]) >= 40
        for actor in meta["actors"]:
            for frame in range(4):
                centre = np.array(actor["centre"][frame] + [1])
                in_rig = np.linalg.inv(poses[frame]) @ centre
                assert np.abs(in_rig[:3] - actor["centre_rig"][frame]).max() < 1e-5
        front = meta["views"]["cube/front"]
        assert front["K"] == [[32.0, 0, 31.5], [0, 32.0, 31.5], [0, 0, 1]]
    card = (all_kinds_release / "README.md").read_text()
    assert "| scene_flow | all but the last 1 |" in card and "bytes per frame" in card


@pytest.fixture(scope="session")
def rig_releases(tmp_path_factory):
    """One small release per rig preset, split."""
    out = {}
    for rig in ("fisheye", "woodscape", "pal", "dual-fisheye"):
        root = tmp_path_factory.mktemp(rig)
        subprocess.run([f"{BIN}/gen_flowscape", "--rig", rig, "--maps", "1",
                        "--sequences-per-map", "2", "--frames", "2", "--resolution", "48",
                        "--spp", "1", "--vehicles", "20", "--pedestrians", "10",
                        "--out", str(root)], check=True, capture_output=True)
        subprocess.run([f"{BIN}/flowscape_split", str(root)], check=True, capture_output=True)
        out[rig] = root
    return out


def rig_cameras(rig_releases):
    """(rig, layout, camera, view record, numpy model) of every camera of the rig releases' first
    sequence."""
    for rig, root in rig_releases.items():
        layout = flowscape.ReleaseLayout(root)
        meta = layout.meta("map00_seq00")
        for camera in layout.cameras:
            view = meta["views"][f"cameras/{camera}"]
            yield rig, layout, camera, view, flowscape.camera_model(view)


def test_numpy_models_round_trip_and_mask_what_the_renderer_masks(rig_releases):
    for rig, layout, camera, view, model in rig_cameras(rig_releases):
        h, w = view["height"], view["width"]
        y, x = np.mgrid[0:h, 0:w] + 0.5
        pixels = np.stack([x, y], -1)
        rays, seen = model.unproject(pixels)
        back, ok = model.project(rays)
        own = seen & ok
        if view["model"] == "dual_fisheye":  # the ring past 90 degrees belongs to the other lens
            own &= np.where(x >= h, -rays[..., 2], rays[..., 2]) >= 0
        assert np.abs(back - pixels)[own].max() < 1e-6, (rig, camera)
        depth = io.read_image(layout.frame_file("map00_seq00", "depth", 0, camera=camera))[..., 0]
        # what the renderer leaves unseen (NaN depth) is what the numpy model cannot unproject
        assert np.array_equal(np.isnan(depth), ~seen), (rig, camera)


def test_a_static_point_seen_off_the_rig_origin_flows_to_its_projection_by_both_poses(rig_releases):
    """The flow of a camera mounted off the rig's origin follows from its own pose at both times
    (meta.json's views[...]["poses"], camera -> world), the point from its depth and ray."""
    for rig in ("woodscape", "pal", "fisheye"):
        root = rig_releases[rig]
        layout = flowscape.ReleaseLayout(root)
        meta = layout.meta("map00_seq00")
        for camera in layout.cameras:
            view = meta["views"][f"cameras/{camera}"]
            model = flowscape.camera_model(view)
            pose0, pose1 = flowscape.camera_poses(view)[:2]
            depth = io.read_image(layout.frame_file("map00_seq00", "depth", 0, camera=camera))[..., 0]
            ids = io.read_image(layout.frame_file("map00_seq00", "instance", 0, camera=camera))[..., 0]
            flow = io.read_flo(layout.frame_file("map00_seq00", "flow", 0, camera=camera))
            h, w = depth.shape
            y, x = np.mgrid[0:h, 0:w] + 0.5
            rays, seen = model.unproject(np.stack([x, y], -1))
            static = seen & np.isfinite(depth) & (ids == 0) & (np.abs(flow[..., 0]) < 1e9)
            point = rays * depth[..., None]  # camera frame at frame 0
            world = point @ pose0[:3, :3].T + pose0[:3, 3]
            then = (world - pose1[:3, 3]) @ pose1[:3, :3]  # camera frame at frame 1
            target, ok = model.project(then)
            use = static & ok
            assert use.sum() > 0.3 * h * w, (rig, camera)
            error = np.hypot(x + flow[..., 0] - target[..., 0], y + flow[..., 1] - target[..., 1])
            assert np.median(error[use]) < 1e-4 and error[use].max() < 1e-2, (rig, camera)
            offset = np.array(view["translation_in_rig"])
            if rig != "fisheye":
                assert np.linalg.norm(offset) > 0.4  # really off the origin


def test_the_plugin_reads_every_camera_and_gt_quality_scores_them(rig_releases):
    root = rig_releases["woodscape"]
    layout = flowscape.ReleaseLayout(root)
    assert layout.cameras == ["front", "rear", "mirror_left", "mirror_right"]
    for camera in layout.cameras:
        data = flowscape.FlowScape(root, "train", camera=camera)
        img1, img2, flow, valid = data[0]
        assert img1.shape[1:] == flow.shape[1:] and float(valid.mean()) > 0.3
    with pytest.raises(ValueError, match="its rig has no ERP; pick a camera"):
        flowscape.FlowScape(root, "train")
    report = subprocess.run([f"{BIN}/gt_quality", "-q", str(root)], check=True,
                            capture_output=True, text=True).stdout
    for camera in layout.cameras:
        assert f"/map00_seq00/{camera}" in report or f"/map00_seq01/{camera}" in report


def test_a_release_in_the_carla_0914_table_names_its_sky_and_drops_it(tmp_path):
    """--classes carla-0.9.14: the manifest names the table; the plugin drops its sky (11)."""
    subprocess.run([f"{BIN}/gen_flowscape", "--maps", "1", "--sequences-per-map", "2", "--frames",
                    "2", "--resolution", "32", "--no-cube", "--spp", "1", "--vehicles", "20",
                    "--pedestrians", "10", "--classes", "carla-0.9.14", "--out", str(tmp_path)],
                   check=True, capture_output=True)
    subprocess.run([f"{BIN}/flowscape_split", str(tmp_path)], check=True, capture_output=True)
    semantic = flowscape.ReleaseLayout(tmp_path).conventions["semantic"]
    assert semantic["table"] == "carla-0.9.14" and semantic["sky"] == 11
    assert semantic["names"][13] == "Rider" and semantic["names"][29] == "EgoVehicle"
    data = flowscape.FlowScape(tmp_path, "train", exclude_sky=True, extras=("semantic",))
    _, _, _, valid, extra = data[0]
    ids = extra["semantic"].numpy()
    assert (valid.numpy()[ids == 11] == 0).all() and (ids == 11).any()
    layout = flowscape.ReleaseLayout(tmp_path)
    for scene in ("map00_seq00", "map00_seq01"):
        semantic_ids = io.read_image(layout.frame_file(scene, "semantic", 0))[..., 0]
        depth = io.read_image(layout.frame_file(scene, "depth", 0))[..., 0]
        assert set(np.unique(semantic_ids[np.isinf(depth)]).tolist()) == {11}
        assert semantic_ids.max() <= 29


TRAIN_SMALL = os.path.join(os.path.dirname(__file__), "..", "..", "python", "examples", "train_small.py")


def _train_small(release, tmp_path, *options):
    return subprocess.run(["/usr/bin/python3", TRAIN_SMALL, str(release), "--workers", "0",
                           "--checkpoints", str(tmp_path / "checkpoints"), *options],
                          capture_output=True, text=True, timeout=300, env=os.environ)


def test_train_small_refuses_a_batch_larger_than_the_train_split(tiny_release, tmp_path):
    """Issue 35, point 3: it hung forever (drop_last left no batch)."""
    run = _train_small(tiny_release, tmp_path, "--batch", "100000", "--steps", "2")
    assert run.returncode != 0
    assert "fewer than --batch 100000" in run.stderr


def test_train_small_runs_fewer_steps_than_a_report(tiny_release, tmp_path):
    """Issue 35, point 3: --steps below 25 crashed at the end (no loss reported yet)."""
    run = _train_small(tiny_release, tmp_path, "--batch", "1", "--steps", "3", "--eval-every", "0")
    assert run.returncode == 0, run.stderr
    assert "step    3  EPE loss" in run.stdout
    assert os.path.isfile(tmp_path / "checkpoints" / "latest.pt")


def test_meta_batches_with_the_default_collate(tiny_release):
    """Issue 35, point 4: extras=("meta",) crashed torch's default collate (None in meta)."""
    dataset = flowscape.FlowScape(tiny_release, "train", extras=("meta",))
    batch = next(iter(torch.utils.data.DataLoader(dataset, batch_size=2)))
    meta = batch[4]["meta"]
    assert meta["face"] == ["", ""] and meta["camera"] == ["", ""]
    assert len(meta["scene"]) == 2 and meta["frame"].shape == (2,)


def test_the_default_augmentation_keeps_a_fisheye_view_whole(rig_releases):
    """Issue 35, point 5: the default Augmentation rolled and cyclically cropped fisheye images
    (the image circle cut, the seam mid-image); now it follows the view (no roll, plain crops)."""
    plain = flowscape.FlowScape(rig_releases["fisheye"], "train", camera="front", as_tensors=False)
    augmented = flowscape.FlowScape(rig_releases["fisheye"], "train", camera="front",
                                    as_tensors=False,
                                    transform=flowscape.Augmentation(jitter=False, seed=3))
    before, after = plain[0], augmented[0]
    assert before["panorama"] is False
    # no shift, no crop asked: the same image, circle and all
    assert np.array_equal(before["img1"], after["img1"])
    cropped = flowscape.Augmentation(jitter=False, seed=3, crop=(32, 32))(plain.sample(0))
    h, w = before["flow"].shape[:2]
    # a plain crop: a window of the image (found at one offset), never wrapped round
    window = cropped["img1"]
    assert any(np.array_equal(window, before["img1"][y:y + 32, x:x + 32])
               for y in range(h - 31) for x in range(w - 31))


def test_bad_roots_faces_and_missing_files_are_named_when_the_dataset_is_made(
        tiny_release, rig_releases, tmp_path):
    """Issue 35, point 8: these failed mid-epoch with a raw FileNotFoundError, or blamed the split."""
    with pytest.raises(ValueError, match="no-such-release: no such folder"):
        flowscape.FlowScape(tmp_path / "no-such-release", "train")
    with pytest.raises(ValueError, match="has no cube faces .*pick one with camera="):
        flowscape.FlowScape(rig_releases["fisheye"], "train", faces=("front",))
    import shutil
    damaged = tmp_path / "damaged"
    shutil.copytree(tiny_release, damaged, symlinks=True)
    scene, frame = open(damaged / "splits" / "train.txt").readline().split()
    image = damaged / "sequences" / scene / "erp" / "color" / f"{int(frame) + 1:06d}.png"
    image.unlink()
    with pytest.raises(ValueError, match=f"{image}: missing"):
        flowscape.FlowScape(damaged, "train")


def test_evaluation_refuses_to_wrap_a_fisheye_view_round(rig_releases):
    """Issue 35, point 5: RaftAdapter's circular padding and evaluate_by_weather(cyclic=True) wrapped
    fisheye and pinhole views round (the seam mid-image); now refused before anything runs, and
    panorama=False evaluates them."""
    test = flowscape.FlowScape(rig_releases["fisheye"], "test", camera="front", extras=("meta",))

    class Zero(torch.nn.Module):
        def forward(self, img1, img2, iters=1, test_mode=True):
            return torch.zeros(img1.shape[0], 2, *img1.shape[2:])

    with pytest.raises(ValueError, match="not a panorama"):
        flowscape.evaluate_by_weather(flowscape.RaftAdapter(Zero()), test)
    with pytest.raises(ValueError, match="cyclic=True turns the image round"):
        flowscape.evaluate_by_weather(flowscape.RaftAdapter(Zero(), panorama=False), test, cyclic=True)
    rows = flowscape.evaluate_by_weather(flowscape.RaftAdapter(Zero(), panorama=False), test)
    assert rows["all"]["pixels"] > 0


def test_a_one_sequence_release_splits_into_all_and_loads(tmp_path):
    """Issue 35, point 6: flowscape_split refused a release of one sequence, and the plugin had no
    split to read it with."""
    root = tmp_path / "one"
    subprocess.run([f"{BIN}/gen_flowscape", "--maps", "1", "--sequences-per-map", "1", "--frames",
                    "3", "--resolution", "16", "--face-size", "8", "--spp", "1", "--vehicles", "4",
                    "--pedestrians", "2", "--out", str(root)], check=True, capture_output=True)
    done = subprocess.run([f"{BIN}/flowscape_split", str(root)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert "splits/all.txt only" in done.stderr
    assert (root / "splits" / "all.txt").read_text().split("\n")[:2] == ["map00_seq00 000000",
                                                                         "map00_seq00 000001"]
    assert len(flowscape.FlowScape(root, "all")) == 2
    with pytest.raises(ValueError, match="split='all' reads its pairs"):
        flowscape.FlowScape(root, "train")


def test_a_hash_split_with_a_validation_side_loads(tiny_release, tmp_path):
    """Issue 35, point 6: no validation split, no split that survives a growing release."""
    import shutil
    root = tmp_path / "hashed"
    shutil.copytree(tiny_release, root, symlinks=True)
    done = subprocess.run([f"{BIN}/flowscape_split", str(root), "--method", "hash", "--test-share",
                           "0.3", "--val-share", "0.4", "--seed", "1", "--no-panoflow"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    sides = {name: {line.split()[0] for line in (root / "splits" / f"{name}.txt").read_text().split("\n")
                    if line} for name in ("train", "test", "val")}
    assert sides["val"] and not (sides["val"] & (sides["train"] | sides["test"]))
    assert len(flowscape.FlowScape(root, "val")) == 2 * len(sides["val"])  # 3 frames: 2 pairs
    wrong = subprocess.run([f"{BIN}/flowscape_split", str(root), "--val-share", "0.4"],
                           capture_output=True, text=True)
    assert wrong.returncode == 2 and "belong to --method hash" in wrong.stderr


def test_a_crop_or_a_scale_of_a_camera_view_comes_with_its_adjusted_camera(rig_releases,
                                                                           tiny_release):
    """Issue 35: crops of a fisheye view returned no camera. crop_view and scale_view give the
    record of the cropped or resized image: every direction is seen where the image operation
    moved it, (u - x0, v - y0) and (sx u, sy v) in continuous coordinates, for every model."""
    rng = np.random.default_rng(5)
    for rig, layout, camera, view, model in rig_cameras(rig_releases):
        w, h = view["width"], view["height"]
        pixels = np.stack([rng.uniform(0, w, 400), rng.uniform(0, h, 400)], -1)
        rays, seen = model.unproject(pixels)
        where, ok = model.project(rays[seen])
        resized = flowscape.camera_model(flowscape.scale_view(view, 2 * w, 2 * h))
        moved, ok2 = resized.project(rays[seen])
        assert ok2[ok].all() and np.abs(moved[ok] - 2 * where[ok]).max() < 1e-6, rig
        if view["model"] == "dual_fisheye":
            with pytest.raises(ValueError, match="not a dual_fisheye image"):
                flowscape.crop_view(view, 3, 5, w - 8, h - 8)
            continue
        cropped = flowscape.camera_model(flowscape.crop_view(view, 3, 5, w - 8, h - 8))
        moved, ok2 = cropped.project(rays[seen])
        assert np.abs(moved[ok] - (where[ok] - [3, 5])).max() < 1e-6, rig

    # through the dataset: Augmentation's crop hands out the cropped fisheye's camera
    dataset = flowscape.FlowScape(rig_releases["fisheye"], "train", camera="front",
                                  as_tensors=False, extras=("calibration",))
    sample = dataset.sample(0)
    view = json.loads(sample["calibration"])
    assert view["model"] == "kannala_brandt" and "poses" not in view
    cropped = flowscape.Augmentation(jitter=False, seed=3, crop=(32, 40))(sample)
    after = json.loads(cropped["calibration"])
    assert (after["width"], after["height"]) == (40, 32)
    shift = np.subtract(view["parameters"]["K"], after["parameters"]["K"])[:2, 2]
    x0, y0 = int(shift[0]), int(shift[1])
    assert np.array_equal(cropped["img1"], sample["img1"][y0:y0 + 32, x0:x0 + 40])
    with pytest.raises(ValueError, match="a mirrored image has no camera"):
        flowscape.flip(sample)
    batch = next(iter(torch.utils.data.DataLoader(
        flowscape.FlowScape(rig_releases["fisheye"], "train", camera="front",
                            extras=("calibration",)), batch_size=2)))
    assert isinstance(batch[4]["calibration"][0], str)
    with pytest.raises(ValueError, match="calibration' is for cameras and cube faces"):
        flowscape.FlowScape(tiny_release, "train", extras=("calibration",))
    faces = flowscape.FlowScape(tiny_release, "train", faces=("left",), extras=("calibration",),
                                as_tensors=False)
    assert json.loads(faces.sample(0)["calibration"])["model"] == "pinhole"


@pytest.mark.parametrize("flow_format,extension", [("kitti-png", ".png"), ("half-exr", ".exr")])
def test_a_release_with_compressed_flow_trains_on_the_same_flow_to_its_precision(
        tiny_release, tmp_path, flow_format, extension):
    out = tmp_path / flow_format
    config = json.loads((tiny_release / "config.json").read_text())
    subprocess.run([f"{BIN}/gen_flowscape", "--maps", "1", "--frames", "3", "--resolution", "32",
                    "--face-size", "16", "--spp", "1", "--vehicles", "10", "--pedestrians", "5",
                    "--flow-format", flow_format, "--out", str(out)], check=True,
                   capture_output=True)
    subprocess.run([f"{BIN}/flowscape_split", str(out)], check=True, capture_output=True)
    assert json.loads((out / "config.json").read_text()) == {**config, "flow_format": flow_format}
    layout = flowscape.ReleaseLayout(out)
    assert layout.frame_file("map00_seq00", "flow", 0).endswith("000000" + extension)
    stored = flowscape.FlowScape(out, "train")
    floats = flowscape.FlowScape(tiny_release, "train")
    assert len(stored) == len(floats) > 0
    for k in range(len(floats)):
        mine, exact = stored.sample(k), floats.sample(k)
        both = (mine["valid"] > 0) & (exact["valid"] > 0)
        assert both.sum() > 0.9 * (exact["valid"] > 0).sum()
        error = np.abs(mine["flow"] - exact["flow"])[both]
        # KITTI: 1/64 px steps, rounded; half: 11 significant bits, rounded
        bound = (1 / 128 if flow_format == "kitti-png"
                 else np.abs(exact["flow"])[both] * 2.0 ** -11 + 1e-7)
        assert (error <= bound + 1e-6).all()
