"""Flow and image files: Middlebury .flo in numpy; PNG/JPEG through the C++ extension (OpenImageIO),
with a pure numpy+zlib PNG decoder when the extension is not built."""
import struct
import zlib

import numpy as np

try:
    import flowscape_native as _native
except ImportError:  # the numpy fallback
    _native = None

UNKNOWN_FLOW = 1e10


def native_available():
    return _native is not None


def read_flo(path):
    """H x W x 2 float32; raises ValueError naming the file when it is not a whole .flo."""
    data = open(path, "rb").read()
    if len(data) < 12 or data[:4] != b"PIEH":
        raise ValueError(f"{path}: not a .flo file")
    width, height = struct.unpack("<ii", data[4:12])
    if width <= 0 or height <= 0 or len(data) != 12 + 8 * width * height:
        raise ValueError(f"{path}: truncated .flo data")
    return np.frombuffer(data, "<f4", offset=12).reshape(height, width, 2).astype(np.float32)


def read_flow(path):
    """H x W x 2 float32 flow of a release's flow file, by its extension: Middlebury .flo, KITTI's
    16-bit PNG (gen_flowscape --flow-format kitti-png) or EXR (half-exr); what the file marks
    unknown (KITTI's B = 0, an EXR's infinity) as UNKNOWN_FLOW, the .flo convention."""
    suffix = str(path).rsplit(".", 1)[-1].lower()
    if suffix == "flo":
        return read_flo(path)
    if suffix == "png":
        png = read_image(path)
        if png.dtype != np.uint16 or png.ndim != 3 or png.shape[2] != 3:
            raise ValueError(f"{path}: not a KITTI flow PNG (16-bit RGB)")
        flow = ((png[..., :2].astype(np.float64) - 32768.0) / 64.0).astype(np.float32)
        flow[png[..., 2] == 0] = UNKNOWN_FLOW
        return flow
    if suffix == "exr":
        exr = read_image(path)
        if exr.ndim != 3 or exr.shape[2] < 2:
            raise ValueError(f"{path}: a flow EXR needs 2 channels (u, v)")
        flow = exr[..., :2].astype(np.float32)
        if np.isnan(flow).any():
            raise ValueError(f"{path}: flow holds NaN")
        flow[np.isinf(flow)] = UNKNOWN_FLOW
        return flow
    raise ValueError(f"{path}: unknown flow file type (use .flo, .png or .exr)")


def write_flo(path, flow):
    flow = np.asarray(flow, dtype="<f4")
    with open(path, "wb") as out:
        out.write(b"PIEH" + struct.pack("<ii", flow.shape[1], flow.shape[0]) + flow.tobytes())


def _unfilter(raw, height, stride, bpp):
    """PNG scanline filters (None, Sub, Up, Average, Paeth) undone row by row."""
    out = np.zeros((height, stride), dtype=np.uint8)
    prev = np.zeros(stride, dtype=np.int32)
    pos = 0
    for y in range(height):
        kind = raw[pos]
        line = np.frombuffer(raw, np.uint8, stride, pos + 1).astype(np.int32)
        pos += stride + 1
        if kind == 0:
            row = line
        elif kind == 1:  # Sub: a running sum per byte of the pixel
            row = (np.cumsum(line.reshape(-1, bpp), axis=0) & 255).reshape(-1)
        elif kind == 2:
            row = (line + prev) & 255
        else:  # Average and Paeth depend on the byte just decoded: one by one (slow, exact)
            row = np.zeros(stride, dtype=np.int32)
            for x in range(stride):
                left = row[x - bpp] if x >= bpp else 0
                up = prev[x]
                if kind == 3:
                    predict = (left + up) >> 1
                else:
                    corner = prev[x - bpp] if x >= bpp else 0
                    p = left + up - corner
                    pa, pb, pc = abs(p - left), abs(p - up), abs(p - corner)
                    predict = left if pa <= pb and pa <= pc else (up if pb <= pc else corner)
                row[x] = (line[x] + predict) & 255
        out[y] = row
        prev = row
    return out


def read_png(path):
    """8/16-bit grey, grey+alpha, RGB or RGBA PNG, not interlaced -> H x W x C (uint8/uint16)."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path}: not a PNG file")
    pos, idat, header = 8, [], None
    while pos + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        chunk = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", chunk)
        elif kind == b"IDAT":
            idat.append(chunk)
        pos += 12 + length
    if header is None or not idat:
        raise ValueError(f"{path}: PNG without header or data")
    width, height, depth, color, _, _, interlace = header
    channels = {0: 1, 2: 3, 4: 2, 6: 4}.get(color)
    if channels is None or depth not in (8, 16) or interlace:
        raise ValueError(f"{path}: PNG kind not supported without the extension")
    try:
        raw = zlib.decompress(b"".join(idat))
    except zlib.error as error:
        raise ValueError(f"{path}: corrupt PNG data ({error})") from None
    bpp = channels * depth // 8
    if len(raw) != height * (width * bpp + 1):
        raise ValueError(f"{path}: truncated PNG data")
    rows = _unfilter(raw, height, width * bpp, bpp)
    if depth == 16:
        rows = rows.reshape(height, width * channels, 2)
        return (rows[..., 0].astype(np.uint16) << 8 | rows[..., 1]).reshape(height, width, channels)
    return rows.reshape(height, width, channels)


def _read_openimageio(path, oiio):
    image = oiio.ImageInput.open(str(path))
    if image is None:
        raise ValueError(f"{path}: {oiio.geterror().splitlines()[0] if oiio.geterror() else 'cannot read'}")
    try:
        spec = image.spec()
        pixels = image.read_image(spec.format)  # uint8, uint16 or float as stored
        if pixels is None:
            raise ValueError(f"{path}: {image.geterror().splitlines()[0]}")
    finally:
        image.close()
    pixels = np.asarray(pixels).reshape(spec.height, spec.width, spec.nchannels)
    return pixels.astype(np.float32) if pixels.dtype == np.float16 else pixels


def _read_pillow(path, pillow):
    try:
        with pillow.open(path) as image:
            pixels = np.asarray(image)
    except (OSError, ValueError) as error:
        raise ValueError(f"{path}: {error}") from None
    if pixels.dtype == np.int32:  # Pillow's mode "I" holds a 16-bit grey PNG
        pixels = pixels.astype(np.uint16)
    return pixels[..., None] if pixels.ndim == 2 else pixels


def read_image(path):
    """H x W x C array in the file's own type (uint8, uint16, float32 for EXR). Decoded by the
    flowscape_native extension when it is built, else by Debian's python3-openimageio (PNG, JPEG,
    EXR), else Pillow (python3-pil: PNG, JPEG), else a numpy PNG decoder."""
    if _native is not None:
        return _native.read_image(str(path))
    try:
        import OpenImageIO
        return _read_openimageio(path, OpenImageIO)
    except ImportError:
        pass
    if not str(path).lower().endswith(".exr"):
        try:
            from PIL import Image
            return _read_pillow(path, Image)
        except ImportError:
            pass
    if str(path).lower().endswith(".png"):
        return read_png(path)
    raise ValueError(f"{path}: reading this format without the flowscape_native extension needs "
                     "python3-openimageio (EXR, PNG, JPEG) or python3-pil (PNG, JPEG)")
