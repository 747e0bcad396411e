#!/usr/bin/python3
"""The README's clean / final / rolling-shutter figure from a release of docs/rigs/side_rolling_shutter.json.

Usage: scripts/figure_rolling_shutter.py RELEASE OUT.png   (frame 0 of map00_seq00; flowviz beside it in build/apps)
"""
import pathlib
import subprocess
import sys
import tempfile

import cv2
import numpy as np


def label(image, text):
    image = image.copy()
    cv2.rectangle(image, (0, 0), (image.shape[1], 18), (0, 0, 0), -1)
    cv2.putText(image, text, (4, 13), cv2.FONT_HERSHEY_SIMPLEX, 0.42, (255, 255, 255), 1, cv2.LINE_AA)
    return image


def main(release, out):
    cameras = pathlib.Path(release) / "sequences/map00_seq00/cameras"
    flowviz = pathlib.Path(__file__).resolve().parent.parent / "build/apps/flowviz"
    with tempfile.TemporaryDirectory() as tmp:
        flows = {}
        for camera in ("global", "rolling"):
            png = pathlib.Path(tmp) / f"{camera}.png"
            subprocess.run([str(flowviz), str(cameras / camera / "flow/000000.flo"), "--wheel", "middlebury",
                            "--scale", "40", "-o", str(png)], check=True, capture_output=True)
            flows[camera] = cv2.imread(str(png))
    read = lambda camera, kind: cv2.imread(str(cameras / camera / kind / "000000.png"))
    tiles = [label(read("global", "color"), "clean, global shutter"),
             label(read("global", "final"), "final: blur, exposure, noise, lens"),
             label(read("rolling", "color"), "rolling shutter, 60 ms row readout"),
             label(read("rolling", "final"), "rolling shutter, final pass"),
             label(flows["global"], "flow, global shutter"),
             label(flows["rolling"], "flow, rolling shutter (exact)")]
    cv2.imwrite(out, np.vstack([np.hstack(tiles[:3]), np.hstack(tiles[3:])]))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
