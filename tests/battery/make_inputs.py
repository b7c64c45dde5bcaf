"""Small input files for the battery, made from nothing but the standard library.

Every function returns bytes (or text); the battery writes them into a case's folder. The images
are tiny PNGs written chunk by chunk with zlib and struct; the 3D files are minimal headers with
just enough data (or deliberately not enough).
"""

import gzip
import math
import struct
import zlib


def png_chunk(kind, data):
    """One PNG chunk: length, type, data, CRC over type and data."""
    crc = zlib.crc32(kind + data) & 0xFFFFFFFF
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", crc)


def png_raw(width, height, colour_type, depth, idat):
    """A PNG of the given header around already compressed IDAT bytes (which may not match)."""
    ihdr = struct.pack(">IIBBBBB", width, height, depth, colour_type, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", ihdr) + png_chunk(b"IDAT", idat) +
            png_chunk(b"IEND", b""))


def png(width, height, pixel, channels=3):
    """An 8-bit PNG whose pixel (x, y) is pixel(x, y): a tuple of `channels` values in [0, 255]."""
    colour_type = {1: 0, 2: 4, 3: 2, 4: 6}[channels]
    rows = bytearray()
    for y in range(height):
        rows.append(0)  # filter: none
        for x in range(width):
            rows.extend(pixel(x, y))
    return png_raw(width, height, colour_type, 8, zlib.compress(bytes(rows), 9))


