#!/usr/bin/env python3
"""The bad-input battery: bad or awkward input for every subcommand and input kind of the CLI.

Usage: battery.py GEOLENS_CLI [NAME_SUBSTRING ...]   (the names select cases; default: all)

Each case gets a fresh folder holding its input files (made here, see make_inputs.py), runs the
CLI there with a 10 s timeout, a 2 GB address-space limit (not under the sanitizers, recognized by
ASAN_OPTIONS, whose shadow memory needs more: there allocations fail past 3 GB of RSS instead) and
a 256 MB file-size limit, and checks:

  - the exit code is the expected one (2 for bad input, 1 for a failure at run time, 0 for an
    awkward input that is valid);
  - a refusal (non-zero) prints exactly one line on stderr, "geolens: error: ..." (exit 2) or
    "geolens: failed: ..." (exit 1), that contains the case's words (what the user gave: the file,
    the option, the value) and no internal name: no C++ qualified name ('::'), no class of the
    library (TiledSource, Flattener, ...), no internal helper (make_grid), no exception text
    (bad_alloc, json.exception), no number of more than 20 digits; on success every stderr
    line is a "geolens: warning: ..." line, held to the same words;
  - nothing in the case's folder changed (every file, link, folder and FIFO, with its size, mode
    and SHA-256) but the outputs the case expects, which must exist and be valid (a PNG of the
    expected size, JSON, CSV, ...); no temporary file is left (TMPDIR is a folder in the case's);
  - wall time under 10 s and peak RSS (getrusage of the child, os.wait4) under 1 GB.

Under the sanitizers (ASAN_OPTIONS set) the time limits are 4 times and the memory limit twice
those, the instrumented code being that much slower and larger. Cases in KNOWN_DEFECTS are real
defects of the program, still run and reported: they do not fail the battery while they fail,
and fail it once they pass (remove them from the list then). It prints one row per case and exits
non-zero naming the failing cases.
"""

import hashlib
import json
import os
import re
import resource
import shlex
import shutil
import signal
import stat
import struct
import subprocess
import sys
import tempfile
import threading
import time
import zlib
from dataclasses import dataclass, field
from pathlib import Path

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, str(Path(__file__).resolve().parent))
import make_inputs as mk  # noqa: E402

SOURCE_DIR = Path(__file__).resolve().parents[2]
SANITIZED = "ASAN_OPTIONS" in os.environ
SLOWDOWN = 4 if SANITIZED else 1
TIMEOUT_S = 10.0 * SLOWDOWN
MAX_WALL_S = 10.0 * SLOWDOWN
MAX_RSS_MB = 1024 * (2 if SANITIZED else 1)
ADDRESS_LIMIT = 2 << 30
FILE_SIZE_LIMIT = 256 << 20

# Cases that fail because of a defect of the program, not of the case: what it does. Remove an
# entry once the program is fixed (the battery fails while a listed case passes).
KNOWN_DEFECTS = {}  # none left (31 when the battery came in)


# ----------------------------------------------------------------------------------------------
# What a case is


@dataclass
class Link:
    """A symbolic link to `target` (relative to the link's folder, or absolute)."""
    target: str


@dataclass
class HardLink:
    """A second name of the case file `target`."""
    target: str


class Fifo:
    """A named pipe."""


@dataclass
class Folder:
    """A folder, with its mode."""
    mode: int = 0o755


@dataclass
class Case:
    name: str
    args: str                   # the command line after the CLI, split by shlex; run in the folder
    files: dict = field(default_factory=dict)  # name -> bytes, str, a function of the folder
    #                                            returning them, Link, HardLink, Fifo or Folder
    code: int = 2
    words: tuple = ()           # each must appear in the stderr line; a tuple: one of them
    outputs: dict = field(default_factory=dict)  # name -> check(path) returning an error or None
    stdin: bytes = b""
    as_nobody: bool = False     # run as an unprivileged user (root writes into read-only folders)
    stdout_check: object = None  # check(bytes) returning an error or None


CASES = []


def case(name, args, files=None, **kw):
    CASES.append(Case(name, args, dict(files or {}), **kw))


# ----------------------------------------------------------------------------------------------
# Output checks: each returns None when the file is what it should be, else what is wrong.


def png_of_size(width, height):
    def check(path):
        data = Path(path).read_bytes()
        if data[:8] != b"\x89PNG\r\n\x1a\n" or data[12:16] != b"IHDR":
            return f"{path} is not a PNG"
        size = struct.unpack(">II", data[16:24])
        return None if size == (width, height) else f"{path} is {size[0]}x{size[1]}"
    return check


def any_png(path):
    data = Path(path).read_bytes()
    return None if data[:8] == b"\x89PNG\r\n\x1a\n" and data[-8:-4] == b"IEND" else "not a PNG"


def json_with(*keys):
    def check(path):
        try:
            document = json.loads(Path(path).read_text())
        except ValueError as error:
            return f"{path} is not JSON: {error}"
        missing = [k for k in keys if k not in document]
        return f"{path} lacks {missing}" if missing else None
    return check


def csv_rows(rows):
    def check(path):
        lines = Path(path).read_text().splitlines()
        body = [line for line in lines if line and not line[0].isalpha()]
        return None if len(body) == rows else f"{path} has {len(body)} rows, not {rows}"
    return check


def any_file(path):
    return None if Path(path).stat().st_size > 0 else f"{path} is empty"


# ----------------------------------------------------------------------------------------------
# Internal names a message must not show


def library_types():
    """Class and struct names of the library's public headers with two or more capitals."""
    names = set()
    for header in (SOURCE_DIR / "include").rglob("*.h"):
        for match in re.finditer(r"^\s*(?:class|struct)\s+([A-Z]\w+)", header.read_text(),
                                 re.MULTILINE):
            names.add(match.group(1))
    return names


def internal_patterns():
    types = library_types()
    camel = sorted(n for n in types if re.search(r"[a-z0-9][A-Z]", n)) + ["Flattener"]
    single = sorted(n for n in types if n not in camel)
    return [
        ("a C++ qualified name", re.compile(r"::")),
        ("a library type", re.compile(r"\b(" + "|".join(camel) + r")\b")),
        ("a library type as a function", re.compile(r"\b(" + "|".join(single) + r"):")),
        ("an internal helper", re.compile(r"\b(make_grid|factorize|cholesky)\b")),
        ("an exception's text", re.compile(r"bad_alloc|json\.exception|basic_string|"
                                           r"what\(\)|terminate called|vector::|Assertion")),
        ("a number of more than 20 digits", re.compile(r"\d{21,}")),
    ]


INTERNAL = internal_patterns()


def lacks(text, word):
    """Whether `text` lacks `word` (a string, or a tuple of which one will do)."""
    return not any(w in text for w in (word if isinstance(word, tuple) else (word,)))


def message_problems(line, words):
    problems = [f"lacks {w!r}" for w in words if lacks(line, w)]
    control = re.search(r"[\x00-\x08\x0b-\x1f\x7f]", line.rstrip("\n"))
    if control:
        problems.append(f"shows a control character ({control.group(0)!r})")
    problems += [f"shows {what} ({m.group(0)!r})"
                 for what, pattern in INTERNAL for m in [pattern.search(line)] if m]
    return problems


# ----------------------------------------------------------------------------------------------
# Running a case


