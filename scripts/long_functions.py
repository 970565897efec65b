#!/usr/bin/env python3
"""Lists the functions in src/ whose body is longer than a limit (default 80 lines).

A body line is a line between the function's braces that is neither blank nor only a
comment. Functions come from universal-ctags (their first and last line); a function
that says why it is long (a comment just above it or at the top of its body with the word
"long") is still listed, marked "reason given".

Usage: scripts/long_functions.py [--limit N] [DIR...]   (default DIR: src)
"""
import argparse
import pathlib
import subprocess
import sys


def body_lines(lines, first, last):
    """Counts the non-blank, non-comment lines after the opening brace, before the closing one."""
    start = first - 1
    while start < last and "{" not in lines[start]:
        start += 1
    count, in_block = 0, False
    for text in lines[start + 1:last - 1]:
        stripped = text.strip()
        if in_block:
            if "*/" in stripped:
                in_block = False
            continue
        if not stripped or stripped.startswith("//"):
            continue
        if stripped.startswith("/*"):
            in_block = "*/" not in stripped
            continue
        count += 1
    return count, start


def reason_given(lines, first, brace_index):
    """True when the comment just above the function or at the top of its body says "long"."""
    above = []
    i = first - 2
    while i >= 0 and lines[i].strip().startswith("//"):
        above.append(lines[i])
        i -= 1
    j = brace_index + 1
    while j < len(lines) and lines[j].strip().startswith("//"):
        above.append(lines[j])
        j += 1
    return any("long" in text.lower() for text in above)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--limit", type=int, default=80)
    parser.add_argument("dirs", nargs="*", default=["src"])
    args = parser.parse_args()
    tags = subprocess.run(
        ["ctags", "-R", "--languages=C++", "--kinds-C++=f", "--fields=+neK", "-f", "-"] + args.dirs,
        check=True, capture_output=True, text=True).stdout
    rows = []
    cache = {}
    for tag in tags.splitlines():
        fields = tag.split("\t")
        extra = dict(f.split(":", 1) for f in fields[3:] if ":" in f)
        if "line" not in extra or "end" not in extra:
            continue
        path = fields[1]
        if path not in cache:
            cache[path] = pathlib.Path(path).read_text(errors="replace").splitlines()
        lines = cache[path]
        count, brace = body_lines(lines, int(extra["line"]), int(extra["end"]))
        if count > args.limit:
            scope = extra.get("class", extra.get("namespace", ""))
            name = f"{scope.split('::')[-1]}::{fields[0]}" if "class" in extra else fields[0]
            note = "  (reason given)" if reason_given(lines, int(extra["line"]), brace) else ""
            rows.append((count, f"{path}:{extra['line']}", name, note))
    for count, where, name, note in sorted(rows, reverse=True):
        print(f"{count:4d}  {where}  {name}{note}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
