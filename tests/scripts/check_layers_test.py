#!/usr/bin/env python3
"""Tests scripts/check_layers.py: the repository passes, and a copy with one include against the
layer table, a public header including a private one or left out of the umbrella header, a folder without a row or a row
naming a layer below it fails, naming the cause."""
import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCRIPT = os.path.join(ROOT, "scripts", "check_layers.py")


def run(root):
    done = subprocess.run([sys.executable, SCRIPT, root], capture_output=True, text=True)
    return done.returncode, done.stdout + done.stderr


def copy_tree(scratch):
    for part in ("include", "src"):
        shutil.copytree(os.path.join(ROOT, part), os.path.join(scratch, part))
    os.makedirs(os.path.join(scratch, "docs"))
    shutil.copy(os.path.join(ROOT, "docs", "architecture.md"), os.path.join(scratch, "docs"))
    return scratch


def append(path, text):
    with open(path, "a") as f:
        f.write(text)


def expect(condition, message):
    if not condition:
        print("FAIL:", message)
        sys.exit(1)


def main():
    code, out = run(ROOT)
    expect(code == 0 and "every include follows" in out, f"the repository fails:\n{out}")

    with tempfile.TemporaryDirectory() as scratch:
        copy_tree(scratch)
        # source/ may not include render/ (render includes source): the cycle the table forbids.
        target = os.path.join(scratch, "src", "source", "source_file.cpp")
        lines = sum(1 for _ in open(target))
        append(target, '#include "geolens/render/render.h"\n')
        code, out = run(scratch)
        expect(code == 1 and f"src/source/source_file.cpp:{lines + 1}: source/ includes render/"
               in out, f"a public include upwards passes:\n{out}")

    with tempfile.TemporaryDirectory() as scratch:
        copy_tree(scratch)
        # A private header of a layer above, as src/ spells it.
        append(os.path.join(scratch, "src", "lens", "lift.cpp"), '#include "eval/lens_json.h"\n')
        code, out = run(scratch)
        expect(code == 1 and "src/lens/lift.cpp" in out and "lens/ includes eval/" in out,
               f"a private include upwards passes:\n{out}")

    with tempfile.TemporaryDirectory() as scratch:
        copy_tree(scratch)
        # A public header may not include a private one, even of its own layer.
        append(os.path.join(scratch, "include", "geolens", "lens", "lens_session.h"),
               '#include "lens/focus_lens.h"\n')
        code, out = run(scratch)
        expect(code == 1 and "include/geolens/lens/lens_session.h" in out and
               "a public header includes a private one" in out,
               f"a public header including a private one passes:\n{out}")

    with tempfile.TemporaryDirectory() as scratch:
        copy_tree(scratch)
        # A public header the umbrella header leaves out.
        open(os.path.join(scratch, "include", "geolens", "lens", "extra.h"), "w").write(
            "#pragma once\n")
        code, out = run(scratch)
        expect(code == 1 and "geolens.h: does not include geolens/lens/extra.h" in out,
               f"a public header left out of the umbrella passes:\n{out}")

    with tempfile.TemporaryDirectory() as scratch:
        copy_tree(scratch)
        os.makedirs(os.path.join(scratch, "src", "extras"))
        code, out = run(scratch)
        expect(code == 1 and "src/extras/: no row" in out, f"a folder without a row passes:\n{out}")

    with tempfile.TemporaryDirectory() as scratch:
        copy_tree(scratch)
        table = os.path.join(scratch, "docs", "architecture.md")
        text = open(table).read()
        row = "| `numerics/` |"
        start = text.index(row)
        end = text.index("\n", start)
        line = text[start:end]
        text = text[:start] + line[:line.rindex("| core |")] + "| core, lens |" + text[end:]
        open(table, "w").write(text)
        code, out = run(scratch)
        expect(code != 0 and "numerics/ names ['lens']" in out,
               f"a row naming a layer below it passes:\n{out}")
    print("check_layers_test: 7 cases passed")


if __name__ == "__main__":
    main()