def build(folder, files):
    """Writes the case's files; links and hard links after everything else."""
    later = []
    for name, what in files.items():
        path = folder / name
        path.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(what, (Link, HardLink)):
            later.append((path, what))
        elif isinstance(what, Folder):
            path.mkdir(exist_ok=True)
        elif isinstance(what, Fifo):
            os.mkfifo(path)
        else:
            data = what(folder) if callable(what) else what
            path.write_bytes(data.encode() if isinstance(data, str) else data)
    for path, what in later:
        if isinstance(what, Link):
            os.symlink(what.target, path)
        else:
            os.link(folder / what.target, path)
    for name, what in files.items():  # modes last: a read-only folder is filled first
        if isinstance(what, Folder):
            os.chmod(folder / name, what.mode)


def snapshot(folder):
    """Every entry under `folder`: its kind, mode and, for files, size and SHA-256."""
    entries = {}
    for root, dirs, names in os.walk(folder):
        for name in dirs + names:
            path = Path(root) / name
            info = path.lstat()
            key = str(path.relative_to(folder))
            if stat.S_ISLNK(info.st_mode):
                entries[key] = ("link", os.readlink(path))
            elif stat.S_ISREG(info.st_mode):
                digest = hashlib.sha256(path.read_bytes()).hexdigest()
                entries[key] = ("file", stat.S_IMODE(info.st_mode), info.st_size, digest)
            else:
                entries[key] = (stat.S_IFMT(info.st_mode), stat.S_IMODE(info.st_mode))
    return entries


def limits(as_nobody):
    """The child's limits, set between fork and exec."""
    def apply():
        os.setsid()
        if not SANITIZED:
            resource.setrlimit(resource.RLIMIT_AS, (ADDRESS_LIMIT, ADDRESS_LIMIT))
        resource.setrlimit(resource.RLIMIT_FSIZE, (FILE_SIZE_LIMIT, FILE_SIZE_LIMIT))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
        if as_nobody and os.geteuid() == 0:
            os.setgroups([])
            os.setgid(65534)
            os.setuid(65534)
    return apply


@dataclass
class Run:
    code: int
    stderr: str
    stdout: bytes
    seconds: float
    peak_mb: float
    timed_out: bool


def run(cli, c, folder, io_folder):
    """Runs the case's command in its folder; stdout and stderr go to files outside it."""
    env = dict(os.environ, TMPDIR=str(folder / ".tmp"), LC_ALL="C")
    if SANITIZED:  # no RLIMIT_AS there: memory past this fails to allocate, as it would with it
        env["ASAN_OPTIONS"] += ":soft_rss_limit_mb=3072:allocator_may_return_null=1"
    out_path, err_path = io_folder / f"{c.name}.out", io_folder / f"{c.name}.err"
    with open(out_path, "wb") as out, open(err_path, "wb") as err:
        start = time.monotonic()
        child = subprocess.Popen([cli] + shlex.split(c.args), cwd=folder, env=env,
                                 stdin=subprocess.PIPE, stdout=out, stderr=err,
                                 preexec_fn=limits(c.as_nobody))
        timed_out = threading.Event()

        def kill():
            timed_out.set()
            kill_session(child.pid)

        timer = threading.Timer(TIMEOUT_S, kill)
        timer.start()
        feeder = threading.Thread(target=feed, args=(child.stdin, c.stdin))
        feeder.start()
        _, status, usage = os.wait4(child.pid, 0)
        seconds = time.monotonic() - start
        timer.cancel()
        child.returncode = os.waitstatus_to_exitcode(status)
        feeder.join()
    kill_session(child.pid)  # anything the child left running
    return Run(child.returncode, err_path.read_bytes().decode(errors="replace"),
               out_path.read_bytes(), seconds, usage.ru_maxrss / 1024, timed_out.is_set())


def kill_session(pid):
    """Kills the session the child leads (its process group), if anything is left of it."""
    try:
        os.killpg(pid, signal.SIGKILL)
    except ProcessLookupError:
        pass


def feed(pipe, data):
    try:
        pipe.write(data)
        pipe.close()
    except (BrokenPipeError, OSError):
        pass


def judge(c, r, before, after, folder):
    """What is wrong with the run of case c (an empty list: nothing)."""
    problems = []
    if r.timed_out:
        problems.append(f"killed after {TIMEOUT_S:.0f} s")
    if r.code != c.code:
        problems.append(f"exit {r.code}, expected {c.code}")
    lines = r.stderr.split("\n")
    if lines[-1] == "":
        lines.pop()
    if c.code != 0:
        prefix = "geolens: error: " if c.code == 2 else "geolens: failed: "
        if r.stderr.count("\n") != 1 or not r.stderr.endswith("\n"):
            problems.append(f"{r.stderr.count(chr(10))} lines on stderr, expected 1")
        if not r.stderr.startswith(prefix):
            problems.append(f"stderr does not start with {prefix!r}")
        problems += message_problems(r.stderr, c.words)
    else:
        for line in lines:
            if not line.startswith("geolens: warning: "):
                problems.append(f"stderr line not a warning: {line[:80]!r}")
            problems += message_problems(line, ())
        problems += [f"no warning with {w!r}" for w in c.words if lacks(r.stderr, w)]
    problems += changes(c, before, after, folder)
    if c.stdout_check:
        problem = c.stdout_check(r.stdout)
        if problem:
            problems.append(problem)
    if r.seconds >= MAX_WALL_S:
        problems.append(f"took {r.seconds:.1f} s")
    if r.peak_mb >= MAX_RSS_MB:
        problems.append(f"peak RSS {r.peak_mb:.0f} MB")
    return problems


def changes(c, before, after, folder):
    """Every change to the folder but the expected outputs, and every output not as expected."""
    problems = []
    for name in sorted(set(before) | set(after)):
        if any(name == out or name.startswith(out + "/") for out in c.outputs):
            continue
        if name not in after:
            problems.append(f"removed {name}")
        elif name not in before:
            problems.append(f"wrote {name}")
        elif before[name] != after[name]:
            problems.append(f"changed {name}")
    for name, check in c.outputs.items():
        path = folder / name
        if not path.exists():
            problems.append(f"no output {name}")
            continue
        problem = check(str(path))
        if problem:
            problems.append(problem)
    return problems


def run_case(cli, c, root, io_folder):
    folder = root / c.name
    folder.mkdir()
    (folder / ".tmp").mkdir()
    build(folder, c.files)
    if c.as_nobody:
        open_to_nobody(root, folder)
    before = snapshot(folder)
    r = run(cli, c, folder, io_folder)
    after = snapshot(folder)
    problems = judge(c, r, before, after, folder)
    for path in [folder] + list(folder.rglob("*")):  # read-only folders back, to remove them
        if path.is_dir() and not path.is_symlink():
            os.chmod(path, 0o755)
    shutil.rmtree(folder, ignore_errors=True)
    return r, problems


def open_to_nobody(root, folder):
    """Lets an unprivileged user read the case's files and write its temporary folder."""
    for path in [root, folder] + list(folder.rglob("*")):
        if path.is_symlink():
            continue
        if path.is_dir():
            os.chmod(path, os.stat(path).st_mode | 0o555)
        elif path.is_file():
            os.chmod(path, 0o644)
    os.chmod(folder / ".tmp", 0o777)


# ----------------------------------------------------------------------------------------------
# The cases. Paths are relative to the case's folder, where the CLI runs. W x H = 160 x 120.

IMG = mk.pattern_png(160, 120)
LENS = "--lens circle:80,60,10"
MAG = f"magnify in.png -o out.png {LENS}"
OUT_OK = {"out.png": png_of_size(160, 120)}
SQUARE = "60 40\n100 40\n100 80\n60 80\n"
BOWTIE = "60 40\n100 80\n100 40\n70 70\n"


def coffee():
    return (SOURCE_DIR / "examples" / "coffee.jpg").read_bytes()


def slug(value):
    """A value as part of a case name."""
    return re.sub(r"\W", "_", value)


