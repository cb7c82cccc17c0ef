"""Pictures of a lagfsi output folder without ParaView: snapshots, a strip, an animation and a ParaView state.

usage: scripts/snapshots.py OUTDIR [--field FIELD] [--times T1,T2,...] [--count N] [--frames N]
                                   [--range VMIN,VMAX] [--box XMIN,XMAX,YMIN,YMAX] [--fluid mesh|particles]
                                   [--cmap NAME] [--dpi D]
                                   [--out DIR] [--no-animation] [--no-mp4] [--no-state] [--quiet]

Reads every <body>.pvd series of OUTDIR (lagfsi_post.vtkxml: no VTK module needed) and draws each body coloured
by FIELD with one colour bar and equal axes: the fluid as its mesh (or its particles), solids as meshes with
their outline, shells as lines, MPM particles as dots, DEM discs (.vtp with a `radius` field) as circles; walls
(<fluid>_walls series, wall particles, fluid walls and MPM boundary segments of resolved_case.json) in grey.
Vector fields are drawn by magnitude. The colour range is shared by all pictures: --range, else from up to 60
frames over the run (per frame the 0.5-99.5 percentiles; the 10th percentile of the lows, the 90th of the highs,
so that one frame's spike does not set it; arrows on the colour bar when values lie beyond). The frame holds
everything drawn (a few flying drops excepted) unless --box is given. Fast on long runs: only the chosen
times and at most --frames animation frames are read.

FIELD: pressure (fluid; MPM: mean stress, or pore pressure when saturated), velocity, displacement, von_mises
(solids; MPM from the stress), damage (when a body writes it), or any other point field of a body. Default:
pressure with a fluid, else von_mises with a solid, else displacement with a shell, else velocity. Bodies without
FIELD are drawn in a plain colour.

Writes into OUTDIR (or --out):
  snapshots/<field>_<k>_t<time>.png   one picture per chosen time (--times, else --count evenly spaced, default 5)
  snapshots.png                       the strip of those pictures
  animation.gif                       at most --frames frames (default 60) evenly spaced over the run (Pillow)
  animation.mp4                       the same frames, when ffmpeg is on the PATH
  paraview_state.py                   `paraview --state=OUTDIR/paraview_state.py`: the series coloured by pressure,
                                      walls in grey

Errors are one line on stderr with exit status 2 (missing folder, no .pvd series, unknown field, bad option).
"""
import argparse
import json
import os
import shutil
import subprocess
import sys

import numpy as np

from .vtkxml import VtkReadError, find_series, read_vtk

PROG = "snapshots.py"
UNITS = {"pressure": "Pa", "velocity": "m/s", "displacement": "m", "von_mises": "Pa", "acceleration": "m/s²",
         "pore_pressure": "Pa", "damage": "-", "thickness": "m", "rotation": "rad", "axial_force": "N/m",
         "shear_force": "N/m", "bending_moment": "N", "volume": "m²", "plastic_multiplier": "-"}
WALL_GREY = "0.45"
PLAIN = {"solid": "#c9a46a", "shell": "#4a5a6a", "mpm": "#b08a5a", "fluid": "#6fa8dc", "dem": "#a0a0a0"}


class UserError(Exception):
    """A one-line error for the user (exit status 2)."""


# --------------------------------------------------------------------------------------------- bodies

class Body:
    """One series of the output folder: name, role (fluid, walls, solid, shell, mpm, dem, grid), its
    (time, path) entries and a cache of read data sets."""

    def __init__(self, name, role, entries):
        self.name, self.role, self.entries = name, role, entries
        self.times = np.array([t for t, _ in entries])
        self._cache = {}

    def at(self, t):
        """The data set nearest to time t (None if the series is empty)."""
        if not self.entries:
            return None
        i = int(np.argmin(np.abs(self.times - t)))
        if i not in self._cache:
            if len(self._cache) > 8:
                self._cache.clear()
            self._cache[i] = read_vtk(self.entries[i][1])
        return self._cache[i]


def _case_roles(out_dir):
    """{body name: type} and the resolved case (or {} and None) from resolved_case.json."""
    try:
        with open(os.path.join(out_dir, "resolved_case.json")) as f:
            case = json.load(f)
        return {b.get("name"): b.get("type") for b in case.get("bodies", [])}, case
    except (OSError, ValueError):
        return {}, None


