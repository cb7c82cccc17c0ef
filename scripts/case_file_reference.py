#!/usr/bin/env python3
"""Checks that docs/case_file_reference.md is what `lagfsi keys` prints (the reference generated from the keys the
code declares), or writes it.

  scripts/case_file_reference.py --exe build/lagfsi           # check: prints the difference, exit 1 when stale
  scripts/case_file_reference.py --exe build/lagfsi --write   # regenerate the file
"""
import argparse
import difflib
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
REFERENCE = ROOT / "docs" / "case_file_reference.md"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=str(ROOT / "build" / "lagfsi"), help="the lagfsi executable")
    ap.add_argument("--write", action="store_true", help="write the reference instead of checking it")
    args = ap.parse_args()
    generated = subprocess.run([args.exe, "keys"], check=True, capture_output=True, text=True).stdout
    # Every key is described: a row "| `key` | default | description |" with an empty description is an error.
    undescribed = [line for line in generated.splitlines() if line.startswith("| `") and line.rstrip().endswith("|  |")]
    if undescribed:
        print("keys declared without a description:\n  " + "\n  ".join(undescribed))
        return 1
    # One section per kind of object: two tables with the same heading would be one reference entry twice.
    headings = [line for line in generated.splitlines() if line.startswith("## ")]
    repeated = sorted({h for h in headings if headings.count(h) > 1})
    if repeated:
        print("sections declared twice:\n  " + "\n  ".join(repeated))
        return 1
    if args.write:
        REFERENCE.write_text(generated)
        print(f"wrote {REFERENCE}")
        return 0
    committed = REFERENCE.read_text() if REFERENCE.exists() else ""
    if generated == committed:
        print(f"{REFERENCE.relative_to(ROOT)} is current")
        return 0
    sys.stdout.writelines(
        difflib.unified_diff(committed.splitlines(True), generated.splitlines(True),
                             "docs/case_file_reference.md (committed)", "lagfsi keys (generated)"))
    print(f"\n{REFERENCE.relative_to(ROOT)} is stale: the declared keys changed. Regenerate it with\n"
          f"  build/lagfsi keys > docs/case_file_reference.md\n"
          f"(or scripts/case_file_reference.py --exe build/lagfsi --write) and commit it.")
    return 1


if __name__ == "__main__":
    sys.exit(main())