def speckle(x, y):
    return x % 3 == 0 and y % 3 == 0


# The command line itself.
case("cli_no_subcommand", "", code=2, words=("subcommand",))
case("cli_unknown_subcommand", "frobnicate in.png", {"in.png": IMG}, words=("frobnicate",))
case("cli_unknown_option", f"{MAG} --frobnicate 3", {"in.png": IMG}, words=("--frobnicate",))
case("cli_option_without_value", "magnify in.png -o out.png --lens", {"in.png": IMG},
     words=("--lens",))
case("cli_no_output", f"magnify in.png {LENS}", {"in.png": IMG}, words=("--output",))
case("cli_no_lens", "magnify in.png -o out.png", {"in.png": IMG}, words=("--lens",))

# Images: PNG and JPEG, damaged, lying about their size, or not files at all.
case("png_missing", f"magnify nothere.png -o out.png {LENS}", words=("nothere.png",))
case("png_empty_file", f"magnify empty.png -o out.png {LENS}", {"empty.png": b""},
     words=("empty.png", "empty"))
case("png_text_file", f"magnify text.png -o out.png {LENS}", {"text.png": "hello\n"},
     words=("text.png",))
case("png_signature_then_garbage", f"magnify bad.png -o out.png {LENS}",
     {"bad.png": b"\x89PNG\r\n\x1a\n" + b"garbage" * 40}, words=("bad.png",))
case("png_truncated", f"magnify cut.png -o out.png {LENS}", {"cut.png": mk.truncated(IMG)},
     words=("cut.png",))
case("png_bad_crc", f"magnify crc.png -o out.png --lens circle:16,16,4",
     {"crc.png": lambda _: mk.corrupt_crc_png()}, words=("crc.png",))
case("png_damaged_idat_byte", f"magnify dmg.png -o out.png --lens circle:16,16,4",
     {"dmg.png": lambda _: mk.damaged_idat_png()}, words=("dmg.png",))
case("png_header_claims_100000_squared", f"magnify huge.png -o out.png {LENS}",
     {"huge.png": mk.png_raw(100000, 100000, 2, 8, zlib.compress(b"\0" * 64))},
     words=("huge.png", "100000"))
case("png_header_claims_2gib_rgba16", f"magnify huge.png -o out.png {LENS}",
     {"huge.png": mk.png_raw(16384, 16384, 6, 16, zlib.compress(b"\0" * 64))},
     words=("huge.png", "PNG data"))
case("png_header_claims_more_than_data", f"magnify short.png -o out.png {LENS}",
     {"short.png": mk.png_raw(8000, 8000, 2, 8, zlib.compress(b"\0" * 5000))},
     words=("short.png",))
case("png_header_claims_16384_rgba_short", f"magnify short.png -o out.png {LENS}",
     {"short.png": mk.png_raw(16384, 16384, 6, 8, zlib.compress(b"\0" * 5000))},
     words=("short.png",))
case("png_zlib_bomb_16384_grey", f"magnify bomb.png -o out.png --size 128x128 "
     "--lens circle:8192,8192,800", {"bomb.png": lambda _: mk.zeros_png(16384, 16384)},
     code=0, outputs={"out.png": png_of_size(128, 128)})
case("png_palette_without_plte", f"magnify pal.png -o out.png {LENS}",
     {"pal.png": mk.png_raw(160, 120, 3, 8, zlib.compress(b"\0" * 121 * 120))},
     words=("pal.png",))
case("png_16bit_grey", "magnify g16.png -o out.png --lens circle:32,32,6",
     {"g16.png": mk.grey16_png(64, 64)}, code=0, outputs={"out.png": png_of_size(64, 64)})
case("png_one_pixel", "magnify dot.png -o out.png --lens circle:0.5,0.5,0.5",
     {"dot.png": mk.png(1, 1, lambda x, y: (9, 9, 9))}, code=0,
     outputs={"out.png": png_of_size(1, 1)})
case("jpeg_truncated", f"magnify cut.jpg -o out.png --lens circle:200,300,30",
     {"cut.jpg": lambda _: mk.truncated(coffee(), 0.3)}, words=("cut.jpg",))
case("jpeg_garbage_after_soi", f"magnify bad.jpg -o out.png {LENS}",
     {"bad.jpg": b"\xff\xd8\xff\xe0" + bytes(range(256)) * 8}, words=("bad.jpg",))
case("jpeg_header_claims_65500_squared", f"magnify huge.jpg -o out.png {LENS}",
     {"huge.jpg": lambda _: mk.jpeg_with_size(coffee(), 65500, 65500)}, words=("huge.jpg",))
case("jpeg_header_claims_16000_squared_short", f"magnify big.jpg -o out.png {LENS}",
     {"big.jpg": lambda _: mk.jpeg_with_size(coffee(), 16000, 16000)}, words=("big.jpg",))
case("jpeg_named_png", "magnify photo.png -o out.jpg --lens circle:200,300,30",
     {"photo.png": lambda _: coffee()}, code=0, outputs={"out.jpg": any_file})
case("image_is_empty_folder", f"magnify adir -o out.png {LENS}", {"adir": Folder()},
     words=("adir",))
case("image_dev_zero", f"magnify /dev/zero -o out.png {LENS}", words=("/dev/zero",))
case("image_fifo", f"magnify fifo.png -o out.png {LENS}", {"fifo.png": Fifo()},
     words=("fifo.png",))
case("image_dev_stdin", f"magnify /dev/stdin -o out.png {LENS}", words=("/dev/stdin",))

# Masks.
case("mask_all_speck", f"magnify in.png -o out.png --lens mask:m.png",
     {"in.png": IMG, "m.png": mk.mask_png(160, 120, speckle)}, words=("m.png", "4 pixels"))
case("mask_empty", "magnify in.png -o out.png --lens mask:m.png",
     {"in.png": IMG, "m.png": mk.mask_png(160, 120, lambda x, y: False)},
     words=("m.png", "non-zero"))
case("mask_wrong_size", "magnify in.png -o out.png --lens mask:m.png",
     {"in.png": IMG, "m.png": mk.mask_png(50, 50, lambda x, y: True)}, words=("m.png", "50"))
case("mask_truncated", "magnify in.png -o out.png --lens mask:m.png",
     {"in.png": IMG, "m.png": mk.truncated(mk.mask_png(160, 120, speckle), 0.6)},
     words=("m.png",))
case("mask_dev_zero", "magnify in.png -o out.png --lens mask:/dev/zero", {"in.png": IMG},
     words=("/dev/zero",))
case("mask_blob_with_speckle", "magnify in.png -o out.png --lens mask:m.png",
     {"in.png": IMG, "m.png": mk.mask_png(
         160, 120, lambda x, y: (70 <= x < 90 and 50 <= y < 70) or (x == 5 and y == 5))},
     code=0, outputs=OUT_OK, words=("speck",))
case("mask_whole_image", "magnify in.png -o out.png --lens mask:m.png",
     {"in.png": IMG, "m.png": mk.mask_png(160, 120, lambda x, y: True)}, code=0,
     outputs=OUT_OK)

# Polygon files.
case("polygon_comma_separated", "magnify in.png -o out.png --lens polygon:p.txt",
     {"in.png": IMG, "p.txt": SQUARE.replace(" ", ",")}, code=0, outputs=OUT_OK)
case("polygon_semicolon_separated", "magnify in.png -o out.png --lens polygon:p.txt",
     {"in.png": IMG, "p.txt": SQUARE.replace(" ", ";")}, code=0, outputs=OUT_OK)
