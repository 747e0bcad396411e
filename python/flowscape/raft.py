"""RAFT-style models in FlowScape's evaluation: RAFT pads its input to a multiple of 8 and returns
a list of refinements in training, (low-res, full-res) in test mode; evaluate_by_weather and
evaluate_cyclic want a callable img1, img2 -> B x 2 x H x W."""


class InputPadder:
    """Pads B x C x H x W tensors to a multiple of `divisor`: panoramas wrap round horizontally
    (the ERP's columns are cyclic) and repeat their edge rows; pinhole views repeat their edges.
    unpad() cuts a padded result back to H x W."""

    def __init__(self, shape, divisor=8, panorama=True):
        height, width = shape[-2:]
        self.pad_y, self.pad_x = (-height) % divisor, (-width) % divisor
        self.panorama = panorama

    def pad(self, *tensors):
        import torch.nn.functional as F
        top, left = self.pad_y // 2, self.pad_x // 2
        bottom, right = self.pad_y - top, self.pad_x - left
        out = []
        for t in tensors:
            if self.panorama:
                t = F.pad(t, (left, right, 0, 0), mode="circular")
                t = F.pad(t, (0, 0, top, bottom), mode="replicate")
            else:
                t = F.pad(t, (left, right, top, bottom), mode="replicate")
            out.append(t)
        return out

    def unpad(self, tensor):
        top, left = self.pad_y // 2, self.pad_x // 2
        height, width = tensor.shape[-2] - self.pad_y, tensor.shape[-1] - self.pad_x
        return tensor[..., top:top + height, left:left + width]


class RaftAdapter:
    """model(img1, img2, iters=iters, test_mode=True) as a callable img1, img2 -> flow: pads to a
    multiple of 8, takes the last (full-resolution) prediction of a list or tuple, unpads.

        evaluate_by_weather(RaftAdapter(raft, iters=32), test_set)

    panorama=False for views that do not wrap round (cube faces, pinholes, fisheyes: edges
    replicated); evaluate_by_weather refuses panorama=True on such a dataset.
    """

    def __init__(self, model, iters=32, divisor=8, panorama=True, test_mode=True):
        self.model, self.iters, self.divisor = model, iters, divisor
        self.panorama, self.test_mode = panorama, test_mode

    def __call__(self, img1, img2):
        padder = InputPadder(img1.shape, self.divisor, self.panorama)
        img1, img2 = padder.pad(img1, img2)
        out = self.model(img1, img2, iters=self.iters, test_mode=self.test_mode)
        if isinstance(out, (list, tuple)):
            out = out[-1]
        return padder.unpad(out)
