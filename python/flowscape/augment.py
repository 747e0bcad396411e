"""Augmentations for panoramic flow training: the PanoFlow paper's flow distortion augmentation
(FDA-R, radial, Eq. 5; FDA-E, equirectangular, Eq. 6-8), with the flow vectors corrected by
moving both ends of every vector through the distortion (Eq. 4); cyclic crops and horizontal
shifts for ERP (exact for 360-degree flow); photometric jitter.

Samples are dicts of numpy arrays: 'img1', 'img2' (H x W x 3 float32), 'flow' (H x W x 2),
'valid' (H x W float32), optionally 'semantic'. Sampling is bilinear at 1/32-pixel steps (as
OpenCV's remap, which the C++ extension uses; the numpy fallback does the same arithmetic)."""
import json
import math

import numpy as np

from . import io as _io
from .cameras import crop_view, scale_view


def remap(image, map_x, map_y, wrap=False):
    """image sampled bilinearly at (map_x, map_y) (index coordinates, pixel centres at integers);
    columns wrap when `wrap`; taps outside the image read 0 (check the coordinates for validity)."""
    image = np.ascontiguousarray(image, dtype=np.float32)
    map_x = np.ascontiguousarray(map_x, dtype=np.float32)
    map_y = np.ascontiguousarray(map_y, dtype=np.float32)
    if _io._native is not None:
        return _io._native.remap(image, map_x, map_y, bool(wrap))
    return _remap_numpy(image, map_x, map_y, wrap)


def _remap_numpy(image, map_x, map_y, wrap):
    h, w = image.shape[:2]
    qx = np.rint(map_x.astype(np.float64) * 32).astype(np.int64)
    qy = np.rint(map_y.astype(np.float64) * 32).astype(np.int64)
    x0, y0 = qx >> 5, qy >> 5
    fx = ((qx & 31) / 32.0).astype(np.float32)
    fy = ((qy & 31) / 32.0).astype(np.float32)
    planes = image if image.ndim == 3 else image[..., None]

    def tap(x, y):
        if wrap:
            x, y = np.mod(x, w), np.mod(y, h)
            return planes[y, x]
        inside = (x >= 0) & (x < w) & (y >= 0) & (y < h)
        value = planes[np.clip(y, 0, h - 1), np.clip(x, 0, w - 1)]
        return np.where(inside[..., None], value, 0)

    fx, fy = fx[..., None], fy[..., None]
    out = ((1 - fx) * (1 - fy) * tap(x0, y0) + fx * (1 - fy) * tap(x0 + 1, y0) +
           (1 - fx) * fy * tap(x0, y0 + 1) + fx * fy * tap(x0 + 1, y0 + 1)).astype(np.float32)
    return out if image.ndim == 3 else out[..., 0]


def _inside(map_x, map_y, w, h, wrap=False):
    ok = (map_y >= 0) & (map_y <= h - 1)
    return ok if wrap else ok & (map_x >= 0) & (map_x <= w - 1)


def _resample(sample, map_x, map_y, valid_here, flow):
    """The sample seen through a coordinate map, with a new flow and validity."""
    h, w = sample["flow"].shape[:2]
    valid_src = remap(sample["valid"], map_x, map_y) > 0.999
    valid = valid_here & valid_src & np.isfinite(flow).all(axis=2)
    out = dict(sample)
    for key in ("img1", "img2"):
        out[key] = remap(sample[key], map_x, map_y) * valid_here[..., None]
    out["flow"] = np.where(valid[..., None], flow, 0).astype(np.float32)
    out["valid"] = valid.astype(np.float32)
    if "semantic" in sample:  # nearest
        xi = np.clip(np.rint(map_x), 0, w - 1).astype(np.int64)
        yi = np.clip(np.rint(map_y), 0, h - 1).astype(np.int64)
        out["semantic"] = sample["semantic"][yi, xi]
    return out


def radial_forward(x, y, xc, yc, k2, k4):
    """FDA-R's F_r (Eq. 5): x_d = c + (x_u - c) (1 + k2 r^2 + k4 r^4), r = |x_u - c|."""
    dx, dy = x - xc, y - yc
    r2 = dx * dx + dy * dy
    s = 1 + k2 * r2 + k4 * r2 * r2
    return xc + dx * s, yc + dy * s


