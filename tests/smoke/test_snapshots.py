#!/usr/bin/python3
"""Smoke test of scripts/snapshots.py (pictures without ParaView).

usage: tests/smoke/test_snapshots.py --exe BUILD/lagfsi --out DIR

Runs the dam break (cases/dam_break_tank) for 0.03 s with output every 2 steps into DIR/run, then
scripts/snapshots.py on it, and checks: the strip, the per-time PNGs, the GIF (several frames) and
paraview_state.py exist; the pictures are not blank (many distinct colours, and the fluid, coloured by the
colour map, fills a fair share of the plot); paraview_state.py runs against a stand-in of paraview.simple
and colours the fluid by pressure and the walls in grey; the reader agrees with the run (particle count);
and the one-line errors: missing folder, folder without .pvd, unknown field (listing the available ones).
Exit 0 when every check passes, 1 otherwise (each failed check printed).
"""
import argparse
import os
import shutil
import subprocess
import sys
import types

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
SNAP = os.path.join(ROOT, "scripts", "snapshots.py")
PY = sys.executable or "/usr/bin/python3"
failures = []


def check(ok, what):
    print("%s: %s" % ("ok" if ok else "FAILED", what))
    if not ok:
        failures.append(what)
    return ok


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, **kw)


def viridis_share(path, box=None):
    """Share of the pixels of `path` (within box = (left, top, right, bottom) fractions) whose colour lies near
    the viridis colour map, and the number of distinct colours of the whole image."""
    import numpy as np
    from PIL import Image
    from matplotlib import colormaps
    im = np.asarray(Image.open(path).convert("RGB")).astype(float)
    distinct = len(np.unique(im.reshape(-1, 3), axis=0))
    if box:
        h, w = im.shape[:2]
        im = im[int(box[1] * h):int(box[3] * h), int(box[0] * w):int(box[2] * w)]
    lut = colormaps["viridis"](np.linspace(0, 1, 64))[:, :3] * 255
    px = im.reshape(-1, 3)[::3]
    d = np.min(np.linalg.norm(px[:, None, :] - lut[None, :, :], axis=2), axis=1)
    return float(np.mean(d < 12.0)), distinct


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--exe", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    out = os.path.abspath(a.out)
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    rundir = os.path.join(out, "run")
    r = run([a.exe, "run", os.path.join(ROOT, "cases", "dam_break_tank", "case.json"), "-o", rundir, "--quiet",
             "--threads", "1", "--set", "analysis.end_time=0.03", "--set", "output.every=2"])
    if not check(r.returncode == 0, "lagfsi run of the tiny dam break (exit %d %s)" % (r.returncode, r.stderr.strip())):
        return 1

    r = run([PY, SNAP, rundir, "--frames", "10", "--count", "3"])
    check(r.returncode == 0 and not r.stderr.strip(), "snapshots.py exits 0 silently on stderr (exit %d: %s)" %
          (r.returncode, r.stderr.strip()))
    strip = os.path.join(rundir, "snapshots.png")
    gif = os.path.join(rundir, "animation.gif")
    state = os.path.join(rundir, "paraview_state.py")
    singles = sorted(os.listdir(os.path.join(rundir, "snapshots"))) if os.path.isdir(
        os.path.join(rundir, "snapshots")) else []
    for p in (strip, gif, state):
        check(os.path.isfile(p) and os.path.getsize(p) > 1000, "%s written (> 1 kB)" % os.path.basename(p))
    check(len(singles) == 3 and all(s.startswith("pressure_") and s.endswith(".png") for s in singles),
          "three per-time pictures snapshots/pressure_*.png (%s)" % singles)
    if failures:
        return 1

    from PIL import Image
    share, distinct = viridis_share(strip)
    check(distinct > 200, "the strip is not blank: %d distinct colours (> 200)" % distinct)
    # a single picture: the plot is the left part, the colour bar on the right; the fluid column fills ~12 % of it
    share, distinct = viridis_share(os.path.join(rundir, "snapshots", singles[0]), box=(0.1, 0.1, 0.7, 0.95))
    check(distinct > 100, "the first picture has %d distinct colours (> 100)" % distinct)
    check(share > 0.04, "the fluid, coloured by pressure, covers %.1f %% of the plot (> 4 %%)" % (100 * share))
    g = Image.open(gif)
    check(getattr(g, "n_frames", 1) >= 5, "animation.gif has %d frames (>= 5)" % getattr(g, "n_frames", 1))
    g.seek(g.n_frames - 1)
    ncol = len(g.convert("RGB").getcolors(1 << 20) or [])
    check(ncol > 30, "the last GIF frame has %d colours (> 30)" % ncol)

    # the reader against the run: the last fluid step's particles
    sys.path.insert(0, os.path.join(ROOT, "cases", "tools"))
    from lagfsi_post.vtkxml import find_series, read_vtk
    s = find_series(rundir)
    check(set(s) == {"water", "water_walls"}, "series found: %s" % sorted(s))
    d = read_vtk(s["water"][-1][1])
    import json
    with open(os.path.join(rundir, "summary.json")) as f:
        summ = json.load(f)
    nodes = [b.get("nodes") for b in summ.get("bodies", []) if b.get("name") == "water"]
    check(nodes and d.n_points == nodes[0] and "pressure" in d.point_data and len(d.triangles()) > 0,
          "the reader: %d points (summary.json: %s), %d triangles" % (d.n_points, nodes, len(d.triangles())))

    # paraview_state.py against a stand-in of paraview.simple that records the calls
    calls = []

    class Proxy:
        def __init__(self, name):
            object.__setattr__(self, "_name", name)

        def __getattr__(self, k):
            return Proxy(self._name + "." + k)

        def __setattr__(self, k, v):
            calls.append(("set", self._name + "." + k, v))

        def __call__(self, *args, **kw):
            calls.append(("call", self._name, args, kw))
            return Proxy(self._name + "()")

    simple = types.ModuleType("paraview.simple")
    names = ["GetActiveViewOrCreate", "PVDReader", "RenameSource", "Show", "ColorBy", "GetColorTransferFunction",
             "Threshold", "GetAnimationScene", "Render"]
    for n in names:
        setattr(simple, n, Proxy(n))
    simple.__all__ = names
    pv = types.ModuleType("paraview")
    pv.simple = simple
    sys.modules["paraview"], sys.modules["paraview.simple"] = pv, simple
    try:
        with open(state) as f:
            code = compile(f.read(), state, "exec")
        exec(code, {"__file__": state, "__name__": "__main__"})
        ran = True
    except Exception as e:  # noqa: BLE001
        ran = False
        print("paraview_state.py:", type(e).__name__, e)
    check(ran, "paraview_state.py runs against paraview.simple")
    readers = [c for c in calls if c[0] == "call" and c[1] == "PVDReader"]
    check(sorted(os.path.basename(c[3]["FileName"]) for c in readers) == ["water.pvd", "water_walls.pvd"] and
          all(os.path.isfile(c[3]["FileName"]) for c in readers), "paraview_state.py reads both .pvd files")
    check(any(c[0] == "call" and c[1] == "ColorBy" and c[2][1:] == (("POINTS", "pressure"),) for c in calls),
          "paraview_state.py colours the fluid by pressure")
    check(any(c[0] == "set" and c[1].endswith("DiffuseColor") and c[2] == [0.5, 0.5, 0.5] for c in calls),
          "paraview_state.py draws the walls in grey")

    # errors: one line, exit 2
    empty = os.path.join(out, "empty")
    os.makedirs(empty)
    for args, want in (([os.path.join(out, "missing")], "no such folder"), ([empty], "no .pvd"),
                       ([rundir, "--field", "nonsense", "--no-state"], "available: ")):
        r = run([PY, SNAP] + args)
        lines = r.stderr.strip().splitlines()
        check(r.returncode == 2 and len(lines) == 1 and want in lines[0],
              "error %r: exit %d, %d line(s): %s" % (want, r.returncode, len(lines), r.stderr.strip()))
    r = run([PY, SNAP, rundir, "--field", "nonsense", "--no-state"])
    check("pressure" in r.stderr and "velocity" in r.stderr, "an unknown field lists pressure and velocity")
    print("%d check(s) failed" % len(failures) if failures else "all checks passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
