#!/usr/bin/env python3
"""The project's layout against its rules, printed: what app/ holds (the applications
only: cli/ and gui/), and in the physics libraries (atmosphere/, eclipse/, terrain/, sky/)
the files over 800 lines and the functions over 100 lines. Exit status 0 either way: a
report, not a test.

Functions are found by their braces: a line at column 0 that opens a definition (it ends
in '{' after a ')', or begins a parameter list continued below) up to its matching '}'.
Lambdas count with the function that holds them.

Usage: scripts/layout-report.py [ROOT]   (ROOT: the checkout, default the script's parent)
"""
import pathlib
import re
import sys

MAX_FILE_LINES = 800
MAX_FUNCTION_LINES = 100
PHYSICS = ["atmosphere", "eclipse", "terrain", "sky"]


def functions(lines):
    """(first line number, length, signature) of each top-level function definition."""
    out, i = [], 0
    start = re.compile(r"^[A-Za-z].*(\)\s*(const)?\s*(override)?\s*\{\s*$|[(,]\s*$)")
    while i < len(lines):
        if not start.match(lines[i]) or lines[i].startswith(("namespace", "struct", "class", "enum", "#")):
            i += 1
            continue
        j = i
        while j < len(lines) and not lines[j].rstrip().endswith("{"):
            if lines[j].rstrip().endswith(";"):
                break
            j += 1
        if j >= len(lines) or not lines[j].rstrip().endswith("{"):
            i = j + 1
            continue
        depth, k = 0, j
        while k < len(lines):
            depth += lines[k].count("{") - lines[k].count("}")
            if depth <= 0:
                break
            k += 1
        out.append((i + 1, k - i + 1, lines[i].strip()))
        i = k + 1
    return out


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
    app = sorted(p.name for p in (root / "app").iterdir() if p.is_dir())
    others = [d for d in app if d not in ("cli", "gui")]
    print(f"app/ holds: {', '.join(app)}" + (f"  (not applications: {', '.join(others)})" if others else ""))
    big, long = [], []
    for folder in PHYSICS:
        for path in sorted((root / folder).rglob("*")):
            if path.suffix not in (".cpp", ".hpp", ".h", ".cxx") or not path.is_file():
                continue
            lines = path.read_text(encoding="utf-8", errors="replace").split("\n")
            rel = path.relative_to(root)
            if len(lines) > MAX_FILE_LINES:
                big.append((len(lines), rel))
            for first, length, signature in functions(lines):
                if length > MAX_FUNCTION_LINES:
                    long.append((length, rel, first, signature[:80]))
    print(f"files over {MAX_FILE_LINES} lines in {', '.join(f + '/' for f in PHYSICS)}: {len(big)}")
    for n, rel in sorted(big, reverse=True):
        print(f"  {n:5d}  {rel}")
    print(f"functions over {MAX_FUNCTION_LINES} lines there: {len(long)}")
    for n, rel, first, signature in sorted(long, reverse=True):
        print(f"  {n:5d}  {rel}:{first}  {signature}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
