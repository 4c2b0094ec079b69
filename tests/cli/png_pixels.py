"""Reads an 8-bit PNG (grey, RGB or RGBA; no interlace) into rows of bytes, with zlib only: the tests
compare frames pixel by pixel without an imaging library. PNG filters per ISO/IEC 15948 §9."""
import struct
import zlib


def read_png(path):
    """Returns (width, height, bytes per pixel, rows), each row a bytearray of width × bpp bytes."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path}: not a PNG")
    pos, width, height, colour, compressed = 8, 0, 0, 0, b""
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or interlace != 0 or colour not in (0, 2, 6):
                raise ValueError(f"{path}: only 8-bit grey, RGB or RGBA without interlace")
        elif kind == b"IDAT":
            compressed += body
    bpp = {0: 1, 2: 3, 6: 4}[colour]
    raw, stride, rows, prev, at = zlib.decompress(compressed), width * bpp, [], bytearray(width * bpp), 0
    for _ in range(height):
        kind, line = raw[at], bytearray(raw[at + 1:at + 1 + stride])
        at += 1 + stride
        for x in range(stride):
            a = line[x - bpp] if x >= bpp else 0
            b = prev[x]
            c = prev[x - bpp] if x >= bpp else 0
            if kind == 1:
                line[x] = (line[x] + a) & 255
            elif kind == 2:
                line[x] = (line[x] + b) & 255
            elif kind == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif kind == 4:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return width, height, bpp, rows


def differing_pixels(path_a, path_b):
    """Number of pixels whose colour differs between two PNGs of the same size."""
    wa, ha, bpp, a = read_png(path_a)
    wb, hb, bpp_b, b = read_png(path_b)
    if (wa, ha) != (wb, hb):
        return wa * ha
    return sum(a[y][x * bpp:x * bpp + 3] != b[y][x * bpp_b:x * bpp_b + 3] for y in range(ha) for x in range(wa))