def classify(out_dir):
    """The bodies of an output folder, in drawing order (walls, fluids, solids, shells, MPM, DEM)."""
    series = find_series(out_dir)
    types, case = _case_roles(out_dir)
    bodies = []
    for name, entries in series.items():
        role = None
        if types.get(name) in ("fluid", "solid", "shell", "mpm", "dem"):
            role = types[name]
        elif name.endswith("_walls") and types.get(name[:-6]) == "fluid":
            role = "walls"
        elif name.endswith("_grid") and types.get(name[:-5]) == "mpm":
            role = "grid"
        if role is None:  # no resolved case (or a new kind of body): guess from the first data set
            if not entries:
                continue
            d = read_vtk(entries[0][1])
            pd = d.point_data
            if name.endswith("_walls"):
                role = "walls"
            elif name.endswith("_grid") and "mass" in pd:
                role = "grid"
            elif "radius" in pd:
                role = "dem"
            elif d.kind == "UnstructuredGrid":
                role = "fluid" if "kind" in pd else "solid"
            elif d.lines:
                role = "shell"
            else:
                role = "mpm"
        if role in ("shell", "solid") and types.get(name) == "solid" and entries and entries[0][1].endswith(".vtp"):
            role = "shell"  # a structure written as polylines is drawn as a shell
        bodies.append(Body(name, role, entries))
    order = {"walls": 0, "fluid": 1, "solid": 2, "shell": 3, "mpm": 4, "dem": 5, "grid": 6}
    bodies.sort(key=lambda b: (order.get(b.role, 9), b.name))
    return bodies, case


def static_walls(case, bodies):
    """Grey segments [(x0, y0, x1, y1) polylines as (n, 2) arrays] from the resolved case: fluid walls when the
    fluid has no _walls series, and MPM boundary segments."""
    if case is None:
        return []
    have = {b.name for b in bodies}
    out = []
    for b in case.get("bodies", []):
        if b.get("type") == "fluid" and b.get("name", "") + "_walls" not in have:
            for w in b.get("walls", []):
                pts = np.array(w.get("points", []), dtype=float)
                if len(pts) >= 2 and not w.get("motion"):
                    out.append(pts)
        if b.get("type") == "mpm":
            for bc in b.get("boundary_conditions", []):
                sel = bc.get("select", {})
                if sel.get("type") == "segment" and "from" in sel and "to" in sel:
                    out.append(np.array([sel["from"], sel["to"]], dtype=float))
    return out


# --------------------------------------------------------------------------------------------- fields

def _von_mises(s):
    """von Mises stress of (n, 4) stresses (xx, yy, xy, zz)."""
    sxx, syy, sxy, szz = s[:, 0], s[:, 1], s[:, 2], s[:, 3]
    return np.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2) + 3.0 * sxy ** 2)


def field_values(body, d, field):
    """Point values of `field` on data set d of `body` (vector fields by magnitude), or None."""
    pd = d.point_data
    if body.role in ("walls", "grid"):
        return None
    if field in pd:
        v = pd[field]
    elif body.role == "mpm" and field == "pressure" and "stress" in pd:
        v = pd["pore_pressure"] if "pore_pressure" in pd else -(pd["stress"][:, 0] + pd["stress"][:, 1] +
                                                                 pd["stress"][:, 3]) / 3.0
    elif field == "von_mises" and body.role in ("mpm", "solid"):
        s = pd.get("stress", pd.get("cauchy_stress"))
        if s is None or s.ndim != 2 or s.shape[1] != 4:
            return None
        v = _von_mises(s)
    else:
        return None
    v = np.asarray(v, dtype=float)
    if v.ndim == 2:
        v = np.linalg.norm(v, axis=1)
    return v


def available_fields(bodies, t):
    """Sorted names of the fields that some body can be coloured by."""
    names = set()
    for b in bodies:
        if b.role in ("walls", "grid"):
            continue
        d = b.at(t)
        if d is None:
            continue
        names.update(k for k in d.point_data if k not in ("kind", "particle_id", "free_surface"))
        if b.role == "mpm" and "stress" in d.point_data:
            names.update(("pressure", "von_mises"))
        if b.role == "solid" and "cauchy_stress" in d.point_data:
            names.add("von_mises")
    return sorted(names)


def default_field(bodies):
    roles = {b.role for b in bodies}
    if "fluid" in roles:
        return "pressure"
    if "solid" in roles:
        return "von_mises"
    if "shell" in roles:
        return "displacement"
    return "velocity"


def field_label(field):
    unit = UNITS.get(field)
    name = field.replace("_", " ")
    if field in ("velocity", "displacement", "acceleration"):
        name = "|%s|" % name
    return "%s [%s]" % (name, unit) if unit else name


# --------------------------------------------------------------------------------------------- geometry

_SUBDIVISION = {}


def _sub_triangles(nodes):
    """Local sub-triangles of a Lagrange triangle with `nodes` nodes in VTK order (3, 6, 10)."""
    if nodes in _SUBDIVISION:
        return _SUBDIVISION[nodes]
    if nodes == 3:
        sub = [(0, 1, 2)]
    elif nodes == 6:
        sub = [(0, 3, 5), (3, 1, 4), (5, 4, 2), (3, 4, 5)]
    elif nodes == 10:
        # Barycentric lattice (i, j, k), i + j + k = 3; vertices, edge nodes from their first vertex, interior.
        lat = {(3, 0, 0): 0, (0, 3, 0): 1, (0, 0, 3): 2, (2, 1, 0): 3, (1, 2, 0): 4, (0, 2, 1): 5, (0, 1, 2): 6,
               (1, 0, 2): 7, (2, 0, 1): 8, (1, 1, 1): 9}

        def node(j, k):
            return lat[(3 - j - k, j, k)]
        sub = []
        for j in range(3):
            for k in range(3 - j):
                sub.append((node(j, k), node(j + 1, k), node(j, k + 1)))
                if j + k <= 1:
                    sub.append((node(j + 1, k), node(j + 1, k + 1), node(j, k + 1)))
    else:
        sub = [(0, 1, 2)]
    _SUBDIVISION[nodes] = sub
    return sub


