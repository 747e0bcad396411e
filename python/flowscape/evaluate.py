"""Evaluation: end-point error (EPE) and 1/3/5-px accuracies, per weather as in the PanoFlow
paper's Table III, and a CFE-style (cyclic flow estimation) wrapper for a model callable."""
import numpy as np


def epe_stats(pred, gt, valid=None):
    """EPE and the share of pixels with EPE below 1, 3 and 5 px, over valid pixels.
    Arrays (numpy or torch) ... x 2 x H x W or H x W x 2 (channel axis found by its size 2)."""
    pred, gt = _numpy(pred), _numpy(gt)
    axis = 1 if pred.ndim == 4 else (0 if pred.shape[0] == 2 else -1)
    error = np.linalg.norm(pred - gt, axis=axis)
    mask = np.ones_like(error, dtype=bool) if valid is None else _numpy(valid) > 0.5
    error = error[mask]
    if error.size == 0:
        return {"epe": float("nan"), "px1": float("nan"), "px3": float("nan"), "px5": float("nan"),
                "pixels": 0}
    return {"epe": float(error.mean()), "px1": float((error < 1).mean()),
            "px3": float((error < 3).mean()), "px5": float((error < 5).mean()),
            "pixels": int(error.size)}


def _numpy(x):
    if hasattr(x, "detach"):
        return x.detach().cpu().numpy()
    return np.asarray(x)


def evaluate_cyclic(model, img1, img2):
    """CFE-style 360-degree flow: the model's flow of the pair and of the pair turned by half a
    panorama (turned back), per pixel the one with the smaller horizontal magnitude, so motion
    across the seam is estimated where it is not cut. Tensors B x 3 x H x W."""
    import torch
    half = img1.shape[-1] // 2
    direct = model(img1, img2)
    turned = torch.roll(model(torch.roll(img1, half, -1), torch.roll(img2, half, -1)), -half, -1)
    take_turned = turned[:, :1].abs() < direct[:, :1].abs()
    return torch.where(take_turned, turned, direct)


def evaluate_by_weather(model, dataset, device="cpu", batch_size=4, cyclic=False):
    """EPE per weather and overall (pixel-weighted), like Table III. `dataset` must yield extras
    with 'meta' (FlowScape(..., extras=('meta',))). On a view that does not wrap round (cube faces,
    pinholes, fisheyes: the dataset's `panorama` is False) cyclic evaluation and a model padding
    circularly (RaftAdapter(panorama=True)) are refused before anything runs."""
    import torch
    if not getattr(dataset, "panorama", True):
        view = getattr(dataset, "faces", None) or getattr(dataset, "camera", None)
        if cyclic:
            raise ValueError(f"cyclic=True turns the image round, but the view {view!r} is not a "
                             "panorama")
        if getattr(model, "panorama", False) is True:
            raise ValueError(f"the model pads by wrapping the image round (RaftAdapter("
                             f"panorama=True)), but the view {view!r} is not a panorama: pass "
                             "panorama=False")
    loader = torch.utils.data.DataLoader(dataset, batch_size=batch_size,
                                         collate_fn=lambda items: items)
    sums = {}
    with torch.no_grad():
        for items in loader:
            img1 = torch.stack([i[0] for i in items]).to(device)
            img2 = torch.stack([i[1] for i in items]).to(device)
            pred = evaluate_cyclic(model, img1, img2) if cyclic else model(img1, img2)
            for k, item in enumerate(items):
                s = epe_stats(pred[k], item[2], item[3])
                for key in (item[4]["meta"]["weather"], "all"):
                    total = sums.setdefault(key, {"epe": 0.0, "px1": 0.0, "px3": 0.0, "px5": 0.0, "pixels": 0})
                    for name in ("epe", "px1", "px3", "px5"):
                        total[name] += s[name] * s["pixels"]
                    total["pixels"] += s["pixels"]
    return {key: {name: (t[name] / t["pixels"] if t["pixels"] else float("nan"))
                  for name in ("epe", "px1", "px3", "px5")} | {"pixels": t["pixels"]}
            for key, t in sums.items()}
