#!/usr/bin/env python3
"""Lists the functions longer than a limit (default 80 lines, the house's bound) in the C++ of
src/, apps/ and python/, longest first, and prints their count: a function is a definition that
starts at the file's or a namespace's level (a signature with its parentheses, then `{` on its
own line's end) and ends at its matching brace; lambdas and member functions defined inside a
class count with what encloses them. Usage: scripts/function_lengths.py [LIMIT]"""
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
FOLDERS = ("src", "apps", "python")
# A definition's first line: not indented (the house does not indent namespaces), not a
# namespace, class, struct, enum or a statement.
START = re.compile(r"^(?!namespace|class |struct |enum |union |#|//|}|using |template <)\S.*\(")


def strip(line):
    """The line without its comment and string or character literals (which may hold braces)."""
    line = re.sub(r'"(\\.|[^"\\])*"', '""', line)
    line = re.sub(r"'(\\.|[^'\\])*'", "''", line)
    return line.split("//")[0]


def functions(path):
    lines = path.read_text().split("\n")
    i = 0
    while i < len(lines):
        if not START.match(lines[i]):
            i += 1
            continue
        # The signature may run over several lines; the body opens with the first `{`.
        j = i
        while j < len(lines) and "{" not in strip(lines[j]) and ";" not in strip(lines[j]):
            j += 1
        if j == len(lines) or ";" in strip(lines[j]).split("{")[0]:
            i = j + 1
            continue
        depth, k = 0, j
        while k < len(lines):
            depth += strip(lines[k]).count("{") - strip(lines[k]).count("}")
            if depth <= 0:
                break
            k += 1
        name = re.search(r"([\w:~]+(?:operator\S+)?)\s*\(", lines[i])
        yield (k - i + 1, f"{path.relative_to(ROOT)}:{i + 1}", name.group(1) if name else "?")
        i = k + 1


def main():
    limit = int(sys.argv[1]) if len(sys.argv) > 1 else 80
    found = []
    for folder in FOLDERS:
        for path in sorted((ROOT / folder).rglob("*.cpp")):
            found += [f for f in functions(path) if f[0] > limit]
    for length, where, name in sorted(found, reverse=True):
        print(f"{length:5d}  {name}  {where}")
    print(f"{len(found)} functions over {limit} lines")


if __name__ == "__main__":
    main()
