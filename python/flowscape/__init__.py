"""FlowScape for PyTorch: the release's splits as torch Datasets, the PanoFlow paper's flow
distortion augmentations (FDA-R, FDA-E), panoramic crops and shifts, photometric jitter, and
EPE evaluation. Heavy per-pixel work runs in C++ (the `flowscape_native` extension built with the
toolkit) when it is importable, in numpy otherwise; both give the same results."""
__version__ = "0.20.0"  # the toolkit's (CMakeLists.txt project version, pyproject.toml)

from .io import read_flo, read_flow, write_flo, read_image, native_available
from .dataset import FlowScape, Concat, pole_mask
from .layout import ReleaseLayout
from .cameras import camera_model, camera_poses, crop_view, scale_view
from .augment import (fda_r, fda_e, cyclic_crop, crop, scale, flip, horizontal_shift,
                      photometric_jitter, Augmentation)
from .evaluate import epe_stats, evaluate_by_weather, evaluate_cyclic
from .raft import RaftAdapter, InputPadder

__all__ = ["FlowScape", "Concat", "pole_mask", "ReleaseLayout", "camera_model", "camera_poses", "crop_view", "scale_view", "read_flo", "read_flow", "write_flo", "read_image",
           "native_available", "fda_r", "fda_e", "cyclic_crop", "crop", "scale", "flip",
           "horizontal_shift", "photometric_jitter", "Augmentation", "epe_stats",
           "evaluate_by_weather", "evaluate_cyclic", "RaftAdapter", "InputPadder"]
