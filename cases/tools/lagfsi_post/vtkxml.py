"""Pure-Python reader of the VTK XML files lagfsi writes (numpy only; no VTK module needed).

    from lagfsi_post.vtkxml import read_vtk, read_pvd, find_series
    series = find_series("out/dam_break_tank")       # {"water": [(t, path), ...], "water_walls": [...]}
    d = read_vtk(series["water"][-1][1])             # a Dataset
    d.points            # (n, 2) float array (z dropped)
    d.point_data        # {"pressure": (n,), "velocity": (n, 3), ...}
    d.triangles()       # (m, 3) corner nodes of the triangles (linear, quadratic or Lagrange cells)
    d.lines             # list of node-index arrays (polydata Lines: polylines)

Formats: UnstructuredGrid (.vtu) and PolyData (.vtp), pieces with "appended" data (raw or base64, zlib-compressed
or not, UInt32 or UInt64 headers, either byte order), "binary" (base64) inline data and "ascii" data, which covers
what VTK's XML writers produce (lagfsi writes binary appended raw, zlib, see src/core/vtk_output.cpp). Collections
(.pvd): read_pvd gives the (time, absolute path) of each data set, sorted by time.
"""
import base64
import os
import re
import xml.etree.ElementTree as ET
import zlib

import numpy as np

_TYPES = {"Float64": "f8", "Float32": "f4", "Int64": "i8", "Int32": "i4", "Int16": "i2", "Int8": "i1",
          "UInt64": "u8", "UInt32": "u4", "UInt16": "u2", "UInt8": "u1"}

# VTK cell types whose first three nodes are a triangle's corners.
_TRIANGLE_TYPES = (5, 22, 69)  # VTK_TRIANGLE, VTK_QUADRATIC_TRIANGLE, VTK_LAGRANGE_TRIANGLE
_LINE_TYPES = (3, 4, 21, 68)   # VTK_LINE, VTK_POLY_LINE, VTK_QUADRATIC_EDGE, VTK_LAGRANGE_CURVE


class VtkReadError(Exception):
    """A file that is not a readable VTK XML file (the message names the file)."""


class Dataset:
    """One piece of a .vtu or .vtp file: points (n, 2), point_data / cell_data {name: array (n,) or (n, k)},
    and the cells: for a .vtu `connectivity`, `offsets`, `types`; for a .vtp `verts`, `lines`, `polys`
    (lists of node-index arrays)."""

    def __init__(self, path, kind):
        self.path = path
        self.kind = kind  # "UnstructuredGrid" or "PolyData"
        self.points = np.zeros((0, 2))
        self.point_data = {}
        self.cell_data = {}
        self.connectivity = np.zeros(0, dtype=np.int64)
        self.offsets = np.zeros(0, dtype=np.int64)
        self.types = np.zeros(0, dtype=np.uint8)
        self.verts, self.lines, self.polys = [], [], []

    @property
    def n_points(self):
        return len(self.points)

    def triangles(self):
        """(m, 3) node indices of the corners of the triangle cells (first three nodes of linear, quadratic and
        Lagrange triangles; .vtp polygons with three or more nodes are fanned)."""
        if self.kind == "PolyData":
            tris = [(p[0], p[k], p[k + 1]) for p in self.polys for k in range(1, len(p) - 1)]
            return np.array(tris, dtype=np.int64).reshape(-1, 3)
        if len(self.offsets) == 0:
            return np.zeros((0, 3), dtype=np.int64)
        starts = np.concatenate(([0], self.offsets[:-1]))
        sel = np.isin(self.types, _TRIANGLE_TYPES) if len(self.types) == len(starts) else np.ones(len(starts), bool)
        s = starts[sel]
        return np.stack([self.connectivity[s], self.connectivity[s + 1], self.connectivity[s + 2]], axis=1)

    def line_cells(self):
        """Polylines: the .vtp Lines, or the .vtu line-type cells (as node-index arrays)."""
        if self.kind == "PolyData":
            return self.lines
        starts = np.concatenate(([0], self.offsets[:-1])) if len(self.offsets) else np.zeros(0, np.int64)
        return [self.connectivity[a:b] for a, b, t in zip(starts, self.offsets, self.types) if t in _LINE_TYPES]

    def in_cells(self):
        """Boolean mask of the points used by some cell (.vtu cells, .vtp lines or polygons)."""
        used = np.zeros(self.n_points, dtype=bool)
        if self.kind == "PolyData":
            for group in (self.lines, self.polys):
                for c in group:
                    used[c] = True
        elif len(self.connectivity):
            used[self.connectivity] = True
        return used

    def __repr__(self):
        return "Dataset(%s, %d points, point data %s)" % (os.path.basename(self.path), self.n_points,
                                                           sorted(self.point_data))


