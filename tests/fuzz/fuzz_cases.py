#!/usr/bin/python3
"""A small mutation fuzzer for case files: bad input must never crash, hang or report success over a wrong answer.

  fuzz_cases.py fuzz SEED.json... [--exe EXE] [--out DIR] [--count N] [--seed S] [--timeout T] [--steps K]
                          [--mutations M]
      Mutates the seed cases (any case file: numbers, types, keys, arrays, structure), runs `lagfsi check` and a
      short `lagfsi run` on each mutant and classifies the outcome. Mutants that end in a finding are kept in
      DIR/findings/<class>/ with the reason; DIR/report.json lists every mutant. The seeds are first shortened
      to at most K load steps (default 2) so that a run takes a moment.
  fuzz_cases.py corpus DIR [--exe EXE] [--out DIR]
      Runs `lagfsi check` on every DIR/*.json (a corpus of mutants that once failed) and requires, for each, a
      non-zero exit (2, bad input) with exactly one line on stderr, `lagfsi: error: <file>: /<json path>:
      <reason>`. Exit 1 when one does not. A mutant named *.run.json is also run (its few steps) when `check`
      accepts it: the run must then end with exit 0 and sensible probes, or with the one-line error. A mutant named
      *.valid.json must pass `check` and run to exit 0 with sensible probes.

Outcome classes (fuzz): crash (a signal, or exit 4 internal error), hang (the timeout), nonsense (exit 0 with
non-finite probe values or a displacement larger than the body's size), multiline (more than one error line),
no_path (an error line without a JSON path), bad_output (a failed run whose summary.json is missing or invalid),
ok (anything else). Run with /usr/bin/python3."""
import argparse
import copy
import json
import math
import os
import random
import re
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
ERROR_LINE = re.compile(r"^lagfsi: error: (?P<file>[^:]+): (?P<path>/\S*): (?P<reason>.+)$")