case("polygon_closing_vertex", "magnify in.png -o out.png --lens polygon:p.txt",
     {"in.png": IMG, "p.txt": "# a square\n" + SQUARE + "60 40\n"}, code=0, outputs=OUT_OK)
case("polygon_mixed_separators_and_blanks", "magnify in.png -o out.png --lens polygon:p.txt",
     {"in.png": IMG, "p.txt": "60,40\n\n  100;40\n100 80  \r\n60\t80\n"}, code=0,
     outputs=OUT_OK)
case("polygon_self_intersecting", "magnify in.png -o out.png --lens polygon:p.txt",
     {"in.png": IMG, "p.txt": BOWTIE}, words=("p.txt", "intersect"))
case("polygon_300k_vertices", "magnify in.png -o out.png --lens polygon:p.txt",
     {"in.png": IMG, "p.txt": lambda _: mk.polygon_circle(300000, 80, 60, 12)}, code=0,
     outputs=OUT_OK)
case("polygon_100k_zigzag_self_intersecting", "magnify in.png -o out.png --lens polygon:p.txt",
     {"in.png": IMG, "p.txt": lambda _: mk.polygon_zigzag(50000, 20, 140, 30, 90)},
     words=("p.txt", ("intersect", "area")))
case("polygon_two_vertices", "magnify in.png -o out.png --lens polygon:p.txt",
     {"in.png": IMG, "p.txt": "60 40\n100 40\n"}, words=("p.txt", "3"))
case("polygon_nan", "magnify in.png -o out.png --lens polygon:p.txt",
     {"in.png": IMG, "p.txt": "60 40\nnan nan\n100 80\n"}, words=("p.txt",))
case("polygon_inf", "magnify in.png -o out.png --lens polygon:p.txt",
     {"in.png": IMG, "p.txt": "60 40\ninf 40\n100 80\n"}, words=("p.txt",))
case("polygon_1e308", "magnify in.png -o out.png --lens polygon:p.txt",
     {"in.png": IMG, "p.txt": "60 40\n1e308 40\n100 80\n"}, words=("p.txt", "outside"))
case("polygon_empty_file", "magnify in.png -o out.png --lens polygon:p.txt",
     {"in.png": IMG, "p.txt": ""}, words=("p.txt",))
case("polygon_binary_one_line", "magnify in.png -o out.png --lens polygon:p.bin",
     {"in.png": IMG, "p.bin": bytes(range(1, 256)).replace(b"\n", b"") * 8000},
     words=("p.bin",))
case("polygon_is_folder", "magnify in.png -o out.png --lens polygon:pdir",
     {"in.png": IMG, "pdir": Folder()}, words=("pdir",))
case("polygon_fifo", "magnify in.png -o out.png --lens polygon:fifo.txt",
     {"in.png": IMG, "fifo.txt": Fifo()}, words=("fifo.txt",))
case("polygon_missing", "magnify in.png -o out.png --lens polygon:none.txt", {"in.png": IMG},
     words=("none.txt",))

# Lens specs.
case("lens_circle_two_numbers", "magnify in.png -o out.png --lens circle:80,60",
     {"in.png": IMG}, words=("circle:80,60",))
case("lens_unknown_kind", "magnify in.png -o out.png --lens square:80,60,10", {"in.png": IMG},
     words=("square",))
case("lens_empty_spec", "magnify in.png -o out.png --lens ''", {"in.png": IMG},
     words=("circle:CX,CY,R",))
case("lens_nan_centre", "magnify in.png -o out.png --lens circle:nan,60,10", {"in.png": IMG},
     words=("centre",))
case("lens_centre_1e308", "magnify in.png -o out.png --lens circle:1e308,60,10",
     {"in.png": IMG}, words=("outside",))
case("lens_radius_1e308", "magnify in.png -o out.png --lens circle:80,60,1e308",
     {"in.png": IMG}, code=0, outputs=OUT_OK, words=("zoom 1 ",))
case("lens_radius_1e-308", "magnify in.png -o out.png --lens circle:80,60,1e-308",
     {"in.png": IMG}, words=("half a pixel",))
case("lens_zoom_garbage", "magnify in.png -o out.png --lens circle:80,60,10:2x",
     {"in.png": IMG}, words=("2x",))
case("lens_zoom_nan", "magnify in.png -o out.png --lens circle:80,60,10:nan", {"in.png": IMG},
     words=("zoom",))
case("lens_extra_field", "magnify in.png -o out.png --lens circle:80,60,10:2:3",
     {"in.png": IMG}, words=("circle:80,60,10:2:3",))
case("lens_200_circles", "magnify in.png -o out.png " + " ".join(
     f"--lens circle:{8 + 8 * (i % 20)},{8 + 11 * (i // 20)},1.5:1.5" for i in range(200)),
     {"in.png": IMG}, code=0, outputs=OUT_OK)

# Option values: NaN, infinity, negative, huge, not a number.
for option, values in {
        "--threads": ("nan", "-1", "1025", "99999999999999999999"),
        "--mesh": ("nan", "-5", "1e3", "3"),
        "--mesh-tolerance": ("nan", "inf", "-1"),
        "--zoom": ("inf", "nan", "0.5"),
        "--footprint": ("nan", "-1", "1e308"),
        "--tolerance": ("nan", "-1"),
        "--max-iterations": ("-1", "2147483648"),
        "--size": ("0x0", "1000000x1000000", "axb", "-5x5", "100x"),
        "--subdivide": ("9",),
        "--extent-factor": ("nan", "1"),
        "--alpha": ("inf",),
}.items():
    for value in values:
        case(f"option_{slug(option.strip('-'))}_{slug(value)}", f"{MAG} {option} {value}",
             {"in.png": IMG}, words=((option, option.strip("-").replace("-", " ")),))
case("option_mesh_tolerance_1e308", f"{MAG} --mesh-tolerance 1e308", {"in.png": IMG}, code=0,
     outputs=OUT_OK)
case("option_threads_64", f"{MAG} --threads 64", {"in.png": IMG}, code=0, outputs=OUT_OK)

# Outputs: the input however spelled, links, folders, devices, parts of inputs.
case("output_is_input", f"magnify in.png -o in.png {LENS}", {"in.png": IMG},
     words=("in.png", "input"))
case("output_is_input_spelled_otherwise", f"magnify in.png -o sub/../in.png {LENS}",
     {"in.png": IMG, "sub": Folder()}, words=("sub/../in.png", "input"))
case("output_symlink_to_input", f"magnify in.png -o link.png {LENS}",
     {"in.png": IMG, "link.png": Link("in.png")}, words=("link.png", "input"))
case("output_hard_link_to_input", f"magnify in.png -o hard.png {LENS}",
     {"in.png": IMG, "hard.png": HardLink("in.png")}, words=("hard.png", "input"))
case("output_dangling_symlink", f"magnify in.png -o dangling.png {LENS}",
     {"in.png": IMG, "dangling.png": Link("missing.png")}, words=("dangling.png", "missing"))
case("output_is_folder", f"magnify in.png -o adir.png {LENS}",
     {"in.png": IMG, "adir.png": Folder()}, words=("adir.png", "folder"))
case("output_in_missing_folder", f"magnify in.png -o nowhere/out.png {LENS}", {"in.png": IMG},
     words=("nowhere",))
case("output_in_unwritable_folder", f"magnify in.png -o ro/out.png {LENS}",
     {"in.png": IMG, "ro": Folder(0o555)}, words=("ro/out.png", "ermission denied"),
     as_nobody=True)
case("output_unknown_extension", f"magnify in.png -o out.gif {LENS}", {"in.png": IMG},
     words=("out.gif",))
