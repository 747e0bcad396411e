"""Writes kitti_drive.txt: 6 s of a car driving straight ahead at 8 m/s with a gentle lane sway
and road bumps, as KITTI odometry's poses/XX.txt holds them (10 Hz, each line the 3 x 4 camera ->
world matrix row-major; the world is the first camera's frame: x right, y down, z forward). The
project's own data (CC BY 4.0); docs/bring_your_own.md replays it with
examples/scenarios/kitti_drive.json.

    /usr/bin/python3 examples/poses/make_kitti_drive.py
"""
import math
from pathlib import Path

lines = []
for k in range(60):
    t = k / 10
    x, y, z = 0.15 * math.sin(0.8 * t), 0.02 * math.sin(3 * t), 8 * t  # right, down, forward
    heading = math.atan2(0.15 * 0.8 * math.cos(0.8 * t), 8)  # along the velocity, about y
    c, s = math.cos(heading), math.sin(heading)
    rows = [[c, 0, s, x], [0, 1, 0, y], [-s, 0, c, z]]
    lines.append(" ".join(f"{v:.9e}" for row in rows for v in row))
Path(__file__).with_name("kitti_drive.txt").write_text("\n".join(lines) + "\n")
