#!/usr/bin/env python3
"""Writes tests/data/robustness.tsv.gz: every distinct Polygon and MultiPolygon of the XML tests of
GEOS and JTS whose file name says validity or overlay (the <a> and <b> inputs), valid or not.

usage: robustness_suites.py GEOS_GIT_DIR JTS_GIT_DIR > tests/data/robustness.tsv
(git directories of clones of libgeos/geos and locationtech/jts; their HEAD commits are printed
to stderr, for tests/data/README.md). Which are valid is PostGIS's verdict, asked by the test.
"""
import html
import re
import subprocess
import sys

SUITES = [
    ("geos", "tests/xmltester/tests"),
    ("jts", "modules/tests/src/test/resources/testxml"),
]


def git(repo, *args):
    return subprocess.run(["git", "-C", repo, *args], capture_output=True, text=True, check=True).stdout


def main():
    seen = set()
    print("source\tfile\twkt")
    for (name, root), repo in zip(SUITES, sys.argv[1:3]):
        print(f"{name}: {git(repo, 'rev-parse', 'HEAD').strip()}", file=sys.stderr)
        for f in sorted(git(repo, "ls-tree", "-r", "--name-only", "HEAD", root).split()):
            if not (f.endswith(".xml") and re.search("valid|overlay", f.rsplit("/", 1)[-1], re.I)):
                continue
            try:
                text = git(repo, "show", "HEAD:" + f)
            except subprocess.CalledProcessError:
                print(f"{name}: {f} could not be read, left out", file=sys.stderr)
                continue
            for m in re.finditer(r"<(a|b)>\s*(.*?)\s*</\1>", text, re.S | re.I):
                wkt = " ".join(html.unescape(m.group(2)).split())
                if re.match(r"(MULTI)?POLYGON\s*\(", wkt, re.I) and wkt not in seen:
                    seen.add(wkt)
                    print(f"{name}\t{f}\t{wkt}")


if __name__ == "__main__":
    main()