case("output_no_extension", f"magnify in.png -o out {LENS}", {"in.png": IMG}, words=("out",))
case("output_dev_null", f"magnify in.png -o /dev/null {LENS}", {"in.png": IMG},
     words=("/dev/null",))
case("output_symlink_followed", f"magnify in.png -o link.png {LENS}",
     {"in.png": IMG, "old.png": b"old", "link.png": Link("old.png")}, code=0,
     outputs={"old.png": png_of_size(160, 120)})
case("stats_same_as_output", f"{MAG} --stats out.png", {"in.png": IMG},
     words=("--stats", "out.png"))
case("stats_is_input_spelled_otherwise", f"{MAG} --stats ./in.png", {"in.png": IMG},
     words=("--stats", "./in.png", "input"))
case("stats_is_folder", f"{MAG} --stats adir", {"in.png": IMG, "adir": Folder()},
     words=("--stats", "adir"))
case("stats_dangling_symlink", f"{MAG} --stats s.json", {"in.png": IMG, "s.json": Link("no/s")},
     words=("--stats", "s.json"))
case("stats_dev_null", f"{MAG} --stats /dev/null", {"in.png": IMG}, code=0, outputs=OUT_OK)
case("stats_dev_full", f"{MAG} --stats /dev/full", {"in.png": IMG}, code=1,
     words=("/dev/full",))
case("stats_symlink_followed", f"{MAG} --stats s.json",
     {"in.png": IMG, "real.json": "old", "s.json": Link("real.json")}, code=0,
     outputs=dict(OUT_OK, **{"real.json": json_with("lenses", "timings_ms")}))
case("before_after_is_input", f"{MAG} --before-after ./in.png", {"in.png": IMG},
     words=("--before-after", "input"))
case("export_mesh_over_polygon_file", "magnify in.png -o out.png --lens polygon:m_flat.obj "
     "--export-mesh m", {"in.png": IMG, "m_flat.obj": SQUARE}, words=("--export-mesh",
                                                                      "m_flat.obj"))
case("output_over_mask_file", "magnify in.png -o m.png --lens mask:m.png",
     {"in.png": IMG, "m.png": mk.mask_png(160, 120, lambda x, y: 70 <= x < 90 and 50 <= y < 70)},
     words=("m.png", "mask"))
case("overlay_dev_zero", f"{MAG} --overlay /dev/zero", {"in.png": IMG}, words=("/dev/zero",))
case("overlay_nested_100000", f"{MAG} --overlay o.geojson",
     {"in.png": IMG, "o.geojson": mk.nested_geojson(100000)}, words=("o.geojson", "256"))

# SVG.
SVG_OK = ('<svg xmlns="http://www.w3.org/2000/svg" width="160" height="120">'
          '<rect x="10" y="10" width="100" height="60" fill="black"/></svg>')
SVG_LENS = "-o out.png --lens circle:80,60,10"
case("svg_malformed", f"magnify bad.svg {SVG_LENS}",
     {"bad.svg": SVG_OK.replace("<rect", "<rect x=\"1\" <oops/")},
     words=("bad.svg",))
case("svg_empty_file", f"magnify empty.svg {SVG_LENS}", {"empty.svg": ""}, words=("empty.svg",))
case("svg_size_1e30", f"magnify big.svg {SVG_LENS}",
     {"big.svg": SVG_OK.replace('width="160" height="120"', 'width="1e30" height="1e30"')},
     words=("big.svg",))
case("svg_zero_size", f"magnify zero.svg {SVG_LENS}",
     {"zero.svg": SVG_OK.replace('width="160" height="120"', 'width="0" height="0"')},
     words=("zero.svg",))
case("svg_billion_laughs", f"magnify laughs.svg {SVG_LENS}", {"laughs.svg": (
    '<?xml version="1.0"?><!DOCTYPE svg [<!ENTITY a "aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa">' +
    "".join(f'<!ENTITY {chr(98 + i)} "' + f"&{chr(97 + i)};" * 10 + '">' for i in range(9)) +
    ']><svg xmlns="http://www.w3.org/2000/svg" width="160" height="120"><text y="20">&j;'
    '</text></svg>')}, words=("laughs.svg",))
case("svg_image_of_dev_zero", f"magnify zero.svg {SVG_LENS}", {"zero.svg": SVG_OK.replace(
    "</svg>", '<image href="file:///dev/zero" width="50" height="50"/></svg>')}, code=0,
    outputs=OUT_OK)
case("svg_huge_stroke", f"magnify wide.svg {SVG_LENS}", {"wide.svg": SVG_OK.replace(
    'fill="black"', 'fill="none" stroke="red" stroke-width="1e300"')}, code=0, outputs=OUT_OK)

# Vector maps (GeoJSON in degrees) and their styles.
MAP = mk.line_geojson([(0, 0), (10, 10)])
MAP_LENS = "--size 160x120 -o out.png --lens circle:80,60,10"
case("map_source_nested_100000", f"magnify deep.geojson {MAP_LENS}",
     {"deep.geojson": mk.nested_geojson(100000)}, words=("deep.geojson", "256"))
case("map_source_bad_coordinates", f"magnify bad.geojson {MAP_LENS}",
     {"bad.geojson": mk.line_geojson([('"a"', '"b"'), (1, 1)])},
     words=("bad.geojson", "feature 0"))
case("map_source_longitude_500", f"magnify far.geojson {MAP_LENS}",
     {"far.geojson": mk.line_geojson([(0, 0), (500, 10)])}, words=("far.geojson", "500"))
case("map_source_number_1e999", f"magnify big.geojson {MAP_LENS}",
     {"big.geojson": mk.line_geojson([(0, 0), ("1e999", 10)])}, words=("big.geojson",))
case("map_source_nan_literal", f"magnify nan.geojson {MAP_LENS}",
     {"nan.geojson": mk.line_geojson([(0, 0), ("NaN", 10)])}, words=("nan.geojson",))
case("map_source_empty_collection", f"magnify none.geojson {MAP_LENS}",
     {"none.geojson": '{"type":"FeatureCollection","features":[]}'}, words=("none.geojson",))
case("map_source_pole", f"magnify pole.geojson {MAP_LENS}",
     {"pole.geojson": mk.line_geojson([(0, 0), (10, 90), (-10, -90)])}, code=0,
     outputs=OUT_OK)
case("map_source_over_max_points", f"magnify line.geojson {MAP_LENS} --max-points 1",
     {"line.geojson": MAP}, words=("line.geojson", "--max-points"))
case("map_source_max_points_1e30", f"magnify line.geojson {MAP_LENS} --max-points 1e30",
     {"line.geojson": MAP}, words=("--max-points", "1e30"))
case("map_source_one_point", f"magnify one.geojson {MAP_LENS}",
     {"one.geojson": '{"type":"Point","coordinates":[5,5]}'}, code=0, outputs=OUT_OK)
STYLE = '{"layers":[{"geometry":"line","stroke":"#ff0000","width":%s}]}'
case("style_width_1e300", f"magnify m.geojson --style s.json {MAP_LENS}",
     {"m.geojson": MAP, "s.json": STYLE % "1e300"}, words=("s.json", "width"))
case("style_width_negative", f"magnify m.geojson --style s.json {MAP_LENS}",
     {"m.geojson": MAP, "s.json": STYLE % "-3"}, words=("s.json", "width"))
case("style_number_1e999", f"magnify m.geojson --style s.json {MAP_LENS}",
     {"m.geojson": MAP, "s.json": STYLE % "1e999"}, words=("s.json",))
case("style_radius_1e300", f"magnify m.geojson --style s.json {MAP_LENS}",
     {"m.geojson": MAP, "s.json": '{"layers":[{"geometry":"point","radius":1e300}]}'},
     words=("s.json", "radius"))