def radial_inverse(xd, yd, xc, yc, k2, k4):
    """x_u with F_r(x_u) = x_d (Newton on the radius); NaN where F_r is not invertible."""
    dx, dy = xd - xc, yd - yc
    rd = np.hypot(dx, dy)
    r = rd.copy()
    for _ in range(8):
        f = r * (1 + k2 * r ** 2 + k4 * r ** 4) - rd
        df = 1 + 3 * k2 * r ** 2 + 5 * k4 * r ** 4
        r = r - f / np.where(df > 1e-3, df, np.nan)
    scale = np.where(rd > 0, r / np.where(rd > 0, rd, 1), 1)
    return xc + dx * scale, yc + dy * scale


def fda_r(sample, rng, k2=None, k4=None):
    """Radial flow distortion (FDA-R): barrel or pincushion about the image centre,
    k2 ~ U(-1e-6, 1e-6), k4 ~ U(-1e-14, 1e-14) unless given."""
    _refuse_calibration(sample, "a radially distorted image")
    h, w = sample["flow"].shape[:2]
    k2 = rng.uniform(-1e-6, 1e-6) if k2 is None else k2
    k4 = rng.uniform(-1e-14, 1e-14) if k4 is None else k4
    xc, yc = (w - 1) / 2, (h - 1) / 2
    yd, xd = np.mgrid[0:h, 0:w].astype(np.float64)
    xu, yu = radial_inverse(xd, yd, xc, yc, k2, k4)
    here = np.isfinite(xu) & np.isfinite(yu) & _inside(xu, yu, w, h)
    xu, yu = np.where(here, xu, -10), np.where(here, yu, -10)
    v = remap(sample["flow"], xu, yu).astype(np.float64)
    ex, ey = radial_forward(xu + v[..., 0], yu + v[..., 1], xc, yc, k2, k4)
    flow = np.stack([ex - xd, ey - yd], axis=2)
    return _resample(sample, xu, yu, here, flow)


def _rotation(theta_y, theta_z):
    cy, sy, cz, sz = math.cos(theta_y), math.sin(theta_y), math.cos(theta_z), math.sin(theta_z)
    ry = np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    rz = np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]])
    return rz @ ry


def fda_e(sample, rng, theta_y=None, theta_z=None, fov_h=None, fov_v=None):
    """Equirectangular flow distortion (FDA-E): the (pinhole) sample seen as part of an ERP of the
    same size: ERP pixel -> unit sphere (Eq. 6) -> rotation R_z R_y (Eq. 7) -> perspective image
    with fields of view fov_h, fov_v (Eq. 8). theta_y ~ U(0, pi), theta_z ~ U(0, 2 pi),
    fov ~ U(pi/3, 2 pi/3) unless given. Pixels that see nothing of the source become invalid;
    the flow comes out as 360-degree ERP flow."""
    h, w = sample["flow"].shape[:2]
    theta_y = rng.uniform(0, math.pi) if theta_y is None else theta_y
    theta_z = rng.uniform(0, 2 * math.pi) if theta_z is None else theta_z
    fov_h = rng.uniform(math.pi / 3, 2 * math.pi / 3) if fov_h is None else fov_h
    fov_v = rng.uniform(math.pi / 3, 2 * math.pi / 3) if fov_v is None else fov_v
    rot = _rotation(theta_y, theta_z)
    fx, fy = w / (2 * math.tan(fov_h / 2)), h / (2 * math.tan(fov_v / 2))
    ye, xe = np.mgrid[0:h, 0:w].astype(np.float64) + 0.5  # ERP pixel centres
    polar, azimuth = math.pi * ye / h, 2 * math.pi * xe / w
    sphere = np.stack([np.sin(polar) * np.cos(azimuth), np.sin(polar) * np.sin(azimuth),
                       np.cos(polar)], axis=-1) @ rot.T
    front = sphere[..., 0] > 1e-6
    safe = np.where(front, sphere[..., 0], 1)
    xs = fx * sphere[..., 1] / safe + w / 2 - 0.5  # perspective index coordinates
    ys = fy * sphere[..., 2] / safe + h / 2 - 0.5
    here = front & _inside(xs, ys, w, h)
    xs, ys = np.where(here, xs, -10), np.where(here, ys, -10)
    v = remap(sample["flow"], xs, ys).astype(np.float64)
    ray = np.stack([np.ones_like(xs), (xs + v[..., 0] + 0.5 - w / 2) / fx,
                    (ys + v[..., 1] + 0.5 - h / 2) / fy], axis=-1) @ rot  # back to the sphere
    ray /= np.linalg.norm(ray, axis=-1, keepdims=True)
    end_y = h * np.arccos(np.clip(ray[..., 2], -1, 1)) / math.pi
    end_x = np.mod(w * np.arctan2(ray[..., 1], ray[..., 0]) / (2 * math.pi), w)
    u = np.mod(end_x - xe + w / 2, w) - w / 2  # the shortest way round
    flow = np.stack([u, end_y - ye], axis=2)
    return _resample(sample, xs, ys, here, flow)


