#!/usr/bin/python3
"""Checks that every relative link of README.md and docs/**/*.md points to an existing file or folder.

  check_links.py [FILE.md ...]

Links are Markdown links and images, [text](target) and ![alt](target); a target with a scheme (http:, https:,
mailto:) is not checked. The '#anchor' of a link to a Markdown file (or of '#anchor' alone, in the same file) must
be one of its headings, as GitHub spells them (lower case, punctuation dropped, spaces as '-', '-1' for a
repeat), or an <a id="..."> of it. Links inside code spans and fenced code blocks are ignored. Exit 1 and one line per broken link,
FILE:LINE: target, when one does not resolve. Run with /usr/bin/python3."""
import glob
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
CODE = re.compile(r"`[^`]*`")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
ANCHOR = re.compile(r"<a\s+(?:id|name)=\"([^\"]+)\"")
_anchors = {}


def slug(text):
    text = re.sub(r"`([^`]*)`", r"\1", text)
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)
    text = text.strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path):
    if path not in _anchors:
        found, seen, fenced = set(), {}, False
        with open(path, encoding="utf-8") as f:
            for line in f:
                if line.lstrip().startswith("```"):
                    fenced = not fenced
                    continue
                if fenced:
                    continue
                found.update(ANCHOR.findall(line))
                m = HEADING.match(line)
                if m:
                    base = slug(m.group(2))
                    n = seen.get(base, 0)
                    seen[base] = n + 1
                    found.add(base if n == 0 else "%s-%d" % (base, n))
        _anchors[path] = found
    return _anchors[path]


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
                if re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target):
                    continue
                file_part, _, anchor = target.partition("#")
                dest = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
                if not os.path.exists(dest):
                    bad.append("%s:%d: %s" % (os.path.relpath(path, ROOT), n, target))
                elif anchor and dest.endswith(".md") and os.path.isfile(dest) and anchor not in anchors(dest):
                    bad.append("%s:%d: %s (no such heading)" % (os.path.relpath(path, ROOT), n, target))
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