case("style_not_json", f"magnify m.geojson --style s.json {MAP_LENS}",
     {"m.geojson": MAP, "s.json": "layers: none"}, words=("s.json",))
case("style_nested_100000", f"magnify m.geojson --style s.json {MAP_LENS}",
     {"m.geojson": MAP, "s.json": "[" * 100000 + "]" * 100000}, words=("s.json", "256"))
case("style_fifo", f"magnify m.geojson --style s.json {MAP_LENS}",
     {"m.geojson": MAP, "s.json": Fifo()}, words=("s.json",))

# geolens map: CSV and GeoJSON points through the lens.
CSV = "x,y,name\n80,60,centre\n85,62,near\n10,10,far\n"
MAP_ARGS = "--size 160x120 --lens circle:80,60,10"
case("csv_valid_to_file", f"map in.csv {MAP_ARGS} -o out.csv", {"in.csv": CSV}, code=0,
     outputs={"out.csv": csv_rows(3)})
case("csv_bad_number", f"map in.csv {MAP_ARGS}", {"in.csv": "x,y\n1,2\n3,oops\n"},
     words=("in.csv", "3"))
case("csv_nan", f"map in.csv {MAP_ARGS}", {"in.csv": "x,y\nnan,nan\n"}, words=("in.csv",))
case("csv_inf", f"map in.csv {MAP_ARGS}", {"in.csv": "x,y\ninf,5\n"}, words=("in.csv",))
case("csv_1e308_dropped", f"map in.csv {MAP_ARGS} -o out.csv",
     {"in.csv": "x,y\n1e308,1e308\n80,60\n"}, code=0, outputs={"out.csv": csv_rows(1)},
     words=("dropped",))
case("csv_empty_file", f"map in.csv {MAP_ARGS} -o out.csv", {"in.csv": ""}, code=0,
     outputs={"out.csv": csv_rows(0)})
case("csv_8mb_line", f"map in.csv {MAP_ARGS}", {"in.csv": "x,y\n7," + "a" * (8 << 20)},
     words=("in.csv:2",))
case("csv_binary", f"map in.csv {MAP_ARGS}", {"in.csv": bytes(range(256)) * 64},
     words=("in.csv",))
case("csv_stdin_with_format", f"map - --format csv {MAP_ARGS}", stdin=CSV.encode(), code=0,
     stdout_check=lambda out: None if out.count(b"\n") == 4 else f"stdout: {out[:200]!r}")
case("map_output_dev_stdout", f"map in.csv {MAP_ARGS} -o /dev/stdout", {"in.csv": CSV}, code=0,
     stdout_check=lambda out: None if out.count(b"\n") == 4 else f"stdout: {out[:200]!r}")
case("csv_stdin_without_format", f"map - {MAP_ARGS}", stdin=CSV.encode(), words=("--format",))
case("csv_fifo", f"map f.csv {MAP_ARGS}", {"f.csv": Fifo()}, words=("f.csv",))
case("csv_folder", f"map d.csv {MAP_ARGS}", {"d.csv": Folder()}, words=("d.csv",))
case("map_output_is_input", f"map in.csv {MAP_ARGS} -o ./in.csv", {"in.csv": CSV},
     words=("./in.csv", "input"))
case("map_image_dev_zero", "map in.csv --image /dev/zero --lens circle:80,60,10",
     {"in.csv": CSV}, words=("/dev/zero",))
case("map_no_frame", "map in.csv --lens circle:80,60,10", {"in.csv": CSV}, words=("--size",))
for value in ("nan", "-1", "1e-300"):
    case("map_max_segment_" + slug(value),
         f"map in.csv {MAP_ARGS} --max-segment {value}", {"in.csv": CSV},
         words=("--max-segment", value))
case("map_max_segment_inf", f"map in.csv {MAP_ARGS} --max-segment inf -o out.csv",
     {"in.csv": CSV}, code=0, outputs={"out.csv": csv_rows(3)})
LINE = ('{"type":"Feature","properties":{},"geometry":{"type":"LineString",'
        '"coordinates":[[10,10],[%s,20]]}}')
case("map_line_to_1e300", f"map l.geojson {MAP_ARGS} -o out.geojson",
     {"l.geojson": LINE % "1e300"}, code=0, outputs={"out.geojson": json_with("type")},
     words=("cut",))
case("map_line_densified_to_15m_vertices", f"map z.geojson {MAP_ARGS} --max-segment 0.01 "
     "-o out.geojson", {"z.geojson": '{"type":"LineString","coordinates":[' +
                        ",".join(f"[{10 + 140 * (i % 2)},{10 + i * 0.08}]" for i in range(1100)) +
                        "]}"}, words=("z.geojson", "--max-segment"))
case("map_geojson_nested_100000", f"map deep.geojson {MAP_ARGS}",
     {"deep.geojson": mk.nested_geojson(100000)}, words=("deep.geojson", "256"))
case("map_output_other_format", f"map in.csv {MAP_ARGS} -o out.geojson", {"in.csv": CSV},
     words=("out.geojson",))

# Tile folders (z/x/y.png) and level lists (.levels).
TILE = mk.png(32, 32, lambda x, y: (100, 100, 100))
TILES = {"t/0/0/0.png": TILE, **{f"t/1/{x}/{y}.png": TILE for x in (0, 1) for y in (0, 1)}}
TILE_ARGS = "--size 64x64 --lens circle:24,24,6:2 -o out.png"
case("tiles_valid", f"magnify t {TILE_ARGS}", TILES, code=0,
     outputs={"out.png": png_of_size(64, 64)})
case("tiles_zoom_40", f"magnify t {TILE_ARGS}", dict(TILES, **{"t/40/0/0.png": TILE}),
     words=("t", "30"))
case("tiles_zoom_past_2_64_ignored", f"magnify t {TILE_ARGS}",
     dict(TILES, **{"t/18446744073709551617/0/0.png": TILE}), code=0,
     outputs={"out.png": png_of_size(64, 64)})
case("tiles_missing_zoom", f"magnify t {TILE_ARGS}", {"t/0/0/0.png": TILE, "t/2/0/0.png": TILE},
     words=("t", "missing zoom"))
case("tiles_corrupt_tile", f"magnify t {TILE_ARGS}",
     dict(TILES, **{"t/1/0/0.png": b"\x89PNG\r\n\x1a\nbroken"}), words=("0.png",))
case("tiles_mixed_sizes", f"magnify t {TILE_ARGS}",
     dict(TILES, **{"t/1/0/0.png": mk.png(16, 16, lambda x, y: (1, 1, 1))}), words=("16",))
case("tiles_tile_fifo_drawn_as_missing", f"magnify t {TILE_ARGS}",
     dict(TILES, **{"t/1/0/0.png": Fifo()}), code=0, outputs={"out.png": png_of_size(64, 64)})
case("tiles_output_inside", "magnify t --size 64x64 --lens circle:24,24,6:2 -o t/1/0/0.png",
     TILES, words=("t/1/0/0.png", "tile folder"))
case("tiles_stats_inside", f"magnify t {TILE_ARGS} --stats t/s.json", TILES,
     words=("t/s.json", "tile folder"))
FINE, COARSE = mk.png(128, 128, lambda x, y: (60,) * 3), mk.png(32, 32, lambda x, y: (90,) * 3)
LEVELS = {"fine.png": FINE, "coarse.png": COARSE, "m.levels": "fine.png\ncoarse.png\n"}
LEVEL_ARGS = "--lens circle:16,16,3:2 -o out.png"
case("levels_valid", f"magnify m.levels {LEVEL_ARGS}", LEVELS, code=0,
     outputs={"out.png": png_of_size(32, 32)})
