"""The plugin's C++ extension on a release's files, for memcheck_test.sh under valgrind: every
array it hands to Python is saved to a file, so that memcheck checks each of its bytes (write(2))
as well as whatever numpy branches on.

    memcheck_native.py OUT IMAGE...
"""
import sys

import numpy as np

import flowscape_native as native

arrays = {}
for k, path in enumerate(sys.argv[2:]):
    image = native.read_image(path)
    height, width = image.shape[:2]
    y, x = np.mgrid[0:height, 0:width].astype(np.float32)
    arrays[f"image{k}"] = image
    arrays[f"remapped{k}"] = native.remap(image.astype(np.float32), x + 0.3, y - 0.6, True)
    arrays[f"clamped{k}"] = native.remap(image.astype(np.float32), x * 1.5, y + 2.2, False)
np.savez(sys.argv[1], **arrays)
