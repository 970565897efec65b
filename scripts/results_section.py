#!/usr/bin/python3
"""Puts a generated section into docs/RESULTS.md between its markers.

usage: results_section.py NAME RESULTS_MD SECTION_FILE

SECTION_FILE starts with <!-- NAME:begin --> and ends with <!-- NAME:end -->; it replaces the
text between the same markers in RESULTS_MD, or is appended when they are not there yet. When
the text between the markers holds a heading the new section does not (someone wrote a section
of their own inside them), nothing is replaced: exit 1 naming the headings, the new section left
in SECTION_FILE.
"""
import os
import sys


def headings(text):
    return [line for line in text.splitlines() if line.startswith("#")]


def main():
    name, results, section_path = sys.argv[1:4]
    begin, end = "<!-- %s:begin -->" % name, "<!-- %s:end -->" % name
    with open(section_path) as f:
        section = f.read().rstrip("\n")
    text = open(results).read() if os.path.exists(results) else "# Results\n"
    b, e = text.find(begin), text.find(end)
    if b != -1 and e > b:
        foreign = [h for h in headings(text[b:e]) if h not in headings(section)]
        if foreign:
            sys.exit("results_section: %s between %s and %s holds sections it did not write (%s); "
                     "move the markers round its own section; the new one is in %s" % (
                         results, begin, end, "; ".join(foreign), section_path))
        text = text[:b] + section + text[e + len(end):]
    else:
        text = text.rstrip("\n") + "\n\n" + section + "\n"
    with open(results, "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
