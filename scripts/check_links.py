#!/usr/bin/python3
"""Checks that every relative link of README.md and docs/**/*.md points to an existing file or folder.

  check_links.py [FILE.md ...]

Links are Markdown links and images, [text](target) and ![alt](target); a target with a scheme (http:, https:,
mailto:) or starting with '#' is not checked, and the '#anchor' of a relative target is ignored (only the file
is). Links inside code spans and fenced code blocks are ignored. Exit 1 and one line per broken link,
FILE:LINE: target, when one does not resolve. Run with /usr/bin/python3."""
import glob
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
CODE = re.compile(r"`[^`]*`")


def files(args):
    if args:
        return [os.path.abspath(a) for a in args]
    out = [os.path.join(ROOT, "README.md")]
    out += sorted(glob.glob(os.path.join(ROOT, "docs", "**", "*.md"), recursive=True))
    return out


def broken(path):
    bad = []
    fenced = False
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            if line.lstrip().startswith("```"):
                fenced = not fenced
                continue
            if fenced:
                continue
            for m in LINK.finditer(CODE.sub("", line)):
                target = m.group(1)
                if re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target) or target.startswith("#"):
                    continue
                file_part = target.split("#", 1)[0]
                if not file_part:
                    continue
                if not os.path.exists(os.path.normpath(os.path.join(os.path.dirname(path), file_part))):
                    bad.append("%s:%d: %s" % (os.path.relpath(path, ROOT), n, target))
    return bad


def main():
    bad = []
    checked = files(sys.argv[1:])
    for p in checked:
        bad += broken(p)
    for b in bad:
        print(b)
    if not bad:
        print("check_links: %d files, every relative link resolves" % len(checked))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