def linear_triangles(d):
    """(m, 3) linear triangles covering the triangle cells of d (quadratic and cubic cells subdivided)."""
    if d.kind != "UnstructuredGrid" or len(d.offsets) == 0:
        return d.triangles()
    starts = np.concatenate(([0], d.offsets[:-1]))
    counts = d.offsets - starts
    out = []
    for n in np.unique(counts):
        if n < 3:
            continue
        s = starts[counts == n]
        if len(d.types) == len(starts):
            s = s[np.isin(d.types[counts == n], (5, 22, 69))]
        if len(s) == 0:
            continue
        cells = d.connectivity[s[:, None] + np.arange(n)[None, :]]
        for a, b, c in _sub_triangles(int(n)):
            out.append(cells[:, [a, b, c]])
    return np.concatenate(out) if out else np.zeros((0, 3), dtype=np.int64)


def boundary_edges(tris):
    """(k, 2) edges of the triangles that belong to one triangle only."""
    if len(tris) == 0:
        return np.zeros((0, 2), dtype=np.int64)
    e = np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]])
    key = np.sort(e, axis=1)
    _, idx, cnt = np.unique(key, axis=0, return_index=True, return_counts=True)
    return e[idx[cnt == 1]]


def spacing(body, d, tris=None):
    """A typical particle spacing (for marker sizes)."""
    pd = d.point_data
    if "volume" in pd and len(pd["volume"]):
        return float(np.sqrt(np.median(np.abs(pd["volume"]))))
    if tris is not None and len(tris):
        e = d.points[tris[:, 1]] - d.points[tris[:, 0]]
        return float(np.median(np.hypot(e[:, 0], e[:, 1])))
    if d.n_points > 1:
        ext = d.points.max(axis=0) - d.points.min(axis=0)
        return float(np.sqrt(max(ext[0] * ext[1], 1e-30) / d.n_points))
    return 0.0


# --------------------------------------------------------------------------------------------- drawing

