#!/usr/bin/env python3
"""Converts a region of Natural Earth's shapefiles into one small GeoJSON file for geolens's
vector-map source (examples/europe.geojson). Natural Earth (naturalearthdata.com) is in the public
domain; Debian's libmagics++-data ships the shapefiles under /usr/share/magics/.

Run once:  python3 scripts/natural_earth_to_geojson.py examples/europe.geojson

Reads .shp (ESRI Shapefile Technical Description, 1998: big-endian record headers, little-endian
shapes; types 1 Point, 3 PolyLine, 5 Polygon) and .dbf (dBASE III: a 32-byte header, 32-byte field
descriptors up to 0x0D, fixed-width records; Natural Earth's text is Latin-1) with the standard
library only. Polygons are clipped to the region's box (Sutherland-Hodgman), lines cut where they
leave it, simplified (Douglas-Peucker, 0.005 degrees: under a pixel at zoom 8 of a 1024-pixel
map of the region), coordinates rounded to 3 decimals (about 100 m), runs of equal points dropped.
"""

import json
import struct
import sys

sys.setrecursionlimit(100000)

MAGICS = "/usr/share/magics"
WEST, SOUTH, EAST, NORTH = -13.0, 34.0, 33.0, 63.0  # the box kept: the style's extent plus a margin


def read_dbf(path):
    with open(path, "rb") as f:
        data = f.read()
    count, header_size, record_size = struct.unpack("<IHH", data[4:12])
    fields, offset = [], 32
    while data[offset] != 0x0D:
        name = data[offset:offset + 11].split(b"\0")[0].decode("ascii").lower()
        fields.append((name, chr(data[offset + 11]), data[offset + 16]))
        offset += 32
    records = []
    for r in range(count):
        start = header_size + r * record_size + 1  # after the deletion flag
        record = {}
        for name, kind, size in fields:
            text = data[start:start + size].decode("latin-1").strip()
            start += size
            if kind in "NF":
                try:
                    record[name] = float(text) if "." in text else int(text)
                except ValueError:
                    record[name] = None
            else:
                record[name] = text
        records.append(record)
    return records


def read_shp(path):
    """Yields each record's shape: ("point", (x, y)) or ("lines" / "rings", [[(x, y), ...], ...])."""
    with open(path, "rb") as f:
        data = f.read()
    offset = 100
    while offset < len(data):
        _, words = struct.unpack(">ii", data[offset:offset + 8])
        body = data[offset + 8:offset + 8 + 2 * words]
        offset += 8 + 2 * words
        kind = struct.unpack("<i", body[:4])[0]
        if kind == 0:
            yield None, None
        elif kind == 1:
            yield "point", struct.unpack("<2d", body[4:20])
        elif kind in (3, 5):
            parts_count, points_count = struct.unpack("<2i", body[36:44])
            parts = list(struct.unpack("<%di" % parts_count, body[44:44 + 4 * parts_count]))
            xy = struct.unpack("<%dd" % (2 * points_count), body[44 + 4 * parts_count:])
            points = list(zip(xy[0::2], xy[1::2]))
            bounds = parts + [points_count]
            yield ("lines" if kind == 3 else "rings"), [points[a:b] for a, b in zip(bounds, bounds[1:])]
        else:
            raise ValueError("%s: shape type %d not handled" % (path, kind))


def inside(p):
    return WEST <= p[0] <= EAST and SOUTH <= p[1] <= NORTH


def clip_ring(ring):
    """Sutherland-Hodgman against the box, one edge after another."""
    def clip(points, keep, cross):
        out = []
        for i, p in enumerate(points):
            q = points[i - 1]
            if keep(p):
                if not keep(q):
                    out.append(cross(q, p))
                out.append(p)
            elif keep(q):
                out.append(cross(q, p))
        return out

    def at_x(x):
        return lambda a, b: (x, a[1] + (b[1] - a[1]) * (x - a[0]) / (b[0] - a[0]))

    def at_y(y):
        return lambda a, b: (a[0] + (b[0] - a[0]) * (y - a[1]) / (b[1] - a[1]), y)

    points = ring[:-1]
    for keep, cross in ((lambda p: p[0] >= WEST, at_x(WEST)), (lambda p: p[0] <= EAST, at_x(EAST)),
                        (lambda p: p[1] >= SOUTH, at_y(SOUTH)), (lambda p: p[1] <= NORTH, at_y(NORTH))):
        points = clip(points, keep, cross)
        if not points:
            return None
    return points + [points[0]]


