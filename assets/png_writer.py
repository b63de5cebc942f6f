"""The image writers the texture and sky generators share (standard library only):
8-bit PNG (grey, grey + alpha, RGB or RGBA; no interlace, every row filter type 0,
zlib level 9) and Radiance RGBE .hdr (flat, uncompressed scanlines). Both write
the same bytes for the same input on every run: no timestamps, no text chunks.

    from png_writer import write_png, write_hdr, srgb8
    write_png("a.png", w, h, rows, 3)    # rows: h rows, top first, each w*3 ints 0..255
    write_hdr("a.hdr", w, h, rows)       # rows: h rows, top first, each w*3 floats >= 0
"""
import math
import struct
import zlib

# PNG colour type by channel count: grey, grey + alpha, RGB, RGBA.
_COLOUR_TYPE = {1: 0, 2: 4, 3: 2, 4: 6}


def _chunk(kind, data):
    # The CRC covers the chunk type and its data, not the length.
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def write_png(path, width, height, rows, channels):
    """Writes an 8-bit PNG. rows: `height` rows, the top one first, each a flat
    sequence (list, bytes) of width * channels integers in 0..255."""
    if channels not in _COLOUR_TYPE:
        raise ValueError("channels must be 1, 2, 3 or 4, not %r" % (channels,))
    rows = list(rows)
    if len(rows) != height:
        raise ValueError("%d rows for height %d" % (len(rows), height))
    raw = bytearray()
    for y, row in enumerate(rows):
        row = bytes(row)  # raises on values outside 0..255
        if len(row) != width * channels:
            raise ValueError("row %d has %d values, not %d" % (y, len(row), width * channels))
        raw.append(0)  # filter type 0 (None): the row as it is
        raw += row
    ihdr = struct.pack(">IIBBBBB", width, height, 8, _COLOUR_TYPE[channels], 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(_chunk(b"IHDR", ihdr))
        f.write(_chunk(b"IDAT", zlib.compress(bytes(raw), 9)))
        f.write(_chunk(b"IEND", b""))


def srgb8(linear):
    """A linear value in [0, 1] (clamped) as an 8-bit sRGB code: colour maps
    (map_Kd, map_Ke) are read as sRGB, so a generator thinks in linear albedo
    and encodes here."""
    x = min(max(linear, 0.0), 1.0)
    s = 12.92 * x if x <= 0.0031308 else 1.055 * x ** (1 / 2.4) - 0.055
    return int(s * 255 + 0.5)


def _rgbe(r, g, b):
    # Greg Ward's shared exponent: the largest channel's mantissa lands in
    # 128..255, so a pixel never starts like a run-length marker (2, 2, <128).
    v = max(r, g, b)
    if v < 1e-32:
        return b"\0\0\0\0"
    m, e = math.frexp(v)  # v = m * 2^e, m in [0.5, 1)
    s = m * 256.0 / v
    return bytes((int(r * s), int(g * s), int(b * s), e + 128))


def write_hdr(path, width, height, rows):
    """Writes a Radiance RGBE .hdr, flat scanlines. rows: `height` rows, the
    top one first (the header says -Y: rows run downwards), each a flat
    sequence of width * 3 non-negative floats (r, g, b, r, g, b, ...)."""
    rows = list(rows)
    if len(rows) != height:
        raise ValueError("%d rows for height %d" % (len(rows), height))
    out = bytearray(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (height, width))
    for y, row in enumerate(rows):
        if len(row) != width * 3:
            raise ValueError("row %d has %d values, not %d" % (y, len(row), width * 3))
        for i in range(0, width * 3, 3):
            r, g, b = row[i], row[i + 1], row[i + 2]
            if not (r >= 0 and g >= 0 and b >= 0) or math.isinf(r + g + b):
                raise ValueError("row %d: %r is not a finite non-negative colour" % (y, (r, g, b)))
            out += _rgbe(r, g, b)
    with open(path, "wb") as f:
        f.write(out)