class Scene:
    """Draws the bodies of one time into an axes with a fixed norm and colour map."""

    def __init__(self, bodies, walls, field, norm, cmap, fluid_style):
        self.bodies, self.walls, self.field = bodies, walls, field
        self.norm, self.cmap, self.fluid_style = norm, cmap, fluid_style

    def draw(self, ax, t):
        """Adds the artists of time t to ax; returns them and the time actually drawn (of the first body)."""
        from matplotlib.collections import EllipseCollection, LineCollection
        arts, shown = [], None
        pts_per_unit = _points_per_unit(ax)
        for w in self.walls:
            arts += ax.plot(w[:, 0], w[:, 1], color=WALL_GREY, lw=2.0, solid_capstyle="round", zorder=1)
        for b in self.bodies:
            if b.role == "grid":
                continue
            d = b.at(t)
            if d is None or d.n_points == 0:
                continue
            if shown is None and b.role != "walls":
                shown = b.entries[int(np.argmin(np.abs(b.times - t)))][0]
            x, y = d.points[:, 0], d.points[:, 1]
            v = field_values(b, d, self.field)
            if b.role == "walls":
                segs = [d.points[c] for c in d.line_cells() if len(c) > 1]
                if segs:
                    arts.append(ax.add_collection(LineCollection(segs, colors=WALL_GREY, linewidths=2.0, zorder=1,
                                                                 capstyle="round")))
                else:
                    arts.append(ax.scatter(x, y, s=2, c=WALL_GREY, lw=0, zorder=1))
            elif b.role == "fluid":
                kind = d.point_data.get("kind", np.zeros(d.n_points))
                tris = linear_triangles(d)
                h = spacing(b, d, tris)
                size = max(0.8 * h * pts_per_unit, 1.5 * 72.0 / ax.figure.dpi) ** 2
                wall = kind == 1
                if wall.any() and not any(o.role == "walls" and o.name == b.name + "_walls" for o in self.bodies):
                    arts.append(ax.scatter(x[wall], y[wall], s=size, c=WALL_GREY, lw=0, zorder=1))
                fluid = kind == 0
                loose = fluid
                if self.fluid_style == "mesh" and len(tris):
                    if v is not None:
                        arts.append(ax.tripcolor(x, y, tris, v, shading="gouraud", cmap=self.cmap, norm=self.norm,
                                                 zorder=2, rasterized=True))
                    else:
                        arts.append(ax.tripcolor(x, y, tris, np.zeros(len(tris)), cmap=_plain_cmap(PLAIN["fluid"]),
                                                 zorder=2, rasterized=True))
                    loose = fluid & ~d.in_cells()
                if loose.any():
                    if v is not None:
                        arts.append(ax.scatter(x[loose], y[loose], s=size, c=v[loose], cmap=self.cmap, norm=self.norm,
                                               lw=0, zorder=3))
                    else:
                        arts.append(ax.scatter(x[loose], y[loose], s=size, c=PLAIN["fluid"], lw=0, zorder=3))
            elif b.role == "solid":
                tris = linear_triangles(d)
                if len(tris):
                    if v is not None:
                        arts.append(ax.tripcolor(x, y, tris, v, shading="gouraud", cmap=self.cmap, norm=self.norm,
                                                 zorder=4, rasterized=True))
                    else:
                        arts.append(ax.tripcolor(x, y, tris, np.zeros(len(tris)), cmap=_plain_cmap(PLAIN["solid"]),
                                                 zorder=4, rasterized=True))
                    e = boundary_edges(tris)
                    arts.append(ax.add_collection(LineCollection(d.points[e], colors="0.15", linewidths=0.6,
                                                                 zorder=5)))
                else:
                    arts.append(ax.scatter(x, y, s=2, c=PLAIN["solid"] if v is None else v, cmap=self.cmap,
                                           norm=self.norm, lw=0, zorder=4))
            elif b.role == "shell":
                segs, vals = [], []
                for c in d.line_cells():
                    for i, j in zip(c[:-1], c[1:]):
                        segs.append(d.points[[i, j]])
                        if v is not None:
                            vals.append(0.5 * (v[i] + v[j]))
                lc = LineCollection(segs, linewidths=3.0, zorder=6, capstyle="round")
                if v is not None:
                    lc.set_array(np.array(vals))
                    lc.set_cmap(self.cmap)
                    lc.set_norm(self.norm)
                else:
                    lc.set_color(PLAIN["shell"])
                arts.append(ax.add_collection(lc))
            elif b.role == "dem" and "radius" in d.point_data:
                r = np.asarray(d.point_data["radius"], dtype=float).ravel()
                ec = EllipseCollection(2 * r, 2 * r, np.zeros_like(r), units="xy", offsets=d.points,
                                       offset_transform=ax.transData, zorder=7, edgecolors="0.2", linewidths=0.3)
                if v is not None:
                    ec.set_array(v)
                    ec.set_cmap(self.cmap)
                    ec.set_norm(self.norm)
                else:
                    ec.set_facecolor(PLAIN["dem"])
                arts.append(ax.add_collection(ec))
            else:  # MPM and other particle series
                h = spacing(b, d)
                size = max(1.25 * h * pts_per_unit, 1.5 * 72.0 / ax.figure.dpi) ** 2  # overlapping, >= 1.5 px
                if v is not None:
                    arts.append(ax.scatter(x, y, s=size, c=v, cmap=self.cmap, norm=self.norm, lw=0, marker="s",
                                           zorder=6))
                else:
                    arts.append(ax.scatter(x, y, s=size, c=PLAIN["mpm"], lw=0, marker="s", zorder=6))
        return arts, (t if shown is None else shown)


def _points_per_unit(ax):
    """Typographic points per data unit along x of an axes whose limits and size are set."""
    fig = ax.figure
    ax.apply_aspect()
    w_in = ax.get_position().width * fig.get_figwidth()
    x0, x1 = ax.get_xlim()
    return 72.0 * w_in / max(x1 - x0, 1e-30)


def _plain_cmap(color):
    from matplotlib.colors import ListedColormap
    return ListedColormap([color])


# --------------------------------------------------------------------------------------------- frames

def bounds(bodies, walls, times):
    """[xmin, xmax, ymin, ymax] of everything drawn at `times`, with a small margin."""
    lo, hi = np.array([np.inf, np.inf]), np.array([-np.inf, -np.inf])
    for w in walls:
        lo, hi = np.minimum(lo, w.min(axis=0)), np.maximum(hi, w.max(axis=0))
    for b in bodies:
        if b.role == "grid":
            continue
        for t in times:
            d = b.at(t)
            if d is None or d.n_points == 0:
                continue
            p = d.points[np.all(np.isfinite(d.points), axis=1)]
            if len(p) == 0:
                continue
            if b.role in ("fluid", "mpm", "dem") and len(p) >= 400:  # a few flying drops do not set the frame
                ext = np.percentile(p, 0.25, axis=0), np.percentile(p, 99.75, axis=0)
            else:
                ext = p.min(axis=0), p.max(axis=0)
            if b.role == "dem" and "radius" in d.point_data:
                r = float(np.max(d.point_data["radius"]))
                ext = ext[0] - r, ext[1] + r
            lo, hi = np.minimum(lo, ext[0]), np.maximum(hi, ext[1])
    if not np.all(np.isfinite(lo)):
        raise UserError("nothing to draw: every series is empty")
    size = np.maximum(hi - lo, 1e-9)
    m = 0.03 * max(size)
    box = [lo[0] - m, hi[0] + m, lo[1] - m, hi[1] + m]
    # a very tall or very flat picture is widened (or heightened) about its centre to an aspect of 1:3 (3:1)
    w, h = box[1] - box[0], box[3] - box[2]
    if w < h / 3:
        c = 0.5 * (box[0] + box[1])
        box[0], box[1] = c - h / 6, c + h / 6
    elif h < w / 6:
        c = 0.5 * (box[2] + box[3])
        box[2], box[3] = c - w / 12, c + w / 12
    return box


