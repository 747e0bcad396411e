"""Independent flow-file writer and reader (numpy + zlib, no FlowScape code) for the C++ tests.

    flow_files.py write DIR   writes reference and corrupt files into DIR
    flow_files.py check DIR   checks DIR/ours.flo and DIR/ours_kitti.png written by FlowScape

Reference field (width 37, height 23): u = (x - 2y) / 4, v = (3x + y) / 8 - 5; pixel (0, 0) of the
.flo is unknown (1e10); in the KITTI file a pixel is valid where (x + y) % 3 != 0.
"""
import struct
import sys
import zlib
from pathlib import Path

import numpy as np

WIDTH, HEIGHT = 37, 23


def reference():
    y, x = np.mgrid[0:HEIGHT, 0:WIDTH].astype(np.float32)
    u = (x - 2 * y) / 4
    v = (3 * x + y) / 8 - 5
    valid = ((x.astype(int) + y.astype(int)) % 3 != 0).astype(np.uint16)
    return u, v, valid


def flo_bytes(u, v, magic=202021.25, width=WIDTH, height=HEIGHT):
    header = np.array([magic], "<f4").tobytes() + np.array([width, height], "<i4").tobytes()
    return header + np.stack([u, v], axis=-1).astype("<f4").tobytes()


def png_chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def png16_bytes(rgb):
    height, width, _ = rgb.shape
    rows = b"".join(b"\x00" + row.astype(">u2").tobytes() for row in rgb)
    return (b"\x89PNG\r\n\x1a\n"
            + png_chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 16, 2, 0, 0, 0))
            + png_chunk(b"IDAT", zlib.compress(rows))
            + png_chunk(b"IEND", b""))


def kitti_rgb(u, v, valid):
    rgb = np.zeros((HEIGHT, WIDTH, 3), np.uint16)
    rgb[..., 0] = np.where(valid, u * 64 + 2**15, 0)
    rgb[..., 1] = np.where(valid, v * 64 + 2**15, 0)
    rgb[..., 2] = valid
    return rgb


def write(folder):
    u, v, valid = reference()
    u_flo, v_flo = u.copy(), v.copy()
    u_flo[0, 0] = v_flo[0, 0] = 1e10
    good = flo_bytes(u_flo, v_flo)
    files = {
        "numpy.flo": good,
        "numpy_kitti.png": png16_bytes(kitti_rgb(u, v, valid)),
        "truncated.flo": good[:-6],
        "header_only.flo": good[:7],
        "bad_magic.flo": flo_bytes(u, v, magic=1.0),
        "bad_size.flo": flo_bytes(u, v, width=-5),
        "trailing.flo": good + b"\x00" * 8,
        "nan.flo": flo_bytes(np.full_like(u, np.nan), v),
        "truncated_kitti.png": png16_bytes(kitti_rgb(u, v, valid))[:300],
        "eight_bit_kitti.png": png8_bytes(np.zeros((HEIGHT, WIDTH, 3), np.uint8)),
        "not_an_image.png": b"this is not a png file at all",
    }
    for name, data in files.items():
        (folder / name).write_bytes(data)


def png8_bytes(rgb):
    height, width, _ = rgb.shape
    rows = b"".join(b"\x00" + row.tobytes() for row in rgb)
    return (b"\x89PNG\r\n\x1a\n"
            + png_chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
            + png_chunk(b"IDAT", zlib.compress(rows))
            + png_chunk(b"IEND", b""))


def paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    return a if pa <= pb and pa <= pc else (b if pb <= pc else c)


def read_png16_rgb(path):
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "bad PNG signature"
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    width, height, depth, colour, _, _, interlace = header
    assert (depth, colour, interlace) == (16, 2, 0), f"expected 16-bit RGB, got {header}"
    raw, stride, bpp = zlib.decompress(idat), width * 6, 6
    previous, rows = bytearray(stride), []
    for r in range(height):
        kind, line = raw[r * (stride + 1)], bytearray(raw[r * (stride + 1) + 1:(r + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = previous[i], previous[i - bpp] if i >= bpp else 0
            predictor = [0, a, b, (a + b) // 2, paeth(a, b, c)][kind]
            line[i] = (line[i] + predictor) & 0xFF
        rows.append(bytes(line))
        previous = line
    return np.frombuffer(b"".join(rows), ">u2").reshape(height, width, 3)


def check(folder):
    u, v, valid = reference()
    raw = (folder / "ours.flo").read_bytes()
    assert np.frombuffer(raw[:4], "<f4")[0] == 202021.25, "bad magic"
    assert tuple(np.frombuffer(raw[4:12], "<i4")) == (WIDTH, HEIGHT), "bad size"
    flow = np.frombuffer(raw[12:], "<f4").reshape(HEIGHT, WIDTH, 2)
    assert np.array_equal(flow[..., 0], u) and np.array_equal(flow[..., 1], v), ".flo values differ"
    assert np.array_equal(read_png16_rgb(folder / "ours_kitti.png"), kitti_rgb(u, v, valid)), "KITTI PNG differs"


if __name__ == "__main__":
    {"write": write, "check": check}[sys.argv[1]](Path(sys.argv[2]))