def _read_binary(buf, pos, header, order, compressed):
    """Array bytes starting at buf[pos] (raw appended layout). Returns the decoded bytes."""
    hdt = np.dtype(header).newbyteorder(order)
    hs = hdt.itemsize
    if not compressed:
        (nbytes,) = np.frombuffer(buf, hdt, 1, pos)
        return bytes(buf[pos + hs:pos + hs + int(nbytes)])
    nb, _, _ = (int(v) for v in np.frombuffer(buf, hdt, 3, pos))
    sizes = np.frombuffer(buf, hdt, nb, pos + 3 * hs).astype(np.int64)
    p = pos + (3 + nb) * hs
    parts = []
    for s in sizes:
        parts.append(zlib.decompress(buf[p:p + s]))
        p += s
    return b"".join(parts)


def _read_base64(text, header, order, compressed):
    """Array bytes of base64 data (inline "binary" or appended base64): the header is encoded apart from the
    data when compressed, together with it otherwise."""
    hdt = np.dtype(header).newbyteorder(order)
    hs = hdt.itemsize
    text = "".join(text.split())
    if not compressed:
        raw = base64.b64decode(text)
        (nbytes,) = np.frombuffer(raw, hdt, 1, 0)
        return raw[hs:hs + int(nbytes)]
    # First the three fixed header words to learn the block count, then the whole header.
    first = base64.b64decode(text[:4 * ((3 * hs + 2) // 3)])
    nb = int(np.frombuffer(first, hdt, 1, 0)[0])
    hlen = (3 + nb) * hs
    henc = 4 * ((hlen + 2) // 3)
    head = base64.b64decode(text[:henc])
    sizes = np.frombuffer(head, hdt, nb, 3 * hs).astype(np.int64)
    data = base64.b64decode(text[henc:])
    parts, p = [], 0
    for s in sizes:
        parts.append(zlib.decompress(data[p:p + s]))
        p += s
    return b"".join(parts)


def read_vtk(path):
    """Reads a .vtu or .vtp file into a Dataset (first piece), or a .pvtu (an MPI run's step: its pieces merged into
    one Dataset, the points of each piece after the previous pieces'). Raises VtkReadError on an unreadable file."""
    if path.endswith(".pvtu"):
        return _read_pvtu(path)
    try:
        with open(path, "rb") as f:
            buf = f.read()
    except OSError as e:
        raise VtkReadError("%s: cannot read (%s)" % (path, e.strerror))
    try:
        return _parse(path, buf)
    except VtkReadError:
        raise
    except Exception as e:  # malformed XML, truncated data, bad zlib stream, ...
        raise VtkReadError("%s: not a readable VTK XML file (%s: %s)" % (path, type(e).__name__, e))


def _parse(path, buf):
    app = buf.find(b"<AppendedData")
    appended_start, appended_encoding = None, None
    if app >= 0:
        tag_end = buf.index(b">", app)
        m = re.search(rb'encoding="(\w+)"', buf[app:tag_end])
        appended_encoding = m.group(1).decode() if m else "raw"
        appended_start = buf.index(b"_", tag_end) + 1
        head = buf[:app].decode("utf-8", "replace") + "</VTKFile>"
    else:
        head = buf.decode("utf-8", "replace")
    root = ET.fromstring(head)
    if root.tag != "VTKFile":
        raise VtkReadError("%s: not a VTK XML file (root element %s)" % (path, root.tag))
    kind = root.get("type")
    if kind not in ("UnstructuredGrid", "PolyData"):
        raise VtkReadError("%s: unsupported VTK data set type %s" % (path, kind))
    order = "<" if root.get("byte_order", "LittleEndian") == "LittleEndian" else ">"
    header = _TYPES.get(root.get("header_type", "UInt32"), "u4")
    compressed = root.get("compressor", "") == "vtkZLibDataCompressor"
    if root.get("compressor") and not compressed:
        raise VtkReadError("%s: unsupported compressor %s" % (path, root.get("compressor")))
    piece = root.find(kind).find("Piece")
    if piece is None:
        raise VtkReadError("%s: no Piece" % path)

    def array(el):
        dt = np.dtype(_TYPES[el.get("type")]).newbyteorder(order)
        ncomp = int(el.get("NumberOfComponents", "1"))
        fmt = el.get("format", "ascii")
        if fmt == "ascii":
            a = np.array((el.text or "").split(), dtype=dt.newbyteorder("="))
        elif fmt == "binary":
            a = np.frombuffer(_read_base64(el.text or "", header, order, compressed), dt)
        elif fmt == "appended":
            if appended_start is None:
                raise VtkReadError("%s: appended array without AppendedData" % path)
            off = appended_start + int(el.get("offset"))
            if appended_encoding == "base64":
                end = buf.find(b"<", off)  # base64 stops at the next '<' or whitespace-delimited chunk
                text = buf[off:end if end >= 0 else len(buf)].decode("ascii").split()[0]
                a = np.frombuffer(_read_base64(text, header, order, compressed), dt)
            else:
                a = np.frombuffer(_read_binary(buf, off, header, order, compressed), dt)
        else:
            raise VtkReadError("%s: unsupported data format %s" % (path, fmt))
        a = a.astype(dt.newbyteorder("="), copy=False)
        return a.reshape(-1, ncomp) if ncomp > 1 else a

    d = Dataset(path, kind)
    pts = piece.find("Points")
    if pts is not None and pts.find("DataArray") is not None:
        p = array(pts.find("DataArray"))
        d.points = np.ascontiguousarray(p.reshape(len(p), -1)[:, :2], dtype=float)
    for tag, target in (("PointData", d.point_data), ("CellData", d.cell_data)):
        sec = piece.find(tag)
        if sec is not None:
            for el in sec.findall("DataArray"):
                target[el.get("Name", "")] = array(el)

    def cell_section(name):
        sec = piece.find(name)
        if sec is None:
            return {}
        return {el.get("Name"): array(el) for el in sec.findall("DataArray")}

    if kind == "UnstructuredGrid":
        c = cell_section("Cells")
        d.connectivity = c.get("connectivity", d.connectivity).astype(np.int64)
        d.offsets = c.get("offsets", d.offsets).astype(np.int64)
        d.types = c.get("types", d.types).astype(np.uint8)
    else:
        for name, attr in (("Verts", "verts"), ("Lines", "lines"), ("Polys", "polys")):
            c = cell_section(name)
            if "connectivity" in c and "offsets" in c:
                conn, offs = c["connectivity"].astype(np.int64), c["offsets"].astype(np.int64)
                starts = np.concatenate(([0], offs[:-1]))
                setattr(d, attr, [conn[a:b] for a, b in zip(starts, offs)])
    return d


def _xml_root(path, what):
    """The root element of the XML file `path` and its folder; VtkReadError naming `what` when it is not readable."""
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as e:
        raise VtkReadError("%s: not a readable %s (%s)" % (path, what, e))
    return root, os.path.dirname(os.path.abspath(path))


def _read_pvtu(path):
    root, base = _xml_root(path, ".pvtu file")
    pieces = [read_vtk(os.path.join(base, el.get("Source"))) for el in root.iter("Piece") if el.get("Source")]
    if not pieces:
        raise VtkReadError("%s: no Piece" % path)
    d = Dataset(path, "UnstructuredGrid")
    d.points = np.concatenate([q.points for q in pieces])
    shift, end = np.cumsum([0] + [q.n_points for q in pieces[:-1]]), np.cumsum([0] + [len(q.connectivity) for q in
                                                                                    pieces[:-1]])
    d.connectivity = np.concatenate([q.connectivity + k for q, k in zip(pieces, shift)]).astype(np.int64)
    d.offsets = np.concatenate([q.offsets + k for q, k in zip(pieces, end)]).astype(np.int64)
    d.types = np.concatenate([q.types for q in pieces]).astype(np.uint8)
    for name in pieces[0].point_data:
        d.point_data[name] = np.concatenate([q.point_data[name] for q in pieces])
    for name in pieces[0].cell_data:
        d.cell_data[name] = np.concatenate([q.cell_data[name] for q in pieces])
    return d


def read_pvd(path):
    """(time, absolute path) of every data set of a .pvd collection, sorted by time (stable)."""
    root, base = _xml_root(path, ".pvd collection")
    out = []
    for ds in root.iter("DataSet"):
        f = ds.get("file")
        if f is None:
            continue
        out.append((float(ds.get("timestep", "0")), os.path.join(base, f)))
    out.sort(key=lambda x: x[0])
    return out


def find_series(out_dir):
    """{series name: [(time, path), ...]} for every <name>.pvd in an output folder (sorted by name)."""
    names = sorted(f[:-4] for f in os.listdir(out_dir) if f.endswith(".pvd"))
    return {n: read_pvd(os.path.join(out_dir, n + ".pvd")) for n in names}


def nearest(entries, t):
    """The (time, path) of `entries` nearest to t."""
    return min(entries, key=lambda e: abs(e[0] - t))