def colour_range(bodies, field, times, given):
    """(vmin, vmax, extend): --range, else per frame the 0.5 and 99.5 percentiles of the values drawn at `times`,
    then the 10th percentile of the lows and the 90th of the highs over the frames (a frame with a pressure spike
    over the whole fluid does not set the scale); from 0 for magnitudes and non-negative fields. `extend` tells
    the colour bar whether values lie beyond the range ("neither", "min", "max", "both")."""
    lows, highs, dmin, dmax = [], [], np.inf, -np.inf
    for t in times:
        vals = []
        for b in bodies:
            d = b.at(t)
            if d is None:
                continue
            v = field_values(b, d, field)
            if v is not None and len(v):
                vals.append(v[np.isfinite(v)])
        v = np.concatenate(vals) if vals else np.zeros(0)
        if len(v):
            lo, hi = np.percentile(v, [0.5, 99.5])
            lows.append(lo)
            highs.append(hi)
            dmin, dmax = min(dmin, v.min()), max(dmax, v.max())
    if given:
        lo, hi = given
    elif not lows:
        lo, hi = 0.0, 1.0
    else:
        lo, hi = float(np.percentile(lows, 10)), float(np.percentile(highs, 90))
        if lo >= 0 and (field in ("velocity", "displacement", "acceleration", "von_mises") or dmin >= 0):
            lo = 0.0
        if hi <= lo:
            hi = lo + max(abs(lo) * 1e-3, 1e-12)
    below, above = bool(dmin < lo), bool(dmax > hi)
    extend = "both" if below and above else "min" if below else "max" if above else "neither"
    return float(lo), float(hi), extend


def pick_times(all_times, requested, count):
    """Output times nearest to the requested ones (or `count` evenly spaced over the run), without repeats."""
    if requested is None:
        count = max(1, min(count, len(all_times)))
        requested = np.linspace(all_times[0], all_times[-1], count)
    out = []
    for r in requested:
        t = float(all_times[int(np.argmin(np.abs(all_times - r)))])
        if not any(abs(t - s) <= 1e-12 * max(1.0, abs(t)) for s in out):
            out.append(t)
    return out


def frame_times(all_times, frames):
    if len(all_times) <= frames:
        return [float(t) for t in all_times]
    idx = np.unique(np.round(np.linspace(0, len(all_times) - 1, frames)).astype(int))
    return [float(all_times[i]) for i in idx]


def _fmt_time(t):
    return ("%.4f" % t).rstrip("0").rstrip(".") if t != 0 else "0"


