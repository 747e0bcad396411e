"""Every camera model of a FlowScape release in numpy: project (camera-frame directions -> pixels)
and unproject (pixels -> unit rays), read from a view of meta.json (`camera_model(meta["views"]
["cameras/front"])`). Written from the models' equations (docs/cameras.md), not from the C++.

Conventions: camera frame x right, y down, z forward; continuous pixel coordinates with pixel
(i, j)'s centre at (i + 0.5, j + 0.5); K and the PAL centre as OpenCV / OCamCalib write them (the
top-left pixel's centre at (0, 0)). Both functions return (values, valid): valid is False where
the model sees nothing (outside the image circle or annulus, beyond the field of view).
crop_view and scale_view give the record of a cropped or resized image (what Augmentation does
to a sample's 'calibration')."""
import copy

import numpy as np


def _solve_increasing(f, df, y, lo, hi, iterations=60):
    """Vectorised safeguarded Newton for f(x) = y with f increasing on [lo, hi]."""
    lo = np.broadcast_to(np.asarray(lo, float), y.shape).copy()
    hi = np.broadcast_to(np.asarray(hi, float), y.shape).copy()
    x = 0.5 * (lo + hi)
    for _ in range(iterations):
        value = f(x) - y
        lo = np.where(value < 0, x, lo)
        hi = np.where(value >= 0, x, hi)
        d = df(x)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = np.where(d > 0, x - value / d, 0.5 * (lo + hi))
        x = np.where((step > lo) & (step < hi), step, 0.5 * (lo + hi))
    return x


def _angles(d):
    d = np.asarray(d, float)
    r = np.hypot(d[..., 0], d[..., 1])
    return r, np.arctan2(r, d[..., 2])


class _Radial:
    """theta -> rho = g(theta); pixel = c + rho (fx x, fy y) / r."""

    def __init__(self, width, height, fx, fy, cx, cy, max_angle):
        self.width, self.height = width, height
        self.fx, self.fy, self.cx, self.cy, self.max_angle = fx, fy, cx, cy, max_angle

    def project(self, d):
        d = np.asarray(d, float)
        r, theta = _angles(d)
        valid = theta <= self.max_angle
        with np.errstate(divide="ignore", invalid="ignore"):
            scale = np.where(r > 0, self.g(theta) / r, 0)
        return np.stack([self.cx + self.fx * scale * d[..., 0],
                         self.cy + self.fy * scale * d[..., 1]], -1), valid

    def unproject(self, p):
        p = np.asarray(p, float)
        mx, my = (p[..., 0] - self.cx) / self.fx, (p[..., 1] - self.cy) / self.fy
        rho = np.hypot(mx, my)
        valid = rho <= self.g(self.max_angle)
        theta = _solve_increasing(self.g, self.dg, np.minimum(rho, self.g(self.max_angle)), 0,
                                  self.max_angle)
        with np.errstate(divide="ignore", invalid="ignore"):
            s = np.where(rho > 0, np.sin(theta) / rho, 1)
        return np.stack([s * mx, s * my, np.cos(theta)], -1), valid


class KannalaBrandt(_Radial):
    """OpenCV's cv::fisheye: theta_d = theta (1 + k1 theta^2 + k2 theta^4 + k3 theta^6 + k4 theta^8)."""

    def __init__(self, p, equidistant=False):
        K = np.asarray(p["K"], float)
        self.k = np.zeros(4) if equidistant else np.asarray(p["D"], float)
        super().__init__(p["width"], p["height"], K[0, 0], K[1, 1], K[0, 2] + 0.5, K[1, 2] + 0.5,
                         np.radians(p["max_angle_degrees"]))

    def g(self, t):
        t2 = t * t
        return t * (1 + t2 * (self.k[0] + t2 * (self.k[1] + t2 * (self.k[2] + t2 * self.k[3]))))

    def dg(self, t):
        t2 = t * t
        return 1 + t2 * (3 * self.k[0] + t2 * (5 * self.k[1] + t2 * (7 * self.k[2] + t2 * 9 * self.k[3])))


class WoodScape(_Radial):
    """rho = k1 theta + k2 theta^2 + k3 theta^3 + k4 theta^4 pixels; vertical times the aspect."""

    def __init__(self, p):
        self.k = np.asarray(p["k"], float)
        super().__init__(p["width"], p["height"], 1.0, p.get("aspect_ratio", 1.0),
                         p["width"] / 2 + p.get("cx_offset", 0.0),
                         p["height"] / 2 + p.get("cy_offset", 0.0),
                         np.radians(p["max_angle_degrees"]))

    def g(self, t):
        return t * (self.k[0] + t * (self.k[1] + t * (self.k[2] + t * self.k[3])))

    def dg(self, t):
        return self.k[0] + t * (2 * self.k[1] + t * (3 * self.k[2] + t * 4 * self.k[3]))