def cyclic_crop(sample, height, width, rng):
    """A height x width crop whose columns may wrap round the ERP seam."""
    h, w = sample["flow"].shape[:2]
    if height > h or width > w:
        raise ValueError(f"crop {height}x{width} is larger than the {h}x{w} sample")
    y0, x0 = int(rng.integers(0, h - height + 1)), int(rng.integers(0, w))
    columns = (x0 + np.arange(width)) % w
    return {k: (v[y0:y0 + height][:, columns] if isinstance(v, np.ndarray) else v)
            for k, v in sample.items()}


def _refuse_calibration(sample, what):
    if "calibration" in sample:
        raise ValueError(f"{what} has no camera of the view's model: leave it out with "
                         "extras=('calibration',)")


def _with_calibration(out, sample, change, *arguments):
    """`out` with the sample's camera record (extras 'calibration': meta.json's view as JSON)
    changed as its image was (cameras.crop_view, scale_view)."""
    if "calibration" in sample:
        out["calibration"] = json.dumps(change(json.loads(sample["calibration"]), *arguments))
    return out


def crop(sample, height, width, rng):
    """A height x width crop inside the image (pinhole views: no wrapping)."""
    h, w = sample["flow"].shape[:2]
    if height > h or width > w:
        raise ValueError(f"crop {height}x{width} is larger than the {h}x{w} sample")
    y0, x0 = int(rng.integers(0, h - height + 1)), int(rng.integers(0, w - width + 1))
    out = {k: (v[y0:y0 + height, x0:x0 + width] if isinstance(v, np.ndarray) else v)
           for k, v in sample.items()}
    return _with_calibration(out, sample, crop_view, x0, y0, width, height)


def scale(sample, scale_x, scale_y):
    """The sample resized by (scale_x, scale_y), rounded to whole pixels (RAFT's scale and stretch).
    A point at x (pixel centres at integers) lands at (x + 0.5) s - 0.5, so every flow vector is
    multiplied by s; images and flow are sampled bilinearly at the new pixels' pre-images (exact
    for flow that is affine between pixels), validity only where all four taps were valid."""
    h, w = sample["flow"].shape[:2]
    new_h, new_w = max(1, int(round(h * scale_y))), max(1, int(round(w * scale_x)))
    sx, sy = new_w / w, new_h / h
    ys, xs = np.mgrid[0:new_h, 0:new_w].astype(np.float64)
    map_x = np.clip((xs + 0.5) / sx - 0.5, 0, w - 1)
    map_y = np.clip((ys + 0.5) / sy - 0.5, 0, h - 1)
    out = _resample(sample, map_x, map_y, np.ones((new_h, new_w), bool),
                    remap(sample["flow"], map_x, map_y) * np.float32([sx, sy]))
    return _with_calibration(out, sample, scale_view, new_w, new_h)


def flip(sample, horizontal=True):
    """The sample mirrored left-right (u negated) or upside down (v negated): x -> W - 1 - x takes
    a target x + u to (W - 1 - x) - u, so the mirrored field is exact. Right for 360-degree ERP
    flow too (a mirrored sphere)."""
    _refuse_calibration(sample, "a mirrored image")
    axis, component = (1, 0) if horizontal else (0, 1)
    out = {k: (np.ascontiguousarray(np.flip(v, axis)) if isinstance(v, np.ndarray) else v)
           for k, v in sample.items()}
    out["flow"] = out["flow"].copy()
    out["flow"][..., component] *= -1
    return out


def horizontal_shift(sample, shift):
    """The panorama turned by `shift` columns: 360-degree flow values stay exactly right."""
    return {k: (np.roll(v, shift, axis=1) if isinstance(v, np.ndarray) else v)
            for k, v in sample.items()}