def strip_layout(n, aspect):
    """(rows, cols) for n panels of width/height `aspect`, aiming at a strip about 5 times as wide as high."""
    best = None
    for cols in range(1, n + 1):
        rows = -(-n // cols)
        if rows > 1 and (rows - 1) * cols >= n:
            continue
        ratio = cols * aspect / rows
        score = abs(np.log(ratio / 5.0)) + 0.3 * (rows * cols - n)
        if best is None or score < best[0]:
            best = (score, rows, cols)
    return best[1], best[2]


# --------------------------------------------------------------------------------------------- ParaView state

STATE = '''# ParaView state of a lagfsi output folder (written by scripts/snapshots.py).
# Open it with   paraview --state=%(path)s
# (or File > Load State in ParaView, or run it in ParaView's Python shell / pvpython).
# Fluids are coloured by pressure, solids by von Mises, shells by bending moment, MPM particles by velocity;
# walls in grey.
import os
from paraview.simple import *

FOLDER = %(folder)r
try:  # the folder of this file, when it was moved with its series
    _here = os.path.dirname(os.path.abspath(__file__))
    if os.path.exists(os.path.join(_here, %(first)r)):
        FOLDER = _here
except NameError:
    pass

# (series, role): role is fluid, walls, solid, shell, mpm, dem or grid.
SERIES = %(series)r
PRESSURE_RANGE = %(prange)r  # the colour range of the pressure (None: ParaView's own)
GREY = [0.5, 0.5, 0.5]

view = GetActiveViewOrCreate("RenderView")
view.InteractionMode = "2D"
view.OrientationAxesVisibility = 0
for name, role in SERIES:
    if role == "grid":
        continue
    src = PVDReader(FileName=os.path.join(FOLDER, name + ".pvd"))
    RenameSource(name, src)
    disp = Show(src, view)
    if role == "walls":
        ColorBy(disp, None)
        disp.AmbientColor = GREY
        disp.DiffuseColor = GREY
        disp.LineWidth = 3.0
    elif role == "fluid":
        ColorBy(disp, ("POINTS", "pressure"))
        lut = GetColorTransferFunction("pressure")
        lut.ApplyPreset("Viridis (matplotlib)", True)
        if PRESSURE_RANGE:
            lut.RescaleTransferFunction(*PRESSURE_RANGE)
        disp.SetScalarBarVisibility(view, True)
        # wall particles (kind 1) of the fluid in grey, as points
        walls = Threshold(Input=src)
        RenameSource(name + "_wall_particles", walls)
        walls.Scalars = ["POINTS", "kind"]
        try:
            walls.LowerThreshold, walls.UpperThreshold = 0.5, 1.5
        except AttributeError:  # ParaView < 5.10
            walls.ThresholdRange = [0.5, 1.5]
        wd = Show(walls, view)
        ColorBy(wd, None)
        wd.SetRepresentationType("Points")
        wd.AmbientColor = GREY
        wd.DiffuseColor = GREY
        wd.PointSize = 3.0
    elif role == "solid":
        ColorBy(disp, ("POINTS", "von_mises"))
        disp.SetScalarBarVisibility(view, True)
    elif role == "shell":
        ColorBy(disp, ("POINTS", "bending_moment"))
        disp.LineWidth = 4.0
    elif role in ("mpm", "dem"):
        disp.SetRepresentationType("Points")
        disp.PointSize = 3.0
        ColorBy(disp, ("POINTS", "velocity", "Magnitude"))
        disp.SetScalarBarVisibility(view, True)

GetAnimationScene().UpdateAnimationUsingDataTimeSteps()
view.ResetCamera()
Render()
'''


def write_state(out_dir, dest, bodies, prange):
    series = [(b.name, b.role) for b in bodies if b.entries]
    path = os.path.join(dest, "paraview_state.py")
    first = (series[0][0] + ".pvd") if series else ""
    with open(path, "w") as f:
        f.write(STATE % {"path": path, "folder": os.path.abspath(out_dir), "first": first, "series": series,
                         "prange": prange})
    return path


# --------------------------------------------------------------------------------------------- main

class _Parser(argparse.ArgumentParser):
    def error(self, message):
        raise UserError(message)


def _floats(text, what, n=None):
    try:
        v = [float(s) for s in text.split(",") if s.strip() != ""]
    except ValueError:
        raise UserError("%s: not a comma-separated list of numbers: %r" % (what, text))
    if not v or (n is not None and len(v) != n) or not all(np.isfinite(v)):
        raise UserError("%s: expected %s finite numbers, got %r" % (what, n or "one or more", text))
    return v


def parse_args(argv):
    p = _Parser(prog=PROG, description=__doc__.split("\n\n", 2)[2], usage=__doc__.split("\n\n")[1][7:],
                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("out_dir", metavar="OUTDIR", help="a lagfsi output folder (with <body>.pvd series)")
    p.add_argument("--field", help="colouring field (default: pressure with a fluid, else von_mises with a solid, "
                   "else displacement with a shell, else velocity)")
    p.add_argument("--times", help="comma-separated times of the snapshots (nearest outputs)")
    p.add_argument("--count", type=int, default=5, help="number of snapshots evenly spaced over the run (default 5)")
    p.add_argument("--frames", type=int, default=60, help="largest number of animation frames (default 60)")
    p.add_argument("--range", dest="vrange", help="colour range VMIN,VMAX (default: from the values, see above); "
                   "negative values as --range=-1,1")
    p.add_argument("--box", help="drawn region XMIN,XMAX,YMIN,YMAX, negative values as --box=-0.1,1,0,1 "
                   "(default: everything drawn, a few flying drops excepted)")
    p.add_argument("--fluid", choices=("mesh", "particles"), default="mesh", help="fluid drawn as (default mesh)")
    p.add_argument("--cmap", default="viridis", help="matplotlib colour map (default viridis)")
    p.add_argument("--dpi", type=int, default=90, help="resolution of the pictures (default 90)")
    p.add_argument("--out", help="folder of the pictures (default OUTDIR)")
    p.add_argument("--no-animation", action="store_true", help="no animation.gif / animation.mp4")
    p.add_argument("--no-mp4", action="store_true", help="no animation.mp4 even when ffmpeg is present")
    p.add_argument("--no-state", action="store_true", help="no paraview_state.py")
    p.add_argument("--quiet", action="store_true", help="print nothing but errors")
    a = p.parse_args(argv)
    if a.count < 1 or a.frames < 1 or a.dpi < 10:
        raise UserError("--count and --frames must be at least 1, --dpi at least 10")
    a.times = _floats(a.times, "--times") if a.times is not None else None
    a.vrange = tuple(_floats(a.vrange, "--range", 2)) if a.vrange is not None else None
    a.box = _floats(a.box, "--box", 4) if a.box is not None else None
    if a.box and (a.box[1] <= a.box[0] or a.box[3] <= a.box[2]):
        raise UserError("--box: XMAX must be larger than XMIN and YMAX than YMIN")
    if a.vrange and a.vrange[1] <= a.vrange[0]:
        raise UserError("--range: VMAX must be larger than VMIN")
    return a


def run(argv):
    a = parse_args(argv)
    if not os.path.isdir(a.out_dir):
        raise UserError("%s: no such folder" % a.out_dir)
    try:
        if not any(f.endswith(".pvd") for f in os.listdir(a.out_dir)):
            raise UserError("%s: no .pvd series (not a lagfsi output folder, or the run wrote no VTK output)" %
                            a.out_dir)
    except OSError as e:
        raise UserError("%s: cannot list the folder (%s)" % (a.out_dir, e.strerror))
    dest = a.out if a.out else a.out_dir
    os.makedirs(dest, exist_ok=True)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import Normalize
    try:
        cmap = matplotlib.colormaps[a.cmap]
    except (KeyError, AttributeError):
        try:
            cmap = plt.get_cmap(a.cmap)
        except ValueError:
            raise UserError("--cmap: unknown colour map %r" % a.cmap)

    bodies, case = classify(a.out_dir)
    drawn = [b for b in bodies if b.role != "grid" and b.entries]
    if not drawn:
        raise UserError("%s: every .pvd series is empty" % a.out_dir)
    main = max((b for b in drawn if b.role != "walls"), key=lambda b: len(b.entries), default=drawn[0])
    all_times = main.times
    field = a.field or default_field(bodies)
    avail = available_fields(bodies, float(all_times[-1]))
    if field not in avail:
        raise UserError("unknown field %r for %s (available: %s)" % (field, a.out_dir, ", ".join(avail) or "none"))
    walls = static_walls(case, bodies)
    snap_t = pick_times(all_times, a.times, a.count)
    anim_t = [] if a.no_animation else frame_times(all_times, a.frames)
    every_t = sorted(set(snap_t) | set(anim_t))
    box = a.box or bounds(drawn, walls, every_t)
    # the colour scale from up to 60 frames over the whole run, whatever is drawn
    vmin, vmax, extend = colour_range(drawn, field, sorted(set(snap_t) | set(frame_times(all_times, 60))), a.vrange)
    norm = Normalize(vmin, vmax)
    scene = Scene(drawn, walls, field, norm, cmap, a.fluid)
    name = (case or {}).get("name") or os.path.basename(os.path.abspath(a.out_dir))
    label = field_label(field)
    aspect = (box[1] - box[0]) / (box[3] - box[2])
    say = (lambda *m: None) if a.quiet else (lambda *m: print(*m))
    written = []

    # One figure for the single pictures and the animation frames: a plot of at most 6.4 x 5 in (sizes in inches:
    # margins, plot, gap, colour bar, room for its labels).
    pw = min(6.4, 5.0 * aspect)
    ph = pw / aspect
    narrow = pw < 3.5
    left, bottom, top, right = 0.6, 0.35, 0.65 if narrow else 0.4, 1.0
    W, H = left + pw + 0.15 + 0.15 + right, bottom + ph + top
    fig = plt.figure(figsize=(W, H), dpi=a.dpi)
    ax = fig.add_axes([left / W, bottom / H, pw / W, ph / H])
    cax = fig.add_axes([(left + pw + 0.15) / W, bottom / H, 0.15 / W, ph / H])
    sm = matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap)
    fig.colorbar(sm, cax=cax, extend=extend).set_label(label, fontsize=8)
    cax.tick_params(labelsize=7)
    ax.set_xlim(box[0], box[1])
    ax.set_ylim(box[2], box[3])
    ax.set_aspect("equal", adjustable="box")
    ax.tick_params(labelsize=7)
    title = ax.set_title("", fontsize=9)

    def render(t):
        arts, shown = scene.draw(ax, t)
        title.set_text(("%s\nt = %s s" if narrow else "%s   t = %s s") % (name, _fmt_time(shown)))
        return arts, shown

    snap_dir = os.path.join(dest, "snapshots")
    os.makedirs(snap_dir, exist_ok=True)
    for f in os.listdir(snap_dir):  # pictures of an earlier call
        if f.endswith(".png"):
            os.remove(os.path.join(snap_dir, f))
    for k, t in enumerate(snap_t):
        arts, shown = render(t)
        path = os.path.join(snap_dir, "%s_%02d_t%s.png" % (field, k, _fmt_time(shown)))
        fig.savefig(path, dpi=a.dpi)
        written.append(path)
        for art in arts:
            art.remove()

    frames = []
    for t in anim_t:
        arts, _ = render(t)
        fig.canvas.draw()
        frames.append(np.asarray(fig.canvas.buffer_rgba())[:, :, :3].copy())
        for art in arts:
            art.remove()
    plt.close(fig)

    # The strip.
    n = len(snap_t)
    rows, cols = strip_layout(n, aspect)
    panel_w = min(12.0 / cols, 3.0 * aspect, 6.0)
    panel_h = panel_w / aspect
    sfig, axes = plt.subplots(rows, cols, figsize=(cols * panel_w + 0.9, rows * (panel_h + 0.35) + 0.45),
                              squeeze=False, dpi=a.dpi)
    for k, sax in enumerate(axes.flat):
        if k >= n:
            sax.axis("off")
            continue
        sax.set_xlim(box[0], box[1])
        sax.set_ylim(box[2], box[3])
        sax.set_aspect("equal", adjustable="box")
        sax.tick_params(labelsize=6)
        if k % cols:
            sax.set_yticklabels([])
        if k < n - cols:
            sax.set_xticklabels([])
    sfig.subplots_adjust(left=0.45 / sfig.get_figwidth() * 1.4, right=1 - 0.9 / sfig.get_figwidth(),
                         bottom=0.35 / sfig.get_figheight(), top=1 - 0.5 / sfig.get_figheight(),
                         wspace=0.06, hspace=0.3)
    for k, t in enumerate(snap_t):
        sax = axes.flat[k]
        _, shown = scene.draw(sax, t)
        sax.set_title("t = %s s" % _fmt_time(shown), fontsize=8)
    # colour bar beside the panels, spanning all rows
    top = axes.flat[0].get_position().y1
    bottom = axes.flat[(rows - 1) * cols].get_position().y0
    cb_ax = sfig.add_axes([1 - 0.75 / sfig.get_figwidth(), bottom, 0.12 / sfig.get_figwidth(), top - bottom])
    sfig.colorbar(matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap), cax=cb_ax, extend=extend).set_label(
        label, fontsize=7)
    cb_ax.tick_params(labelsize=6)
    sfig.suptitle("%s: %s" % (name, label), fontsize=9)
    strip = os.path.join(dest, "snapshots.png")
    sfig.savefig(strip, dpi=a.dpi, bbox_inches="tight", pad_inches=0.08)
    plt.close(sfig)
    written.insert(0, strip)

    if frames:
        from PIL import Image
        imgs = [Image.fromarray(f) for f in frames]
        pal = imgs[len(imgs) // 2].quantize(colors=128, method=Image.Quantize.MEDIANCUT) \
            if hasattr(Image, "Quantize") else imgs[len(imgs) // 2].quantize(colors=128)
        q = [im.quantize(palette=pal, dither=0) for im in imgs]
        gif = os.path.join(dest, "animation.gif")
        duration = int(max(60, min(200, 6000 / len(q))))
        q[0].save(gif, save_all=True, append_images=q[1:], duration=duration, loop=0, optimize=False)
        written.append(gif)
        ffmpeg = shutil.which("ffmpeg")
        if ffmpeg and not a.no_mp4:
            mp4 = os.path.join(dest, "animation.mp4")
            h, w = frames[0].shape[:2]
            cmd = [ffmpeg, "-y", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt", "rgb24", "-s", "%dx%d" % (w, h),
                   "-r", "%g" % (1000.0 / duration), "-i", "-", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                   "-pix_fmt", "yuv420p", "-c:v", "libx264", mp4]
            r = subprocess.run(cmd, input=b"".join(f.tobytes() for f in frames), capture_output=True)
            if r.returncode == 0:
                written.append(mp4)
            else:
                print("%s: ffmpeg failed, no animation.mp4: %s" % (PROG, r.stderr.decode(errors="replace")
                                                                    .strip().splitlines()[-1:]), file=sys.stderr)

    if not a.no_state:
        prange = (vmin, vmax) if field == "pressure" else None
        written.append(write_state(a.out_dir, dest, bodies, prange))

    say("%s: %s coloured by %s (%.4g to %.4g), %d snapshots, %d animation frames" %
        (PROG, name, field, vmin, vmax, len(snap_t), len(frames)))
    for w in written:
        say("wrote", w)
    return 0


def main(argv=None):
    try:
        return run(sys.argv[1:] if argv is None else argv)
    except UserError as e:
        print("%s: error: %s" % (PROG, e), file=sys.stderr)
        return 2
    except VtkReadError as e:
        print("%s: error: %s" % (PROG, e), file=sys.stderr)
        return 2
    except ImportError as e:
        print("%s: error: %s (install python3-matplotlib python3-numpy python3-pil: bash scripts/setup.sh)" %
              (PROG, e), file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("%s: interrupted" % PROG, file=sys.stderr)
        return 130