class DoubleSphere:
    """Usenko et al. 2018 (Eq. 40-51)."""

    def __init__(self, p):
        K = np.asarray(p["K"], float)
        self.width, self.height = p["width"], p["height"]
        self.fx, self.fy, self.cx, self.cy = K[0, 0], K[1, 1], K[0, 2] + 0.5, K[1, 2] + 0.5
        self.xi, self.alpha = p["xi"], p["alpha"]
        self.max_angle = np.radians(p["max_angle_degrees"])

    def project(self, d):
        d = np.asarray(d, float)
        x, y, z = d[..., 0], d[..., 1], d[..., 2]
        d1 = np.linalg.norm(d, axis=-1)
        shifted = self.xi * d1 + z
        d2 = np.sqrt(x * x + y * y + shifted * shifted)
        den = self.alpha * d2 + (1 - self.alpha) * shifted
        valid = np.arccos(np.clip(z / d1, -1, 1)) <= self.max_angle
        return np.stack([self.fx * x / den + self.cx, self.fy * y / den + self.cy], -1), valid

    def unproject(self, p):
        p = np.asarray(p, float)
        mx, my = (p[..., 0] - self.cx) / self.fx, (p[..., 1] - self.cy) / self.fy
        r2 = mx * mx + my * my
        a, xi = self.alpha, self.xi
        inside = np.ones_like(r2, bool) if a <= 0.5 else r2 <= 1 / (2 * a - 1)
        r2c = np.where(inside, r2, 0)
        mz = (1 - a * a * r2c) / (a * np.sqrt(1 - (2 * a - 1) * r2c) + 1 - a)
        k = (mz * xi + np.sqrt(mz * mz + (1 - xi * xi) * r2c)) / (mz * mz + r2c)
        ray = np.stack([k * mx, k * my, k * mz - xi], -1)
        ray /= np.linalg.norm(ray, axis=-1, keepdims=True)
        return ray, inside & (np.arccos(np.clip(ray[..., 2], -1, 1)) <= self.max_angle)


class DualFisheye:
    """Two equidistant lenses in one image: the left half looks along +z, the right along -z (its
    x mirrored); a direction goes to the lens whose axis is nearer."""

    def __init__(self, p):
        self.width, self.height = p["width"], p["height"]
        self.max_angle = np.radians(p["max_angle_degrees"])
        self.f = p.get("f", self.height / 2 / self.max_angle)

    def _centre_x(self, rear):
        return np.where(rear, 1.5, 0.5) * self.height

    def project(self, d):
        d = np.asarray(d, float)
        rear = d[..., 2] < 0
        own = np.where(rear[..., None], d * np.array([-1, 1, -1]), d)
        r, theta = _angles(own)
        with np.errstate(divide="ignore", invalid="ignore"):
            s = np.where(r > 0, self.f * theta / r, 0)
        return np.stack([self._centre_x(rear) + s * own[..., 0], self.height / 2 + s * own[..., 1]],
                        -1), np.ones(rear.shape, bool)

    def unproject(self, p):
        p = np.asarray(p, float)
        rear = p[..., 0] >= self.height
        mx, my = (p[..., 0] - self._centre_x(rear)) / self.f, (p[..., 1] - self.height / 2) / self.f
        theta = np.hypot(mx, my)
        with np.errstate(divide="ignore", invalid="ignore"):
            s = np.where(theta > 0, np.sin(theta) / theta, 1)
        own = np.stack([s * mx, s * my, np.cos(theta)], -1)
        return np.where(rear[..., None], own * np.array([-1, 1, -1]), own), theta <= self.max_angle


