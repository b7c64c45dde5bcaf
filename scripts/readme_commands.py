#!/usr/bin/env python3
"""Runs the commands of the README and the docs pages, then checks or regenerates their pictures.

Usage: readme_commands.py [--build DIR] [--regenerate]

Every ```sh and ```python block of README.md and of the PAGES under docs/ is run in order (the
pages' order, each page's blocks top to bottom, all in one scratch folder) (bash -euo pipefail; python3 with
the build's module on its path) except those that set up, build or install geolens: a block
calling scripts/*.sh, `cmake -S`, `cmake --install` or `pkg-config` (CI runs those itself, and
scripts/package_check.sh the install). They run in a scratch folder holding copies of examples/
and docs/ and a link to the build folder (default build/), so the commands are run exactly as
written and the repository is not touched. Checked:

  - each block exits 0 within TIMEOUT seconds;
  - a ```output block (or a table after a line <!-- output -->) after a command block holds
    lines that block's output (stdout and stderr) must contain, each line somewhere in it;
  - every picture a page shows exists in the repository and is made by a command of the
    pages, either written to docs/ directly or written to out/ by a line that says "kept as
    docs/NAME" (its out/ path with the same extension is the picture), unless MADE_ELSEWHERE says
    which other script made it and why;
  - each picture made here matches the committed one: the same size, and a mean difference of
    at most MAX_MEAN_DIFFERENCE of 255 per sample (the solve and the codecs are deterministic, so
    this fails when a change alters what a command draws and the picture was not regenerated).

With --regenerate the pictures made are copied into the repository's docs/ instead of compared,
and the viewer's pictures are made again by their own scripts (MADE_ELSEWHERE). Exits non-zero
naming each failure.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TIMEOUT = 600
MAX_MEAN_DIFFERENCE = 0.5
# The pages whose commands run, in order (the README's sections before they became pages).
PAGES = ["README.md", "docs/cli.md", "docs/sources.md", "docs/viewer.md", "docs/library.md",
         "docs/python.md", "docs/development.md"]
SETUP = re.compile(r"scripts/\S+\.sh|cmake -S|cmake --install|pkg-config")
# Pictures of the pages no command of them makes: the script that does, or why none does.
MADE_ELSEWHERE = {
    "docs/demo_before_after.jpg": "scripts/demo.sh (the README's first command)",
    "docs/rim_before.jpg": "the power ring's rim before issue 28, kept for the comparison",
    "docs/line_before.jpg": "a line of text solved in the image's frame, kept for the comparison",
    "docs/paragraph_margin_before.jpg": "a paragraph at the margin as 5a76c1f (before issue 28) "
    "solved it, kept for the comparison",
    "docs/compare_focus_panel.jpg": "a crop of compare's panel.png around the focus lens",
    "docs/reproduction/sweep_zoom2.png": "scripts/reproduce_figures.sh",
    "docs/viewer.png": "docs/viewer_screenshot.sh",
    "docs/viewer_drag_1.jpg": "docs/viewer_drag.sh",
    "docs/viewer_drag_2.jpg": "docs/viewer_drag.sh",
    "docs/viewer_drag_3.jpg": "docs/viewer_drag.sh",
    "docs/web_demo.jpg": "scripts/web_pictures.mjs (the browser pages in headless chromium)",
    "docs/web_map.jpg": "scripts/web_pictures.mjs (the browser pages in headless chromium)",
}


def blocks(readme):
    """The fenced blocks of the README and the tables marked <!-- output --> (as "output"
    blocks), in order: (info string, text, line number)."""
    found = []
    for pattern in (r"^```(\w*)\n((?s:.*?))^```", r"^<!-- (output) -->\n((?:\|.*\n)+)"):
        for match in re.finditer(pattern, readme, re.M):
            line = readme.count("\n", 0, match.start()) + 1
            found.append((match.group(1), match.group(2), line))
    return sorted(found, key=lambda block: block[2])


def made_pictures(text):
    """{docs picture: path it is written to} for one command block's text."""
    made = {}
    for line in text.splitlines():
        kept = re.search(r"kept as `?(docs/[\w/.-]+\.\w+)", line)
        if kept:
            picture = kept.group(1)
            ext = os.path.splitext(picture)[1]
            outs = [p for p in re.findall(r"out/[\w/.-]+", line) if p.endswith(ext)]
            if len(outs) != 1:
                raise SystemExit(f"readme_commands: cannot tell which out/ file is {picture}: {line}")
            made[picture] = outs[0]
            continue
        for picture in re.findall(r"docs/[\w/.-]+\.(?:jpg|png)", line):
            made[picture] = picture
    return made