case("levels_empty", f"magnify m.levels {LEVEL_ARGS}", {"m.levels": ""}, words=("m.levels",))
case("levels_missing_image", f"magnify m.levels {LEVEL_ARGS}", {"m.levels": "gone.png\n"},
     words=("gone.png",))
case("levels_lists_itself", f"magnify m.levels {LEVEL_ARGS}", {"m.levels": "m.levels\n"},
     words=("m.levels",))
case("levels_dev_zero", f"magnify m.levels {LEVEL_ARGS}", {"m.levels": "/dev/zero\n"},
     words=("/dev/zero",))
case("levels_extents_disagree", f"magnify m.levels {LEVEL_ARGS}",
     dict(LEVELS, **{"coarse.png": mk.png(64, 40, lambda x, y: (1, 1, 1))}),
     words=("coarse.png",))
case("levels_output_is_level", "magnify m.levels --lens circle:16,16,3:2 -o coarse.png", LEVELS,
     words=("coarse.png", "input"))

# Meshes: OBJ and PLY.
SCENE_ARGS = "--size 160x120 -o out.png --lens circle:80,60,10"
case("obj_valid_cube", f"magnify c.obj {SCENE_ARGS}", {"c.obj": mk.cube_obj()}, code=0,
     outputs=OUT_OK)
case("obj_face_index_out_of_range", f"magnify c.obj {SCENE_ARGS}",
     {"c.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"}, words=("c.obj", "9"))
case("obj_face_index_20_digits", f"magnify c.obj {SCENE_ARGS}",
     {"c.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n"}, words=("c.obj",))
case("obj_no_triangle", f"magnify c.obj {SCENE_ARGS}", {"c.obj": "v 0 0 0\n"},
     words=("c.obj", "triangle"))
case("obj_nan_vertex", f"magnify c.obj {SCENE_ARGS}",
     {"c.obj": "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"}, words=("c.obj",))
case("obj_1e308_vertex", f"magnify c.obj {SCENE_ARGS}",
     {"c.obj": "v 0 0 0\nv 1e308 0 0\nv 0 1e308 0\nv -1e308 -1e308 1e308\nf 1 2 3\nf 2 3 4\n"},
     words=("c.obj",))
case("obj_over_max_vertices", f"magnify c.obj {SCENE_ARGS} --max-vertices 7",
     {"c.obj": mk.cube_obj()}, words=("c.obj", "8 vertices", "--max-vertices"))
case("obj_max_vertices_raised", f"magnify c.obj {SCENE_ARGS} --max-vertices 8",
     {"c.obj": mk.cube_obj()}, code=0, outputs=OUT_OK)
case("obj_max_vertices_zero", f"magnify c.obj {SCENE_ARGS} --max-vertices 0",
     {"c.obj": mk.cube_obj()}, words=("--max-vertices", "0"))
case("obj_one_point_repeated", f"magnify c.obj {SCENE_ARGS}",
     {"c.obj": "v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n"}, code=0, outputs=OUT_OK)
case("obj_binary", f"magnify c.obj {SCENE_ARGS}", {"c.obj": bytes(range(256)) * 64},
     words=("c.obj",))
case("obj_view_nan", f"magnify c.obj {SCENE_ARGS} --view nan,0", {"c.obj": mk.cube_obj()},
     words=("view", "nan,0"))
case("obj_view_elevation_1e308", f"magnify c.obj {SCENE_ARGS} --view 0,1e308",
     {"c.obj": mk.cube_obj()}, words=("view", "elevation"))
case("obj_view_azimuth_1e308", f"magnify c.obj {SCENE_ARGS} --view 1e308,0",
     {"c.obj": mk.cube_obj()}, code=0, outputs=OUT_OK)
case("ply_vertex_count_2_31", f"magnify m.ply {SCENE_ARGS}",
     {"m.ply": mk.ply_header(2147483647, 1) + b"\0" * 49}, words=("m.ply", "2147483647"))
case("ply_vertex_count_20_digits", f"magnify m.ply {SCENE_ARGS}",
     {"m.ply": mk.ply_header("99999999999999999999", 1) + b"\0" * 49}, words=("m.ply",))
case("ply_rows_without_properties", f"magnify m.ply {SCENE_ARGS}", {"m.ply": (
    b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
    b"property float y\nproperty float z\nelement junk 1000000000000000000\nelement face 1\n"
    b"property list uchar int vertex_indices\nend_header\n" + b"\0" * 49)}, words=("m.ply",))
case("ply_ascii_claims_10_9", f"magnify m.ply {SCENE_ARGS}",
     {"m.ply": mk.ply_header(1000000000, 1, "ascii") + b"0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
     words=("m.ply",))
case("ply_face_list_of_255", f"magnify m.ply {SCENE_ARGS}",
     {"m.ply": mk.ply_header(3, 1) + struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) +
      b"\xff" + struct.pack("<3i", 0, 1, 2)}, words=("m.ply",))
case("ply_no_end_header", f"magnify m.ply {SCENE_ARGS}",
     {"m.ply": b"ply\nformat ascii 1.0\nelement vertex 3\n" + b"comment x\n" * 100000},
     words=("m.ply",))

# Volumes: NIfTI and NRRD.
SPHERE = bytes(200 if (i - 7.5) ** 2 + (j - 7.5) ** 2 + (k - 7.5) ** 2 < 36 else 0
               for k in range(16) for j in range(16) for i in range(16))
case("nifti_valid", f"magnify v.nii {SCENE_ARGS}",
     {"v.nii": mk.nifti((16, 16, 16), data=SPHERE)}, code=0, outputs=OUT_OK)
case("nifti_vox_offset_1e10", f"magnify v.nii {SCENE_ARGS}",
     {"v.nii": mk.nifti((16, 16, 16), vox_offset=1e10, data=SPHERE)}, words=("v.nii",))
case("nifti_claims_2000_cubed", f"magnify v.nii {SCENE_ARGS}",
     {"v.nii": mk.nifti((2000, 2000, 2000), data=SPHERE)}, words=("v.nii", "2000"))
case("nifti_gzip_bomb_trailing_256mb", f"magnify v.nii.gz {SCENE_ARGS}",
     {"v.nii.gz": lambda _: mk.gzip_zeros(mk.nifti((16, 16, 16), data=SPHERE), 256 << 20)},
     code=0, outputs=OUT_OK)
case("nifti_gzip_claims_more_than_stream", f"magnify v.nii.gz {SCENE_ARGS}",
     {"v.nii.gz": mk.gzipped(mk.nifti((512, 512, 512)))}, words=("v.nii.gz",))
case("nifti_truncated_header", f"magnify v.nii {SCENE_ARGS}",
     {"v.nii": mk.nifti((16, 16, 16))[:100]}, words=("v.nii",))
case("nifti_unknown_datatype", f"magnify v.nii {SCENE_ARGS}",
     {"v.nii": mk.nifti((16, 16, 16), datatype=999, data=SPHERE)}, words=("v.nii",))
case("nifti_short_data", f"magnify v.nii {SCENE_ARGS}",
     {"v.nii": mk.nifti((16, 16, 16), data=SPHERE[:100])}, words=("v.nii",))
case("nrrd_valid", f"magnify v.nrrd {SCENE_ARGS}", {"v.nrrd": mk.nrrd((16, 16, 16), data=SPHERE)},
     code=0, outputs=OUT_OK)
case("nrrd_claims_huge", f"magnify v.nrrd {SCENE_ARGS}",
     {"v.nrrd": mk.nrrd((65536, 65536, 3), encoding="gzip", data=b"xx")},
     words=("v.nrrd", "65536"))