class PanoramicAnnular:
    """Scaramuzza's omnidirectional model (OCamCalib): m = A^-1 (pixel - centre) looks along
    (m_x, m_y, f(|m|)), f(rho) = a0 + a1 rho + ... + a4 rho^4; sees angles from the axis in
    [min_angle, max_angle]."""

    def __init__(self, p):
        self.width, self.height = p["width"], p["height"]
        self.centre = np.asarray(p["centre"], float) + 0.5
        c, d, e = p.get("affine", [1, 0, 0])
        self.A = np.array([[c, d], [e, 1.0]])
        self.a = np.asarray(p["polynomial"], float)
        self.lo, self.hi = np.radians(p["min_angle_degrees"]), np.radians(p["max_angle_degrees"])
        rho = np.linspace(0, 4 * max(self.width, self.height), 40001)
        angle = self._angle(rho)
        self.rho_lo = np.interp(self.lo, angle, rho) - 1
        self.rho_hi = np.interp(self.hi, angle, rho) + 1

    def _f(self, rho):
        return np.polyval(self.a[::-1], rho)

    def _angle(self, rho):
        return np.arctan2(rho, self._f(rho))

    def _angle_slope(self, rho):
        f, df = self._f(rho), np.polyval(np.polyder(self.a[::-1]), rho)
        return (f - rho * df) / (rho * rho + f * f)

    def unproject(self, p):
        m = (np.asarray(p, float) - self.centre) @ np.linalg.inv(self.A).T
        rho = np.linalg.norm(m, axis=-1)
        ray = np.concatenate([m, self._f(rho)[..., None]], -1)
        ray /= np.linalg.norm(ray, axis=-1, keepdims=True)
        theta = self._angle(rho)
        return ray, (theta >= self.lo) & (theta <= self.hi)

    def project(self, d):
        d = np.asarray(d, float)
        r, theta = _angles(d)
        valid = (theta >= self.lo) & (theta <= self.hi) & (r > 0)
        rho = _solve_increasing(self._angle, self._angle_slope, np.clip(theta, self.lo, self.hi),
                                self.rho_lo, self.rho_hi)
        with np.errstate(divide="ignore", invalid="ignore"):
            m = np.where(r[..., None] > 0, rho[..., None] / r[..., None] * d[..., :2], 0)
        return m @ self.A.T + self.centre, valid


class Pinhole:
    """K with OpenCV's radial-tangential distortion D = k1, k2, p1, p2, k3 (cv::projectPoints)."""

    def __init__(self, p):
        K = np.asarray(p["K"], float)
        self.width, self.height = p["width"], p["height"]
        self.fx, self.fy, self.cx, self.cy = K[0, 0], K[1, 1], K[0, 2] + 0.5, K[1, 2] + 0.5
        self.D = np.asarray(p.get("D", [0, 0, 0, 0, 0]), float)

    def _distort(self, x, y):
        k1, k2, p1, p2, k3 = self.D
        r2 = x * x + y * y
        k = 1 + r2 * (k1 + r2 * (k2 + r2 * k3))
        return (x * k + 2 * p1 * x * y + p2 * (r2 + 2 * x * x),
                y * k + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y)

    def project(self, d):
        d = np.asarray(d, float)
        z = d[..., 2]
        with np.errstate(divide="ignore", invalid="ignore"):
            xd, yd = self._distort(d[..., 0] / z, d[..., 1] / z)
        return np.stack([self.fx * xd + self.cx, self.fy * yd + self.cy], -1), z > 0

    def unproject(self, p, iterations=50):
        p = np.asarray(p, float)
        tx, ty = (p[..., 0] - self.cx) / self.fx, (p[..., 1] - self.cy) / self.fy
        x, y = tx.copy(), ty.copy()
        h = 1e-7
        for _ in range(iterations):  # Newton on the 2-D map, numerical Jacobian
            fx, fy = self._distort(x, y)
            ax, ay = self._distort(x + h, y)
            bx, by = self._distort(x, y + h)
            j11, j21, j12, j22 = (ax - fx) / h, (ay - fy) / h, (bx - fx) / h, (by - fy) / h
            det = j11 * j22 - j12 * j21
            ex, ey = fx - tx, fy - ty
            x, y = x - (j22 * ex - j12 * ey) / det, y - (-j21 * ex + j11 * ey) / det
        ray = np.stack([x, y, np.ones_like(x)], -1)
        fx, fy = self._distort(x, y)
        valid = np.hypot(fx - tx, fy - ty) < 1e-9
        return ray / np.linalg.norm(ray, axis=-1, keepdims=True), valid


class Equirectangular:
    """The ERP in the front face's camera frame (x right = rig -y, y down = rig -z, z = rig x)."""

    def __init__(self, width, height):
        self.width, self.height = width, height

    def unproject(self, p):
        p = np.asarray(p, float)
        phi = 2 * np.pi * p[..., 0] / self.width - np.pi
        theta = np.pi * p[..., 1] / self.height - np.pi / 2
        rig = np.stack([np.cos(theta) * np.cos(phi), -np.cos(theta) * np.sin(phi), -np.sin(theta)], -1)
        return np.stack([-rig[..., 1], -rig[..., 2], rig[..., 0]], -1), np.ones(phi.shape, bool)

    def project(self, d):
        d = np.asarray(d, float)
        rig = np.stack([d[..., 2], -d[..., 0], -d[..., 1]], -1)
        phi = np.arctan2(-rig[..., 1], rig[..., 0])
        theta = np.arctan2(-rig[..., 2], np.hypot(rig[..., 0], rig[..., 1]))
        return np.stack([(phi + np.pi) * self.width / (2 * np.pi),
                         (theta + np.pi / 2) * self.height / np.pi], -1), np.ones(phi.shape, bool)