def cut_line(line):
    """The pieces of a line inside the box, each with its first vertex outside, so it reaches it."""
    pieces, piece = [], []
    for i, p in enumerate(line):
        if inside(p) or (i + 1 < len(line) and inside(line[i + 1])) or (i > 0 and inside(line[i - 1])):
            piece.append(p)
        elif piece:
            pieces.append(piece)
            piece = []
    if piece:
        pieces.append(piece)
    return [p for p in pieces if len(p) >= 2]


def simplified(points, tolerance=0.005):
    """Douglas-Peucker: the points farther than `tolerance` from the chord, recursively."""
    if len(points) <= 2:
        return points
    (ax, ay), (bx, by) = points[0], points[-1]
    dx, dy = bx - ax, by - ay
    length = (dx * dx + dy * dy) ** 0.5
    best, far = -1.0, 0
    for i in range(1, len(points) - 1):
        px, py = points[i][0] - ax, points[i][1] - ay
        d = abs(dx * py - dy * px) / length if length > 0 else (px * px + py * py) ** 0.5
        if d > best:
            best, far = d, i
    if best <= tolerance:
        return [points[0], points[-1]]
    return simplified(points[:far + 1], tolerance)[:-1] + simplified(points[far:], tolerance)


def rounded(points):
    out = []
    for x, y in simplified(points):
        p = [round(x, 3), round(y, 3)]
        if not out or p != out[-1]:
            out.append(p)
    return out


def features(name, properties, keep=lambda record: True):
    base = "%s/%s/ne_%s" % (MAGICS, name.split("_")[0], name)
    for record, (kind, shape) in zip(read_dbf(base + ".dbf"), read_shp(base + ".shp")):
        if kind is None or not keep(record):
            continue
        props = {k: record[k] for k in properties}
        if kind == "point":
            if inside(shape):
                yield props, {"type": "Point", "coordinates": rounded([shape])[0]}
        elif kind == "lines":
            lines = [rounded(piece) for line in shape for piece in cut_line(line)]
            lines = [l for l in lines if len(l) >= 2]
            if lines:
                yield props, {"type": "MultiLineString", "coordinates": lines}
        else:
            # Natural Earth's rings are exterior (clockwise) or holes; each clipped on its own and
            # drawn even-odd, so they need not be grouped into polygons.
            rings = [rounded(r) for r in (clip_ring(ring) for ring in shape) if r]
            rings = [r for r in rings if len(r) >= 4]
            if rings:
                yield props, {"type": "MultiPolygon", "coordinates": [[r] for r in rings]}


def main():
    out = []
    out += features("50m_land", ["featurecla"])
    out += features("50m_admin_0_boundary_lines_land", ["featurecla"])
    out += features("10m_rivers_lake_centerlines", ["featurecla", "scalerank"],
                    lambda r: r["scalerank"] is not None and r["scalerank"] <= 6)
    places = list(features("10m_populated_places_simple",
                           ["featurecla", "nameascii", "scalerank", "pop_max"],
                           lambda r: r["scalerank"] <= 8))
    # The more important first: labels of equal rank are placed in this order.
    places.sort(key=lambda f: (f[0]["scalerank"], -(f[0]["pop_max"] or 0)))
    for props, _ in places:
        del props["pop_max"]
    out += places
    with open(sys.argv[1], "w", encoding="utf-8") as f:
        f.write('{"type": "FeatureCollection", "features": [\n')
        f.write(",\n".join(json.dumps({"type": "Feature", "properties": p, "geometry": g},
                                      separators=(",", ":"), ensure_ascii=False) for p, g in out))
        f.write("\n]}\n")


if __name__ == "__main__":
    main()