def pattern_png(width=96, height=64):
    """A colour picture with stripes: a plain valid input image."""
    return png(width, height, lambda x, y: (x * 255 // width, y * 255 // height,
                                            200 if (x // 4 + y // 4) % 2 else 20))


def grey16_png(width=64, height=64):
    """A 16-bit grey PNG (valid; read rounded to 8 bits)."""
    rows = bytearray()
    for y in range(height):
        rows.append(0)
        for x in range(width):
            rows.extend(struct.pack(">H", (x * 1000 + y * 7) & 0xFFFF))
    return png_raw(width, height, 0, 16, zlib.compress(bytes(rows), 9))


def mask_png(width, height, inside):
    """A one-channel mask: 255 where inside(x, y), else 0."""
    return png(width, height, lambda x, y: (255 if inside(x, y) else 0,), channels=1)


def zeros_png(width, height, colour_type=0, depth=8, channels=1):
    """A header-consistent PNG of all-zero rows, compressed row by row (a zlib bomb when large)."""
    row = b"\0" * (1 + (width * channels * depth + 7) // 8)
    packer = zlib.compressobj(9)
    idat = bytearray()
    for _ in range(height):
        idat.extend(packer.compress(row))
    idat.extend(packer.flush())
    return png_raw(width, height, colour_type, depth, bytes(idat))


def corrupt_crc_png():
    """A valid picture whose IDAT checksum is wrong."""
    data = bytearray(pattern_png(32, 32))
    start = data.index(b"IDAT")
    length = struct.unpack(">I", data[start - 4:start])[0]
    data[start + 4 + length] ^= 0xFF
    return bytes(data)


def truncated(data, keep=0.5):
    """The first `keep` fraction of a file."""
    return data[:int(len(data) * keep)]


def jpeg_with_size(jpeg, width, height):
    """A copy of a JPEG whose frame header (SOF0/SOF2) claims width x height."""
    data = bytearray(jpeg)
    i = 2
    while i + 4 < len(data):
        marker, length = data[i + 1], struct.unpack(">H", data[i + 2:i + 4])[0]
        if marker in (0xC0, 0xC1, 0xC2):
            data[i + 5:i + 9] = struct.pack(">HH", height, width)
            return bytes(data)
        i += 2 + length
    raise ValueError("no frame header")


def polygon_circle(n, cx, cy, r):
    """A circle traced by n vertices, one 'x y' a line."""
    lines = []
    for i in range(n):
        a = 2 * math.pi * i / n
        lines.append(f"{cx + r * math.cos(a):.6f} {cy + r * math.sin(a):.6f}")
    return "\n".join(lines) + "\n"


def polygon_zigzag(n, x0, x1, y0, y1):
    """n vertices zigzagging between two lines and closed back: self-intersecting everywhere."""
    lines = [f"{x0 + (x1 - x0) * i / n:.4f} {y0 if i % 2 else y1}" for i in range(n)]
    lines += [f"{x0 + (x1 - x0) * i / n:.4f} {y1 if i % 2 else y0}" for i in reversed(range(n))]
    return "\n".join(lines) + "\n"


def nested_geojson(depth):
    """GeometryCollections nested `depth` levels deep."""
    return '{"type":"GeometryCollection","geometries":[' * depth + "]}" * depth


def line_geojson(coordinates):
    """A FeatureCollection of one LineString through the given (x, y) pairs (numbers or JSON
    text), with a name: a vector map when they are degrees."""
    line = ",".join(f"[{x},{y}]" for x, y in coordinates)
    return ('{"type":"FeatureCollection","features":[{"type":"Feature","properties":'
            '{"name":"a"},"geometry":{"type":"LineString","coordinates":[' + line + "]}}]}")


def cube_obj():
    """A cube [-1, 1]^3 of quads."""
    return ("v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\n"
            "v -1 1 1\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 3 4 8 7\nf 2 3 7 6\nf 1 5 8 4\n")


def ply_header(vertices, faces, fmt="binary_little_endian"):
    """A PLY header of float x y z vertices and uchar/int index-list faces."""
    return (f"ply\nformat {fmt} 1.0\nelement vertex {vertices}\nproperty float x\n"
            f"property float y\nproperty float z\nelement face {faces}\n"
            "property list uchar int vertex_indices\nend_header\n").encode()


def nrrd(sizes, type_="uchar", encoding="raw", extra="", data=b""):
    """A NRRD header (attached data unless `extra` names a data file) followed by `data`."""
    head = (f"NRRD0004\ntype: {type_}\ndimension: {len(sizes)}\n"
            f"sizes: {' '.join(str(s) for s in sizes)}\nencoding: {encoding}\n"
            f"endian: little\n{extra}")
    return head.encode() + (b"\n" + data if "data file" not in extra else b"")


def nifti(dims, datatype=2, bitpix=8, vox_offset=352.0, data=b""):
    """A NIfTI-1 single file (.nii): the 348-byte header, 4 extension bytes, then `data`."""
    header = bytearray(348)
    struct.pack_into("<i", header, 0, 348)
    dim = [len(dims)] + list(dims) + [1] * (7 - len(dims))
    struct.pack_into("<8h", header, 40, *dim)
    struct.pack_into("<hh", header, 70, datatype, bitpix)
    struct.pack_into("<8f", header, 76, *([1.0] * 8))
    struct.pack_into("<f", header, 108, vox_offset)
    struct.pack_into("<f", header, 112, 1.0)  # scl_slope
    header[344:348] = b"n+1\0"
    return bytes(header) + b"\0\0\0\0" + data


def gzip_zeros(header, size):
    """`header` followed by `size` zero bytes, gzipped in a stream (a gzip bomb when large)."""
    packer = zlib.compressobj(9, zlib.DEFLATED, 31)
    out = bytearray(packer.compress(header))
    block = b"\0" * (1 << 20)
    for _ in range(size >> 20):
        out.extend(packer.compress(block))
    out.extend(packer.flush())
    return bytes(out)


def gzipped(data):
    """`data` gzipped."""
    return gzip.compress(data, 9)


def damaged_idat_png():
    """A picture with one byte of its compressed data changed (its IDAT checksum left stale);
    with this zlib the damaged stream still inflates, to made-up pixels."""
    data = bytearray(pattern_png(32, 32))
    data[data.index(b"IDAT") + 4 + 900] ^= 0x55
    return bytes(data)