def strip_comments(text):
    """The JSON of a case file without its // and /* */ comments (strings kept as they are)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            out.append(text[i:j + 1])
            i = j + 1
        elif text.startswith("//", i):
            while i < n and text[i] != "\n":
                i += 1
        elif text.startswith("/*", i):
            i = text.find("*/", i + 2)
            i = n if i < 0 else i + 2
        else:
            out.append(c)
            i += 1
    return "".join(out)


def load_case(path):
    with open(path, encoding="utf-8") as f:
        return json.loads(strip_comments(f.read()))


def shorten(case, steps):
    """At most `steps` load steps and an output every step (a mutant then runs in a moment)."""
    an = case.get("analysis")
    if isinstance(an, dict) and isinstance(an.get("load_steps"), int):
        an["load_steps"] = min(an["load_steps"], steps)
    return case


def all_paths(node, prefix=()):
    """Every location in the tree, as a tuple of keys and indices (the root excluded)."""
    out = []
    if isinstance(node, dict):
        for k, v in node.items():
            out.append(prefix + (k,))
            out.extend(all_paths(v, prefix + (k,)))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            out.append(prefix + (i,))
            out.extend(all_paths(v, prefix + (i,)))
    return out


def get(node, path):
    for p in path:
        node = node[p]
    return node


def pointer(path):
    return "/" + "/".join(str(p) for p in path)


NUMBERS = [0, 0.0, -1.0, 1e-300, -1e-300, 1e300, -1e300, 1e-12, 1e12, 2147483648, -2147483649, 1e9, 0.5, 2.5]
STRINGS = ["nan", "NaN", "inf", "-inf", "Infinity", "", "x", "1e999", "é" * 3, "a" * 5000]
RAW = ["NaN", "Infinity", "-Infinity", "1e999", "-1e999", "0x10", "1e-999"]


def mutate_value(rng, v):
    """A replacement for the value v, and a short description."""
    if isinstance(v, bool):
        return rng.choice([not v, 0, "true", None]), "bool"
    if isinstance(v, (int, float)):
        r = rng.random()
        if r < 0.55:
            x = rng.choice(NUMBERS)
            return x, "number %r" % x
        if r < 0.7:
            x = -v if v else -1
            return x, "negate"
        if r < 0.85:
            x = rng.choice([v * 1e6, v * 1e-6, v + 0.5, v * 1e20, v * 1e-20])
            return x, "scale %r" % x
        x = rng.choice(STRINGS[:5])
        return x, "number as string %r" % x
    if isinstance(v, str):
        x = rng.choice(STRINGS + [v + "_", v.upper(), " " + v])
        return x, "string %r" % x[:20]
    if isinstance(v, list):
        r = rng.random()
        if r < 0.25:
            return [], "empty array"
        if r < 0.45 and v:
            w = copy.deepcopy(v)
            i = rng.randrange(len(w))
            w.insert(i, copy.deepcopy(w[i]))
            return w, "duplicate entry %d" % i
        if r < 0.6 and v:
            w = copy.deepcopy(v)
            del w[rng.randrange(len(w))]
            return w, "remove an entry"
        if r < 0.75:
            return v + [copy.deepcopy(v[-1]) if v else 0] * 3, "longer array"
        if r < 0.9 and v:
            w = copy.deepcopy(v)
            w.reverse()
            return w, "reversed"
        return [v], "nested in an array"
    if isinstance(v, dict):
        r = rng.random()
        if r < 0.4 and v:
            w = dict(v)
            k = rng.choice(list(w))
            del w[k]
            return w, "delete key %s" % k
        if r < 0.7:
            w = dict(v)
            w["fuzz_unknown"] = 1
            return w, "unknown key"
        return {}, "empty object"
    return rng.choice([0, "x", [], {}]), "null to value"


def swap_type(rng, v):
    options = [0, 1.5, "text", [], [1, 2], {}, {"a": 1}, None, True, False]
    x = rng.choice([o for o in options if type(o) is not type(v)])
    return x, "type swap to %s" % json.dumps(x)


def mutate(rng, case, times=1):
    """A mutant of the case with `times` mutations: (json text, description)."""
    text, whats = None, []
    for _ in range(times):
        try:
            case = json.loads(text) if text is not None else case
        except (ValueError, RecursionError):
            break  # a raw token or a deep nesting: the text is no longer JSON that Python reads back
        text, what = mutate_once(rng, case)
        whats.append(what)
    return text, "; ".join(whats)


def mutate_once(rng, case):
    m = copy.deepcopy(case)
    paths = all_paths(m)
    path = rng.choice(paths)
    parent = get(m, path[:-1])
    key = path[-1]
    v = parent[key]
    r = rng.random()
    raw = None
    if r < 0.55:
        new, what = mutate_value(rng, v)
    elif r < 0.75:
        new, what = swap_type(rng, v)
    elif r < 0.82 and isinstance(parent, dict):
        del parent[key]
        return json.dumps(m, indent=2, ensure_ascii=False), "delete %s" % pointer(path)
    elif r < 0.86:
        depth = rng.choice([50, 200, 2000])  # written as text: json.dumps recurses
        raw = "[" * depth + json.dumps(v) + "]" * depth
        new, what = "@@RAW@@", "nested %d deep" % depth
    elif r < 0.9 and isinstance(v, (int, float)) and not isinstance(v, bool):
        raw = rng.choice(RAW)
        new, what = "@@RAW@@", "raw token %s" % raw
    elif r < 0.95 and isinstance(parent, dict):
        parent[key + "_fuzz"] = v
        return json.dumps(m, indent=2, ensure_ascii=False), "unknown key next to %s" % pointer(path)
    else:
        new, what = mutate_value(rng, v)
    parent[key] = new
    text = json.dumps(m, indent=2, ensure_ascii=False)
    if raw is not None:
        text = text.replace('"@@RAW@@"', raw)
    return text, "%s at %s" % (what, pointer(path))


def run(cmd, timeout):
    env = dict(os.environ, OMP_NUM_THREADS="1")
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env, errors="replace")
        return p.returncode, p.stderr
    except subprocess.TimeoutExpired:
        return None, ""


def error_problem(rc, err, case_file):
    """A finding class for a failing exit, or None when the message is one line naming the file and a path."""
    if rc is None:
        return "hang", "timeout"
    if rc < 0 or rc == 4 or rc > 128:
        return "crash", "exit %d: %s" % (rc, err.strip()[-300:])
    lines = [l for l in err.splitlines() if not l.startswith("lagfsi: warning: ")]
    if len(lines) != 1:
        return "multiline", "%d lines: %s" % (len(lines), err.strip()[:300])
    m = ERROR_LINE.match(lines[0])
    if not m or m.group("file") != case_file:
        return "no_path", lines[0][:300]
    return None


def body_size(case):
    """The diagonal of the bodies' domains (from a rectangle's size, a plate's size), or None."""
    sizes = []
    for b in case.get("bodies", []) if isinstance(case, dict) else []:
        d = b.get("domain") if isinstance(b, dict) else None
        if not isinstance(d, dict):
            continue
        s = d.get("size")
        if isinstance(s, list) and len(s) == 2 and all(isinstance(x, (int, float)) for x in s):
            sizes.append(math.hypot(*s))
        elif isinstance(s, (int, float)):
            sizes.append(math.sqrt(2) * s)
    return max(sizes) if sizes else None