case("nrrd_detached_dev_zero", f"magnify v.nrrd {SCENE_ARGS}",
     {"v.nrrd": mk.nrrd((16, 16, 16), extra="data file: /dev/zero\n")},
     words=("v.nrrd", "/dev/zero"))
case("nrrd_detached_missing", f"magnify v.nrrd {SCENE_ARGS}",
     {"v.nrrd": mk.nrrd((16, 16, 16), extra="data file: gone.raw\n")}, words=("gone.raw",))
case("nrrd_detached_itself", f"magnify v.nrrd {SCENE_ARGS}",
     {"v.nrrd": mk.nrrd((16, 16, 16), extra="data file: v.nrrd\n")}, words=("v.nrrd",))
case("nrrd_stats_over_detached_data", f"magnify v.nrrd {SCENE_ARGS} --stats v.raw",
     {"v.nrrd": mk.nrrd((16, 16, 16), extra="data file: v.raw\n"), "v.raw": SPHERE},
     words=("--stats", "v.raw"))
case("nrrd_short_data", f"magnify v.nrrd {SCENE_ARGS}",
     {"v.nrrd": mk.nrrd((16, 16, 16), data=SPHERE[:10])}, words=("v.nrrd",))
case("nrrd_zero_size", f"magnify v.nrrd {SCENE_ARGS}", {"v.nrrd": mk.nrrd((16, 0, 16))},
     words=("v.nrrd",))
case("nrrd_negative_size", f"magnify v.nrrd {SCENE_ARGS}",
     {"v.nrrd": mk.nrrd((16, -4, 16), data=SPHERE)}, words=("v.nrrd",))
case("nrrd_corrupt_gzip", f"magnify v.nrrd {SCENE_ARGS}",
     {"v.nrrd": mk.nrrd((16, 16, 16), encoding="gzip", data=b"\x1f\x8b\x08\0garbage" * 9)},
     words=("v.nrrd",))
case("nrrd_gzip_claims_a_gigabyte", f"magnify v.nrrd {SCENE_ARGS}",  # allocated 1 GiB, once
     {"v.nrrd": mk.nrrd((1024, 1024, 256), "float", "gzip", data=mk.gzipped(bytes(1000)))},
     words=("v.nrrd", "1073741824 bytes", "the gzip data holds 1000 bytes"))
case("volume_transfer_dev_zero", f"magnify v.nrrd {SCENE_ARGS} --transfer /dev/zero",
     {"v.nrrd": mk.nrrd((16, 16, 16), data=SPHERE)}, words=("/dev/zero",))
case("volume_transfer_bad_table", f"magnify v.nrrd {SCENE_ARGS} --transfer t.txt",
     {"v.nrrd": mk.nrrd((16, 16, 16), data=SPHERE), "t.txt": "0 1 2\nnan 0 0 0 0\n"},
     words=("t.txt",))

# geolens compare.
CMP = "compare in.png --lens circle:80,60,10"
case("compare_valid", f"{CMP} -o out --tile 64 --baseline-mesh 40 --mesh 40", {"in.png": IMG},
     code=0, outputs={"out": lambda p: None if (Path(p) / "report.json").exists() and
                      any_png(str(Path(p) / "panel.png")) is None else "no report or panel"})
case("compare_output_is_file", f"{CMP} -o afile", {"in.png": IMG, "afile": "x"},
     words=("afile",))
case("compare_output_dev_null", f"{CMP} -o /dev/null", {"in.png": IMG}, words=("/dev/null",))
case("compare_input_dev_zero", "compare /dev/zero --lens circle:80,60,10 -o out",
     words=("/dev/zero",))
case("compare_output_parent_missing", f"{CMP} -o nowhere/out", {"in.png": IMG},
     words=("nowhere",))
case("compare_input_is_an_output", "compare out/geometric.png --lens circle:80,60,10 -o out",
     {"out/geometric.png": IMG}, words=("out/geometric.png", "input"))
case("compare_tile_100000", f"{CMP} -o out --tile 100000", {"in.png": IMG}, words=("--tile",))
case("compare_jpeg_quality_0", f"{CMP} -o out --format jpg --jpeg-quality 0", {"in.png": IMG},
     words=("--jpeg-quality",))
case("compare_heat_max_nan", f"{CMP} -o out --heat-max nan", {"in.png": IMG},
     words=("--heat-max",))
case("compare_heat_max_inf", f"{CMP} -o out --heat-max inf", {"in.png": IMG},
     words=("--heat-max",))
case("compare_baseline_mesh_99999", f"{CMP} -o out --baseline-mesh 99999", {"in.png": IMG},
     words=("--baseline-mesh",))
case("compare_format_bmp", f"{CMP} -o out --format bmp", {"in.png": IMG}, words=("bmp",))
case("compare_sweep_two_lenses", f"{CMP} --lens circle:20,20,5 -o out --sweep",
     {"in.png": IMG}, words=("--sweep",))
case("compare_overlapping_lenses", f"{CMP} --lens circle:85,60,10 -o out", {"in.png": IMG},
     words=("overlap",))
case("compare_self_intersecting_polygon", "compare in.png --lens polygon:p.txt -o out",
     {"in.png": IMG, "p.txt": BOWTIE}, words=("p.txt", "intersect"))
case("compare_threads_nan", f"{CMP} -o out --threads nan", {"in.png": IMG},
     words=("--threads",))


# ----------------------------------------------------------------------------------------------
# The table


def row(name, r, problems, verdict):
    message = r.stderr.strip().replace("\n", " | ")
    if len(message) > 110:
        message = message[:107] + "..."
    return f"{name:<38} {r.code:>4}  {r.seconds:6.2f} {r.peak_mb:7.1f}  {verdict:<5} {message}"


def main(argv):
    if len(argv) < 2:
        print(__doc__)
        return 2
    cli = str(Path(argv[1]).resolve())
    selected = [c for c in CASES if len(argv) == 2 or any(s in c.name for s in argv[2:])]
    names = [c.name for c in CASES]
    assert len(names) == len(set(names)), "two cases share a name"
    assert set(KNOWN_DEFECTS) <= set(names), set(KNOWN_DEFECTS) - set(names)
    root = Path(tempfile.mkdtemp(prefix="geolens-battery-"))
    io_folder = root / "_io"
    io_folder.mkdir()
    failed, known, fixed = [], [], []
    started = time.monotonic()
    print(f"{'case':<38} {'exit':>4}  {'time s':>6} {'peak MB':>7}  {'':<5} message")
    try:
        for c in selected:
            r, problems = run_case(cli, c, root, io_folder)
            if c.name in KNOWN_DEFECTS:
                verdict = "KNOWN" if problems else "FIXED"
                (known if problems else fixed).append((c, problems))
            else:
                verdict = "FAIL" if problems else "ok"
                if problems:
                    failed.append((c, problems))
            print(row(c.name, r, problems, verdict), flush=True)
            for problem in problems:
                print(f"{'':<40}- {problem}")
    finally:
        shutil.rmtree(root, ignore_errors=True)
    print(f"\n{len(selected)} cases in {time.monotonic() - started:.1f} s: {len(failed)} failed, "
          f"{len(known)} known defects, {len(fixed)} known defects now passing")
    for c, problems in known:
        print(f"known defect {c.name}: {KNOWN_DEFECTS[c.name]}")
    for c, _ in fixed:
        print(f"FIXED: {c.name} passes now: remove it from KNOWN_DEFECTS")
    for c, problems in failed:
        print(f"FAILED: {c.name}: geolens {c.args}: " + "; ".join(problems))
    return 1 if failed or fixed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
