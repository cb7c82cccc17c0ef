"""Shared code of the studies in cases/studies/<study>/run.py (run them with /usr/bin/python3).

Every study drives `lagfsi run CASE.json --set ... --threads 1 --quiet` under `nice -n 19`, one run at a time,
writes CSV tables and PNG charts, and takes the same options:
  --exe PATH    lagfsi executable (default <repo>/build/lagfsi)
  --out DIR     run folders, tables and charts (default <repo>/out/studies/<study>)
  --quick       a few small runs (a smoke test: exits non-zero unless its outputs exist and are finite)
  --publish     tables and charts go to cases/studies/<study>/results/ (the run folders stay in --out)
  --cases DIR   the case files (default <repo>/cases)
  --rerun       run again even when a run folder with the same command (and executable time stamp) already
                holds a finished run
  --plan FILE   make no run: write the runs still needed to FILE for jobs.py (an MPI launch or a job array), then
                run again without --plan to collect them
Post-processing reuses cases/tools/lagfsi_post (read_csv, last_period_stats, interp, ...; the .pvd/.vtu reader
lagfsi_post.vtkxml)."""
import argparse
import atexit
import csv
import json
import math
import os
import shlex
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))
CASES = os.path.join(REPO, "cases")
sys.path.insert(0, os.path.join(CASES, "tools"))
sys.path.insert(0, HERE)
import runjob  # noqa: E402  (one run and its record, shared with the jobs of a plan: jobs.py)
import lagfsi_post  # noqa: E402  (read_csv, last_period_stats, interp, peak, coupling_lines, save)
from lagfsi_post import read_csv  # noqa: E402
from lagfsi_post.vtkxml import read_pvd, read_vtk  # noqa: E402  (the VTK XML reader shared with the pictures)

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402,F401  (re-exported for the studies)

PENDING = -2  # the exit code of a run in a --plan: not made yet
EXIT_NAMES = {0: "ok", 1: "usage", 2: "bad input", 3: "solver failure", 4: "internal error", -1: "timeout",
              PENDING: "pending (planned, not made yet)"}


# ------------------------------------------------------------------------------------------------ options