def nonsense(run_dir, case):
    """A reason when a completed run's output is not a sensible answer, else None."""
    try:
        with open(os.path.join(run_dir, "summary.json")) as f:
            summary = json.load(f)
        with open(os.path.join(run_dir, "probes.csv")) as f:
            rows = [l.strip().split(",") for l in f if l.strip()]
    except (OSError, ValueError) as e:
        return "output unreadable: %s" % e
    if summary.get("status") not in ("completed",):
        return "status %r with exit 0" % summary.get("status")
    header, size = rows[0], body_size(case)
    kinds = {p.get("name"): p.get("type") for p in case.get("probes", []) if isinstance(p, dict)}
    for row in rows[1:]:
        for name, cell in zip(header, row):
            try:
                x = float(cell)
            except ValueError:
                return "probe %s: %r is not a number" % (name, cell)
            if not math.isfinite(x):
                return "probe %s: %s" % (name, cell)
            if kinds.get(name) == "displacement" and size and abs(x) > size:
                return "probe %s: displacement %g larger than the body (%g)" % (name, x, size)
    return None


def fuzz(args):
    rng = random.Random(args.seed)
    seeds = [(s, shorten(load_case(s), args.steps)) for s in args.seeds]
    out = os.path.abspath(args.out)
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    report, counts = [], {}
    for i in range(args.count):
        seed_file, seed = seeds[i % len(seeds)]
        text, what = mutate(rng, seed, args.mutations)
        d = os.path.join(out, "m%04d" % i)
        os.makedirs(d)
        case_file = os.path.join(d, "case.json")
        with open(case_file, "w", encoding="utf-8") as f:
            f.write(text)
        cls, reason, stage = "ok", "", "check"
        rc, err = run([args.exe, "check", case_file], args.timeout)
        finding = error_problem(rc, err, case_file) if rc != 0 else None
        if finding is None and rc == 0:
            stage = "run"
            rd = os.path.join(d, "run")
            rc, err = run([args.exe, "run", case_file, "-o", rd, "--quiet"], args.timeout)
            if rc == 0:
                try:
                    mutant = json.loads(text)
                except (ValueError, RecursionError):
                    mutant = {}
                r = nonsense(rd, mutant)
                finding = ("nonsense", r) if r else None
            else:
                finding = error_problem(rc, err, case_file)
                if finding is None and rc is not None:
                    try:
                        with open(os.path.join(rd, "summary.json")) as f:
                            if json.load(f).get("status") != "failed":
                                finding = ("bad_output", "summary.json status is not 'failed'")
                    except (OSError, ValueError) as e:
                        finding = ("bad_output", "summary.json: %s" % e)
        if finding:
            cls, reason = finding
            keep = os.path.join(out, "findings", cls)
            os.makedirs(keep, exist_ok=True)
            shutil.copy(case_file, os.path.join(keep, "m%04d.json" % i))
        if rc is not None and cls == "ok":
            shutil.rmtree(os.path.join(d, "run"), ignore_errors=True)
        counts[cls] = counts.get(cls, 0) + 1
        report.append({"mutant": i, "seed": os.path.relpath(seed_file, ROOT), "mutation": what, "stage": stage,
                       "exit": rc, "class": cls, "reason": reason, "stderr": err.strip()[:400]})
        if cls != "ok":
            print("m%04d %-10s %s | %s | %s" % (i, cls, os.path.relpath(seed_file, ROOT), what, reason[:200]))
            sys.stdout.flush()
    with open(os.path.join(out, "report.json"), "w") as f:
        json.dump(report, f, indent=1)
    print("mutants: %d; %s" % (args.count, ", ".join("%s %d" % kv for kv in sorted(counts.items()))))
    return 0