def mean_difference(a_path, b_path, geolens):
    a, b = geolens.load_image(a_path), geolens.load_image(b_path)
    if a.shape != b.shape:
        return None
    return float(abs(a.astype("int16") - b.astype("int16")).mean())


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--regenerate", action="store_true")
    args = parser.parse_args()
    build = os.path.abspath(args.build)
    python_path = os.path.join(build, "python")
    sys.path.insert(0, python_path)
    import geolens  # the build's module: the pictures are compared with its decoder

    shown = []
    for page in PAGES:
        with open(os.path.join(ROOT, page)) as f:
            text = f.read()
        for link in re.findall(r"!\[[^]]*\]\(([^)]+)\)", text):
            shown.append(os.path.normpath(os.path.join(os.path.dirname(page), link)))
    failures = []
    work = tempfile.mkdtemp(prefix="readme-")
    try:
        for folder in ("examples", "docs"):
            shutil.copytree(os.path.join(ROOT, folder), os.path.join(work, folder))
        os.symlink(build, os.path.join(work, "build"))
        env = dict(os.environ, PYTHONPATH=python_path, TMPDIR=work)
        made, last_output, last_line = {}, None, None
        for page in PAGES:
            with open(os.path.join(ROOT, page)) as f:
                text = f.read()
            for info, block, line in blocks(text):
                where = f"{page}:{line}"
                if info == "output":
                    if last_output is None:
                        failures.append(f"{where}: an output block after no command block")
                    for wanted in filter(None, (w.strip() for w in block.splitlines())):
                        if wanted not in last_output:
                            failures.append(f"{where}: the block at {last_line} did not print: {wanted}")
                    continue
                if info not in ("sh", "python") or (info == "sh" and SETUP.search(block)):
                    continue
                command = ["bash", "-euo", "pipefail", "-c", block] if info == "sh" else [sys.executable, "-c", block]
                start = time.monotonic()
                try:
                    run = subprocess.run(command, cwd=work, env=env, capture_output=True, text=True, timeout=TIMEOUT)
                    status, output = run.returncode, run.stdout + run.stderr
                except subprocess.TimeoutExpired:
                    status, output = "timeout", ""
                print(f"{where}: {info} block, exit {status}, {time.monotonic() - start:.1f} s", flush=True)
                if status != 0:
                    failures.append(f"{where}: the block exited {status}:\n{output.strip()[-2000:]}")
                made.update(made_pictures(block))
                last_output, last_line = output, where
        for picture in sorted(set(shown)):
            if not os.path.isfile(os.path.join(ROOT, picture)):
                failures.append(f"{picture}: shown on a page but not in the repository")
            elif (picture in made) == (picture in MADE_ELSEWHERE):
                failures.append(f"{picture}: made by {'both a command of the pages and' if picture in made else 'neither a command of the pages nor'} MADE_ELSEWHERE")
        for picture, path in sorted(made.items()):
            produced = os.path.join(work, path)
            if not os.path.isfile(produced):
                failures.append(f"{picture}: its command did not write {path}")
            elif args.regenerate:
                shutil.copyfile(produced, os.path.join(ROOT, picture))
                print(f"regenerated {picture}")
            else:
                difference = mean_difference(produced, os.path.join(ROOT, picture), geolens)
                print(f"{picture}: mean difference {difference}")
                if difference is None or difference > MAX_MEAN_DIFFERENCE:
                    failures.append(f"{picture}: the pages' command now draws a different picture "
                                    f"(mean difference {difference}); run scripts/readme_commands.py --regenerate")
        if args.regenerate:
            for script in sorted({s for s in MADE_ELSEWHERE.values() if s.startswith("docs/") and s.endswith(".sh")}):
                subprocess.run(["bash", os.path.join(ROOT, script), build], check=True)
                print(f"ran {script}")
    finally:
        shutil.rmtree(work)
    for failure in failures:
        print(f"readme_commands: {failure}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
