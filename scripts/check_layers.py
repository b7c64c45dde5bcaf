#!/usr/bin/env python3
"""Checks every #include of the library against the layer table of docs/architecture.md.

Usage: check_layers.py [ROOT]   (default: the repository this script is in)

The table's rows name a layer (`core/`, `lens/`, ...) and, in its last column, the layers it may
include ("—" for none, "all of the above" for every row above it). A file of a layer
(include/geolens/LAYER/ or src/LAYER/) may include its own layer's headers, public
("geolens/LAYER/x.h") or private ("LAYER/x.h" from src/), and those of the layers its row names;
a public header includes public headers only (the private ones are not installed), and the
umbrella header include/geolens/geolens.h includes every public header.
Any other include of a layer's header, or a folder of include/geolens/ or src/ without a row,
is printed as FILE:LINE and fails the check (exit 1).
"""
import os
import re
import sys


def layer_table(architecture):
    """{layer: set of the layers it may include}, in the table's order."""
    allowed, above = {}, []
    for line in architecture.splitlines():
        row = re.match(r"^\| `(\w+)/` \|.*\| ([^|]*) \|$", line)
        if not row:
            continue
        layer, includes = row.group(1), row.group(2).strip()
        if includes == "all of the above":
            names = set(above)
        elif includes == "—":
            names = set()
        else:
            names = {name.strip() for name in includes.split(",")}
        unknown = names - set(above)
        if unknown:
            raise SystemExit(f"check_layers: the row of {layer}/ names {sorted(unknown)}, "
                             "which are not rows above it")
        allowed[layer] = names
        above.append(layer)
    return allowed


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                           os.path.join(os.path.dirname(__file__), ".."))
    with open(os.path.join(root, "docs", "architecture.md")) as f:
        allowed = layer_table(f.read())
    problems = []
    for base in (os.path.join(root, "include", "geolens"), os.path.join(root, "src")):
        for layer in sorted(os.listdir(base)):
            folder = os.path.join(base, layer)
            if not os.path.isdir(folder):
                continue
            if layer not in allowed:
                problems.append(f"{os.path.relpath(folder, root)}/: no row in the layer table")
                continue
            for name in sorted(os.listdir(folder)):
                path = os.path.join(folder, name)
                with open(path, errors="replace") as f:
                    for number, line in enumerate(f, 1):
                        include = re.match(r'\s*#\s*include\s+"(geolens/)?(\w+)/', line)
                        if not include or include.group(2) not in allowed:
                            continue
                        other = include.group(2)
                        if base.endswith("geolens") and not include.group(1):
                            problems.append(f"{os.path.relpath(path, root)}:{number}: a public "
                                            f"header includes a private one ({line.strip()}), "
                                            "which is not installed")
                        if other != layer and other not in allowed[layer]:
                            problems.append(f"{os.path.relpath(path, root)}:{number}: {layer}/ "
                                            f"includes {other}/ ({line.strip()})")
    # The umbrella header includes every public header.
    with open(os.path.join(root, "include", "geolens", "geolens.h")) as f:
        umbrella = set(re.findall(r'#include "(geolens/\w+/\w+\.h)"', f.read()))
    for layer in sorted(allowed):
        folder = os.path.join(root, "include", "geolens", layer)
        for name in sorted(os.listdir(folder)) if os.path.isdir(folder) else []:
            if f"geolens/{layer}/{name}" not in umbrella:
                problems.append(f"include/geolens/geolens.h: does not include geolens/{layer}/{name}")
    for problem in problems:
        print(problem)
    print(f"check_layers: {len(problems)} includes against the layer table" if problems else
          f"check_layers: every include follows the layer table ({len(allowed)} layers)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