def camera_model(view):
    """The model of a view of meta.json (an entry of meta["views"])."""
    model = view["model"]
    p = view.get("parameters", view)
    if model == "equirectangular":
        return Equirectangular(view.get("width", 2 * p["height"]), p["height"])
    models = {"pinhole": Pinhole, "kannala_brandt": KannalaBrandt, "woodscape": WoodScape,
              "double_sphere": DoubleSphere, "dual_fisheye": DualFisheye,
              "panoramic_annular": PanoramicAnnular}
    if model == "equidistant":
        return KannalaBrandt(p, equidistant=True)
    if model not in models:
        raise ValueError(f"unknown camera model {model!r}")
    return models[model](p)


def camera_poses(view):
    """The view's camera -> world poses per frame, 4 x 4 (meta.json: 3 x 4 row-major)."""
    return [np.vstack([np.asarray(pose, float).reshape(3, 4), [0, 0, 0, 1]]) for pose in view["poses"]]


def _with_parameters(view, width, height, change):
    """A copy of the view record with the image size and `change(parameters)` applied."""
    out = copy.deepcopy(view)
    p = out.setdefault("parameters", out)
    change(p)
    p["width"], p["height"] = width, height
    out["width"], out["height"] = width, height
    out.pop("poses", None)
    return out


def crop_view(view, x0, y0, width, height):
    """The view record (meta.json's: model, parameters, width, height) of its image cropped to the
    width x height window whose top-left pixel is (x0, y0): every direction is seen at its old
    position minus (x0, y0). K's centre (OpenCV's convention, as meta.json states it) and the PAL's
    centre move by the window's corner, WoodScape's centre offset by the old centre's move against
    the new image centre; a dual fisheye's and a panorama's image has no cropped form (ValueError)."""
    model = view["model"]
    if model in ("dual_fisheye", "equirectangular"):
        raise ValueError(f"a crop of a {model} image is not a {model} image")

    def change(p):
        if "K" in p:
            K = np.asarray(p["K"], float)
            K[0, 2] -= x0
            K[1, 2] -= y0
            p["K"] = K.tolist()
        if model == "woodscape":  # centre = size / 2 + offset
            p["cx_offset"] = p.get("cx_offset", 0.0) + view["width"] / 2 - x0 - width / 2
            p["cy_offset"] = p.get("cy_offset", 0.0) + view["height"] / 2 - y0 - height / 2
        if model == "panoramic_annular":
            p["centre"] = [p["centre"][0] - x0, p["centre"][1] - y0]
    return _with_parameters(view, width, height, change)


def scale_view(view, width, height):
    """The view record for its image resized to width x height (as augment.scale resizes it: a
    point at continuous x lands at x * sx, sx = width / old width): every direction is seen at
    (sx u, sy v). The rules of docs/cameras.md "Scaling a camera" (renderer/lens.h scaled_lens):
    fx' = sx fx, cx' = sx (cx + 0.5) - 0.5; WoodScape's k by sx and aspect by sy / sx; the PAL's
    affine first row by sx / sy and a_i by sy^(1 - i); a dual fisheye only with sx = sy."""
    model = view["model"]
    sx, sy = width / view["width"], height / view["height"]
    if model == "equirectangular":
        raise ValueError("a resized panorama is described by its new size alone")

    def change(p):
        if "K" in p:
            K = np.asarray(p["K"], float)
            K[0, 0], K[1, 1] = K[0, 0] * sx, K[1, 1] * sy
            K[0, 2], K[1, 2] = (K[0, 2] + 0.5) * sx - 0.5, (K[1, 2] + 0.5) * sy - 0.5
            p["K"] = K.tolist()
        if model == "woodscape":
            p["k"] = [k * sx for k in p["k"]]
            p["aspect_ratio"] = p.get("aspect_ratio", 1.0) * sy / sx
            p["cx_offset"], p["cy_offset"] = p.get("cx_offset", 0.0) * sx, p.get("cy_offset", 0.0) * sy
        if model == "dual_fisheye":
            if abs(sx - sy) > 1e-12:
                raise ValueError("a dual fisheye scales by one factor (its width stays twice its height)")
            p["f"] = p["f"] * sy
        if model == "panoramic_annular":
            c, d, e = p.get("affine", [1.0, 0.0, 0.0])
            p["affine"] = [c * sx / sy, d * sx / sy, e]
            p["centre"] = [(p["centre"][0] + 0.5) * sx - 0.5, (p["centre"][1] + 0.5) * sy - 0.5]
            p["polynomial"] = [a * sy ** (1 - i) for i, a in enumerate(p["polynomial"])]
    return _with_parameters(view, width, height, change)


def camera_record(view):
    """The view record without its per-frame poses (what a sample's 'calibration' holds)."""
    return {k: v for k, v in view.items() if k != "poses"}
