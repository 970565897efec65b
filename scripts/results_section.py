#!/usr/bin/python3
"""Puts a generated section into docs/RESULTS.md between its markers.

usage: results_section.py NAME RESULTS_MD SECTION_FILE

SECTION_FILE starts with <!-- NAME:begin --> and ends with <!-- NAME:end -->; it replaces the
text between the same markers in RESULTS_MD, or is appended when they are not there yet.
"""
import os
import sys

name, results, section_path = sys.argv[1:4]
begin, end = "<!-- %s:begin -->" % name, "<!-- %s:end -->" % name
with open(section_path) as f:
    section = f.read().rstrip("\n")
text = open(results).read() if os.path.exists(results) else "# Results\n"
b, e = text.find(begin), text.find(end)
if b != -1 and e > b:
    text = text[:b] + section + text[e + len(end):]
else:
    text = text.rstrip("\n") + "\n\n" + section + "\n"
with open(results, "w") as f:
    f.write(text)