def photometric_jitter(sample, rng, brightness=0.3, contrast=0.3, saturation=0.3, gamma=0.15):
    """The same random brightness, contrast, saturation and gamma change on both images."""
    b = 1 + rng.uniform(-brightness, brightness)
    c = 1 + rng.uniform(-contrast, contrast)
    s = 1 + rng.uniform(-saturation, saturation)
    g = 1 + rng.uniform(-gamma, gamma)
    out = dict(sample)
    for key in ("img1", "img2"):
        image = sample[key] / 255.0
        grey = image.mean(axis=2, keepdims=True)
        image = grey + s * (image - grey)
        image = image.mean() + c * (image - image.mean())
        image = np.clip(b * image, 0, 1) ** g
        out[key] = (image * 255).astype(np.float32)
    return out


class Augmentation:
    """A transform for FlowScape(transform=...), RAFT's FlowAugmentor and the paper's FDA:
    FDA ('r', 'e' or None) with `fda_probability`; with `scale` = (min, max) log2 factors a
    random scale (probability `scale_probability`), stretched by up to 2^+-`stretch` per axis with
    probability `stretch_probability`; flips left-right / upside down with `h_flip` / `v_flip`
    probability; for panoramas a random horizontal shift; a crop to `crop` (height, width; cyclic
    on panoramas), the sample first scaled up when it is smaller than the crop; photometric jitter.
    panorama=None (the default) follows the sample's view (FlowScape states it: the ERP and
    equirectangular cameras wrap round, cube faces, pinholes and fisheyes do not); False: no shift,
    plain crops (the image circle and the seam stay where they are); True: always a panorama.
    Each DataLoader worker draws its own numbers (seeded from torch's worker seed)."""

    def __init__(self, fda=None, fda_probability=0.5, crop=None, shift=True, jitter=True, seed=None,
                 scale=None, scale_probability=0.8, stretch=0.2, stretch_probability=0.8,
                 h_flip=0.0, v_flip=0.0, panorama=None):
        if fda not in (None, "r", "e"):
            raise ValueError(f"fda must be None, 'r' or 'e', not {fda!r}")
        self.fda, self.fda_probability, self.crop = fda, fda_probability, crop
        self.shift, self.jitter, self.seed, self.rng = shift, jitter, seed, None
        self.scale, self.scale_probability = scale, scale_probability
        self.stretch, self.stretch_probability = stretch, stretch_probability
        self.h_flip, self.v_flip, self.panorama = h_flip, v_flip, panorama

    def _scale_factors(self, h, w, rng):
        sx = sy = 1.0
        if self.scale and rng.uniform() < self.scale_probability:
            sx = sy = 2 ** rng.uniform(*self.scale)
            if rng.uniform() < self.stretch_probability:
                sx *= 2 ** rng.uniform(-self.stretch, self.stretch)
                sy *= 2 ** rng.uniform(-self.stretch, self.stretch)
        if self.crop and (h * sy < self.crop[0] or w * sx < self.crop[1]):
            needed = max((self.crop[0] + 8) / h, (self.crop[1] + 8) / w)  # RAFT's margin
            sx, sy = max(sx, needed), max(sy, needed)
        return sx, sy

    def __call__(self, sample):
        if self.rng is None:
            seed = self.seed
            if seed is None:
                import torch
                seed = torch.initial_seed()
            self.rng = np.random.default_rng(seed)
        rng = self.rng
        if self.fda and rng.uniform() < self.fda_probability:
            sample = (fda_r if self.fda == "r" else fda_e)(sample, rng)
        sx, sy = self._scale_factors(*sample["flow"].shape[:2], rng)
        if (sx, sy) != (1.0, 1.0):
            sample = scale(sample, sx, sy)
        if rng.uniform() < self.h_flip:
            sample = flip(sample, horizontal=True)
        if rng.uniform() < self.v_flip:
            sample = flip(sample, horizontal=False)
        panorama = sample.get("panorama", True) if self.panorama is None else self.panorama
        if self.shift and panorama:
            sample = horizontal_shift(sample, int(rng.integers(0, sample["flow"].shape[1])))
        if self.crop:
            sample = (cyclic_crop if panorama else crop)(sample, self.crop[0], self.crop[1], rng)
        if self.jitter:
            sample = photometric_jitter(sample, rng)
        return sample