def corpus(args):
    files = sorted(f for f in os.listdir(args.dir) if f.endswith(".json"))
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    failures = []
    for name in files:
        case_file = os.path.join(os.path.abspath(args.dir), name)
        valid = name.endswith(".valid.json")
        rc, err = run([args.exe, "check", case_file], args.timeout)
        problem = None
        if valid:
            if rc != 0:
                problem = "expected exit 0, found %s: %s" % (rc, err.strip()[:300])
        elif rc == 0 and not name.endswith(".run.json"):
            problem = "expected an error, found exit 0"
        elif rc != 0:
            f = error_problem(rc, err, case_file)
            if f:
                problem = "%s: %s" % f
        if problem is None and rc == 0 and (valid or name.endswith(".run.json")):
            rd = os.path.join(out, name[:-5])
            shutil.rmtree(rd, ignore_errors=True)
            rc, err = run([args.exe, "run", case_file, "-o", rd, "--quiet"], args.timeout)
            if rc == 0:
                r = nonsense(rd, load_case(case_file))
                if r:
                    problem = "run completed over nonsense: " + r
            elif valid:
                problem = "run: expected exit 0, found %s: %s" % (rc, err.strip()[:300])
            else:
                f = error_problem(rc, err, case_file)
                if f:
                    problem = "run: %s: %s" % f
        print("%-4s %s%s" % ("ok" if problem is None else "FAIL", name, "" if problem is None else ": " + problem))
        if problem:
            failures.append(name)
    print("%d of %d corpus files as expected" % (len(files) - len(failures), len(files)))
    return 1 if failures or not files else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    f = sub.add_parser("fuzz")
    f.add_argument("seeds", nargs="+")
    f.add_argument("--exe", default=os.path.join(ROOT, "build", "lagfsi"))
    f.add_argument("--out", default="/tmp/lagfsi_fuzz")
    f.add_argument("--count", type=int, default=300)
    f.add_argument("--seed", type=int, default=1)
    f.add_argument("--timeout", type=float, default=20)
    f.add_argument("--steps", type=int, default=2)
    f.add_argument("--mutations", type=int, default=1, help="mutations per mutant")
    c = sub.add_parser("corpus")
    c.add_argument("dir")
    c.add_argument("--exe", default=os.path.join(ROOT, "build", "lagfsi"))
    c.add_argument("--out", default="/tmp/lagfsi_fuzz_corpus")
    c.add_argument("--timeout", type=float, default=60)
    args = ap.parse_args()
    return fuzz(args) if args.cmd == "fuzz" else corpus(args)


if __name__ == "__main__":
    sys.exit(main())