class Study:
    """Options, folders and the run helper of one study."""

    def __init__(self, name, description, argv=None):
        ap = argparse.ArgumentParser(description=description)
        ap.add_argument("--exe", default=os.path.join(REPO, "build", "lagfsi"), help="lagfsi executable")
        ap.add_argument("--out", default=None, help="output folder (default <repo>/out/studies/%s)" % name)
        ap.add_argument("--quick", action="store_true", help="a few small runs (smoke test)")
        ap.add_argument("--publish", action="store_true",
                        help="write tables and charts into cases/studies/%s/results/" % name)
        ap.add_argument("--rerun", action="store_true", help="ignore finished runs in the output folder")
        ap.add_argument("--cases", default=CASES,
                        help="folder of the case files (default <repo>/cases; e.g. the cases of the source tree the "
                             "executable was built from)")
        ap.add_argument("--threads", type=int, default=1, help="OpenMP threads per run (default 1)")
        ap.add_argument("--no-nice", action="store_true", help="do not run the solver under nice -n 19")
        ap.add_argument("--plan", metavar="FILE", default=None,
                        help="make no run: write the runs still to be made (not finished in --out) to FILE, one JSON "
                             "job per line, for jobs.py (a batch job array or mpirun); then run the study again "
                             "without --plan to collect them (a study whose runs depend on earlier results plans "
                             "them in waves: plan again until the plan is empty)")
        self.args = ap.parse_args(argv)
        self.name = name
        self.quick = self.args.quick
        self.exe = os.path.abspath(self.args.exe)
        self.cases = os.path.abspath(self.args.cases)
        mode = "quick" if self.quick else "full"
        self.out = os.path.abspath(self.args.out or os.path.join(REPO, "out", "studies", name))
        self.runs_dir = os.path.join(self.out, "runs_" + mode)
        if self.args.publish and not self.quick:
            self.results = os.path.join(HERE, name, "results")
        else:
            self.results = os.path.join(self.out, "results_" + mode)
        os.makedirs(self.runs_dir, exist_ok=True)
        os.makedirs(self.results, exist_ok=True)
        self.t0 = time.time()
        self.written = []  # tables and charts, checked by finish()
        self.run_wall = 0.0  # the wall time of every run of this study, reused ones included
        self.n_runs = 0
        self.n_reused = 0
        self.plan = [] if self.args.plan else None  # --plan: the jobs the study still needs
        if self.plan is not None:
            atexit.register(self._write_plan)
            sys.excepthook = self._pending_excepthook
        if not os.access(self.exe, os.X_OK):
            sys.exit("%s: lagfsi executable not found at %s (give --exe)" % (name, self.exe))
        print("[%s] %s mode; exe %s; runs in %s; results in %s" % (name, mode, self.exe, self.runs_dir,
                                                                   self.results), flush=True)

    # -------------------------------------------------------------------------------------------- runs

    def run(self, case, tag, sets=(), timeout=None):
        """Runs `case` (a path, relative to cases/ if not absolute) with the --set overrides `sets` (a dict or a
        list of "key=value") into runs_dir/tag. Returns a Run. A finished run with the same command is reused
        unless --rerun. timeout (s): the run is killed and reported with rc -1. With --plan the run is not made but
        added to the plan (a pending Run: rc PENDING, no output)."""
        case_path = case if os.path.isabs(case) else os.path.join(self.cases, case)
        if isinstance(sets, dict):
            sets = ["%s=%s" % (k, v if isinstance(v, str) else json.dumps(v)) for k, v in sets.items()]
        out = os.path.join(self.runs_dir, tag)
        cmd = [self.exe, "run", case_path, "-o", out, "--threads", str(self.args.threads), "--quiet"]
        for s in sets:
            cmd += ["--set", s]
        old = None if self.args.rerun else runjob.finished(cmd, out)
        self.n_runs += 1
        if old is not None:
            self.run_wall += old["wall"]
            self.n_reused += 1
            return Run(out, old["rc"], old["wall"], cmd, old.get("stderr", ""), old.get("cpu"))
        job = {"cmd": cmd, "out": out, "timeout": timeout, "nice": not self.args.no_nice}
        if self.plan is not None:
            if all(j["out"] != out for j in self.plan):  # one job per folder, however often the study asks
                self.plan.append(job)
            return Run(out, PENDING, 0.0, cmd, EXIT_NAMES[PENDING])
        rec = runjob.execute(job)
        self.run_wall += rec["wall"]
        r = Run(out, rec["rc"], rec["wall"], cmd, rec["stderr"], rec["cpu"])
        print("  %-44s rc=%d (%s) %6.1f s%s" % (tag, r.rc, EXIT_NAMES.get(r.rc, "?"), r.wall,
                                                 "" if r.rc == 0 else "  " + r.message[:110]), flush=True)
        return r

    def _write_plan(self):
        """--plan: the pending jobs, one JSON line each (jobs.py reads them), and what to do next."""
        with open(self.args.plan, "w") as f:
            for job in self.plan:
                f.write(json.dumps(job) + "\n")
        print("[%s] plan: %d runs to make (%d finished) -> %s%s" % (
            self.name, len(self.plan), self.n_reused, self.args.plan,
            "; run them with jobs.py, then this study again" if self.plan else ""), flush=True)

    def _pending_excepthook(self, kind, value, tb):
        """--plan: an analysis that fails on runs not made yet is not an error (the plan is still written)."""
        if self.plan:
            print("[%s] analysis stopped on the pending runs (%s: %s)" % (self.name, kind.__name__, value))
            sys.exit(0)
        sys.__excepthook__(kind, value, tb)

    # ---------------------------------------------------------------------------------------- outputs

    def table(self, filename, rows, columns=None):
        """Writes rows (dicts) as a CSV table into the results folder; returns its path (None with --plan)."""
        if self.plan is not None:
            return None
        columns = columns or list(rows[0].keys())
        path = os.path.join(self.results, filename)
        with open(path, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(columns)
            for r in rows:
                w.writerow([fmt(r.get(c, "")) for c in columns])
        self.written.append(path)
        print("wrote", path)
        return path

    def figure(self, fig, filename):
        if self.plan is not None:
            plt.close(fig)
            return None
        path = os.path.join(self.results, filename)
        fig.savefig(path, dpi=110, bbox_inches="tight")
        plt.close(fig)
        self.written.append(path)
        print("wrote", path)
        return path

    def readme_table(self, markdown):
        """With --publish in full mode: puts `markdown` between the study README's generated-table markers."""
        if not (self.args.publish and not self.quick) or self.plan is not None:
            return
        readme = os.path.join(HERE, self.name, "README.md")
        with open(readme) as f:
            text = f.read()
        b, e = "<!-- study:begin (generated by run.py --publish; do not edit) -->", "<!-- study:end -->"
        i, j = text.find(b), text.find(e)
        if i >= 0 and j > i:
            with open(readme, "w") as f:
                f.write(text[:i + len(b)] + "\n" + markdown + "\n" + text[j:])
            print("wrote the table of", readme)

    def finish(self, required_finite=(), extra_problems=()):
        """Writes meta.json; checks that every table and chart exists and is non-empty and, in quick mode, that the
        columns `required_finite` ((filename, column) pairs) hold only finite numbers and that there are no
        `extra_problems`. Exits 1 on a failed check. With --plan: writes the plan instead and exits 0."""
        if self.plan is not None:
            sys.exit(0)  # the plan is written at exit
        meta = {"study": self.name, "mode": "quick" if self.quick else "full", "commit": commit(self.exe),
                "source": source_dir(self.exe),
                "exe": self.exe, "version": version(self.exe), "wall_time_s": round(time.time() - self.t0, 1),
                "runs": self.n_runs, "runs_reused": self.n_reused, "runs_wall_time_s": round(self.run_wall, 1),
                "threads": self.args.threads, "machine_cpus": os.cpu_count()}
        path = os.path.join(self.results, "meta.json")
        with open(path, "w") as f:
            json.dump(meta, f, indent=1)
        problems = list(extra_problems) if self.quick else []
        for p in self.written:
            if not os.path.isfile(p) or os.path.getsize(p) == 0:
                problems.append("missing or empty: " + p)
        for filename, col in (required_finite if self.quick else ()):  # full mode: failed runs are results
            p = os.path.join(self.results, filename)
            try:
                vals = read_csv(p)[col]
                if not vals or not all(isinstance(v, float) and math.isfinite(v) for v in vals):
                    problems.append("%s: column %s not all finite: %s" % (filename, col, vals))
            except (OSError, KeyError, IndexError) as e:
                problems.append("%s: %s" % (filename, e))
        print("[%s] %s mode done in %.0f s, %d runs (%d reused) (commit %s)" % (
            self.name, meta["mode"], meta["wall_time_s"], self.n_runs, self.n_reused, meta["commit"]))
        if problems:
            print("[%s] CHECK FAILED:\n  " % self.name + "\n  ".join(problems))
            sys.exit(1)
        return meta


class Run:
    """One finished (or failed) lagfsi run: rc, wall and cpu (s, measured around the process; cpu: user + system of
    the process, None for a run recorded before it was measured), out folder."""

    def __init__(self, out, rc, wall, cmd, stderr, cpu=None):
        self.out, self.rc, self.wall, self.cmd, self.cpu = out, rc, wall, cmd, cpu
        self.summary = {}
        try:
            with open(os.path.join(out, "summary.json")) as f:
                self.summary = json.load(f)
        except (OSError, ValueError):
            pass
        self.message = self.summary.get("message") or stderr.strip().splitlines()[-1:] and \
            stderr.strip().splitlines()[-1] or ""

    @property
    def ok(self):
        return self.rc == 0

    @property
    def solver_wall(self):
        """The solver's own wall time (summary.json), else the process time."""
        return self.summary.get("wall_time", self.wall)

    def probes(self):
        return read_csv(os.path.join(self.out, "probes.csv"))

    def log(self):
        return read_csv(os.path.join(self.out, "log.csv"))

    def has_probes(self):
        try:
            return len(self.probes()["time"]) > 1
        except (OSError, KeyError, IndexError):
            return False


def accepts(study, case, sets):
    """Whether `lagfsi check` accepts the case with the overrides (e.g. an option a given executable lacks)."""
    cmd = [study.exe, "check", os.path.join(study.cases, case)]
    for k, v in sets.items():
        cmd += ["--set", "%s=%s" % (k, json.dumps(v))]
    return subprocess.call(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL) == 0


def fmt(v):
    if isinstance(v, float):
        return "nan" if math.isnan(v) else "%.6g" % v
    return v


def source_dir(exe):
    """The source tree the executable was built from (CMAKE_HOME_DIRECTORY of its build folder), else the repo."""
    try:
        with open(os.path.join(os.path.dirname(exe), "CMakeCache.txt")) as f:
            for line in f:
                if line.startswith("CMAKE_HOME_DIRECTORY:"):
                    return line.split("=", 1)[1].strip()
    except OSError:
        pass
    return REPO


def commit(exe=None):
    """Short commit of the executable's source tree (dirty trees marked +)."""
    src = source_dir(exe) if exe else REPO
    try:
        c = subprocess.check_output(["git", "-C", src, "rev-parse", "--short", "HEAD"],
                                    universal_newlines=True).strip()
        dirty = subprocess.call(["git", "-C", src, "diff", "--quiet", "HEAD", "--", "src", "fsi", "include",
                                 "meshing"]) != 0
        return c + ("+" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def version(exe):
    try:
        return subprocess.check_output([exe, "--version"], universal_newlines=True).strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


# ------------------------------------------------------------------------------------- shared measures

def area_drift(run):
    """(drift at the end, largest |drift|) of the fluid area in %, from log.csv (area after each step)."""
    a = run.log()["fluid_area"]
    if not a:
        return float("nan"), float("nan")
    a0 = a[0]
    d = [100 * (x / a0 - 1) for x in a]
    return d[-1], max(d, key=abs)


def dam_break_tank_errors(run):
    """As cases/dam_break_tank/plot.py: front RMS in Z = x/L up to the wall (Z < 4) against the pysph and the
    DualSPHysics digitizations of Koshizuka & Oka (1996), and the wall-impact time (front within 1.5 h of the
    right wall; h from the resolved case). NaN where the run stopped before the reference point."""
    ref_dir = os.path.join(CASES, "dam_break_tank", "reference")
    ref = read_csv(os.path.join(ref_dir, "koshizuka_oka_1996_surge_front_pysph.csv"))
    dsph = read_csv(os.path.join(ref_dir, "koshizuka_oka_1996_surge_front_dualsphysics.csv"))
    L, g = 0.146, 9.81
    scale = math.sqrt(2 * g / L)
    h = resolved(run)["bodies"][0]["spacing"]
    p = run.probes()
    T = [t * scale for t in p["time"]]
    Z = [x / L for x in p["front_x"]]

    def rms(Ts, Zs):
        e = [interp_nan(Tr, T, Z) - Zr for Tr, Zr in zip(Ts, Zs) if Zr < 4.0]
        e = [x for x in e if math.isfinite(x)]
        return math.sqrt(sum(x * x for x in e) / len(e)) if e else float("nan"), len(e)

    r1, n1 = rms(ref["T"], ref["Z"])
    r2, n2 = rms(dsph["T_nondim"], dsph["x_tip_over_L"])
    impact = next((t for t, x in zip(p["time"], p["front_x"]) if x >= 4 * L - 1.5 * h), float("nan"))
    return {"front_rms_pysph": r1, "front_rms_dsph": r2, "front_points": n1, "impact_time": impact,
            "impact_error": impact - 0.30 if math.isfinite(impact) else float("nan")}


def dam_break_floor_errors(run):
    """As cases/dam_break_floor/plot.py: front RMS in Z = x/a for T <= 3 and column-height RMS in H against
    Martin & Moyce (1952), a = 2.25 in."""
    a, g = 0.05715, 9.81
    ref = read_csv(os.path.join(CASES, "dam_break_floor", "reference", "martin_moyce_1952_tables_2_6.csv"))
    surge = [(t, v) for s, t, v in zip(ref["series"], ref["time_nondim"], ref["value"]) if s == "surge"]
    height = [(t, v) for s, t, v in zip(ref["series"], ref["time_nondim"], ref["value"]) if s == "height"]
    p = run.probes()
    T = [t * math.sqrt(2 * g / a) for t in p["time"]]
    tau = [t * math.sqrt(g / a) for t in p["time"]]
    Z = [x / a for x in p["front_x"]]
    H = [hh / (2 * a) for hh in p["column_height"]]
    ez = [interp_nan(Tr, T, Z) - Zr for Tr, Zr in surge if Tr <= 3.0]
    eh = [interp_nan(tr, tau, H) - Hr for tr, Hr in height if tr <= tau[-1]]

    def rms(e):
        e = [x for x in e if math.isfinite(x)]
        return math.sqrt(sum(x * x for x in e) / len(e)) if e else float("nan"), len(e)

    rz, nz = rms(ez)
    rh, nh = rms(eh)
    return {"front_rms": rz, "front_points": nz, "height_rms": rh, "height_points": nh}


def interp_nan(x, xs, ys):
    """Linear interpolation; NaN outside the sampled range (a run that stopped early)."""
    if not xs or x < xs[0] or x > xs[-1]:
        return float("nan")
    return lagfsi_post.interp(x, xs, ys)


def resolved(run):
    with open(os.path.join(run.out, "resolved_case.json")) as f:
        return json.load(f)


def fit_slope(xs, ys):
    """Least-squares slope and intercept of log(y) against log(x) over the finite positive pairs."""
    pts = [(math.log(x), math.log(y)) for x, y in zip(xs, ys)
           if x > 0 and y > 0 and math.isfinite(x) and math.isfinite(y)]
    if len(pts) < 2:
        return float("nan"), float("nan")
    n = len(pts)
    mx = sum(p[0] for p in pts) / n
    my = sum(p[1] for p in pts) / n
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    if sxx == 0:
        return float("nan"), float("nan")
    s = sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx
    return s, my - s * mx


def pareto(points):
    """Indices of the Pareto-optimal (cost, error) points (no other point both cheaper and more accurate)."""
    idx = [i for i, (c, e) in enumerate(points) if math.isfinite(c) and math.isfinite(e)]
    front = []
    for i in idx:
        ci, ei = points[i]
        if not any((points[j][0] <= ci and points[j][1] <= ei) and (points[j][0] < ci or points[j][1] < ei)
                   for j in idx):
            front.append(i)
    return sorted(front, key=lambda i: points[i][0])


# ------------------------------------------------------------------------------------------- VTU files

def read_vtu(path):
    """Reads a lagfsi .vtu (lagfsi_post.vtkxml) into {"points": (n, 2) array, "connectivity": [...],
    "offsets": [...], point-data name: array}."""
    d = read_vtk(path)
    out = {"points": d.points, "connectivity": d.connectivity, "offsets": d.offsets}
    out.update(d.point_data)
    return out


def pvd_files(out_dir, pvd_name):
    """(time, path) of every file of a .pvd series."""
    return read_pvd(os.path.join(out_dir, pvd_name))


def detached_fluid_particles(vtu):
    """Fluid particles (kind 0) in no element of the fluid mesh of one .vtu (read_vtu)."""
    import numpy as np
    kind = np.asarray(vtu.get("kind", []))
    used = np.zeros(len(kind), dtype=bool)
    conn = np.asarray(vtu.get("connectivity", []), dtype=np.int64)
    used[conn[conn < len(kind)]] = True
    return int(np.count_nonzero((kind == 0) & ~used))


def cmdline(run):
    return " ".join(shlex.quote(c) for c in run.cmd)
