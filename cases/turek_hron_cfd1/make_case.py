"""Writes the case files of turek_hron_cfd1: the obstacle's outline depends on the spacing h (its circle is cut into
segments of about h, and the fluid region's hole follows the same points, so that the particles on it lie on the
walls), hence one file per resolution: case.json (h = 0.01 m), case_coarse.json (0.02 m), case_fine.json (0.007 m),
each with dt = min(h, 0.01) s. Usage: /usr/bin/python3 cases/turek_hron_cfd1/make_case.py (rewrites the three)."""
import json
import math
import os
import re

here = os.path.dirname(os.path.abspath(__file__))
L, H = 2.5, 0.41
XC, YC, R = 0.2, 0.2, 0.05
FLAG_END, FLAG_T = 0.6, 0.02


def rounded(p):
    return [round(p[0], 6), round(p[1], 6)]


def outline(h):
    """The cylinder's arc (counter-clockwise from the flag's upper edge round to its lower edge) and the flag's
    outline (lower edge, end, upper edge), sharing their two junction points."""
    th0 = math.asin(FLAG_T / 2 / R)
    arc = 2 * math.pi - 2 * th0
    n = max(8, round(arc * R / h))
    cyl = [rounded((XC + R * math.cos(th0 + arc * k / n), YC + R * math.sin(th0 + arc * k / n))) for k in range(n + 1)]
    x0 = cyl[0][0]
    flag = [cyl[-1], [FLAG_END, round(YC - FLAG_T / 2, 6)], [FLAG_END, round(YC + FLAG_T / 2, 6)], cyl[0]]
    assert abs(cyl[0][0] - x0) < 1e-12
    return cyl, flag


def case(h, dt, end_time, tag):
    cyl, flag = outline(h)
    hole = cyl[:-1] + flag[:-1]  # the obstacle's outline, not closed
    body = {
        "name": "water",
        "type": "fluid",
        "density": 1000.0,
        "viscosity": 1.0,
        "spacing": h,
        "particles": "unstructured",
        "regions": [{"type": "polygon", "points": [[0, 0], [L, 0], [L, H], [0, H]], "holes": [hole]}],
        "walls": [
            {"name": "bottom", "points": [[0, 0], [L, 0]]},
            {"name": "top", "points": [[0, H], [L, H]]},
            {"name": "cylinder", "points": cyl},
            {"name": "flag", "points": flag},
        ],
        "wall_friction": "held",
        "domain_detection": "advected",
        "wall_model": "particles",
        "scheme": {"type": "fractional_step"},
        "boundaries": [
            {"type": "inflow", "name": "inlet", "segment": [[0, 0], [0, H]], "velocity": [0.2, 0],
             "profile": "parabolic", "function": {"type": "ramp", "t1": 1.0}},
            {"type": "outflow", "name": "outlet", "segment": [[L, 0], [L, H]]},
        ],
    }
    probes = [
        {"name": "drag_cylinder", "type": "wall_force", "body": "water", "wall": "cylinder", "component": "x"},
        {"name": "lift_cylinder", "type": "wall_force", "body": "water", "wall": "cylinder", "component": "y"},
        {"name": "drag_flag", "type": "wall_force", "body": "water", "wall": "flag", "component": "x"},
        {"name": "lift_flag", "type": "wall_force", "body": "water", "wall": "flag", "component": "y"},
        {"name": "p_front", "type": "pressure", "body": "water", "from": [XC - R, YC], "to": [XC - R, YC]},
        {"name": "discharge", "type": "discharge", "body": "water", "from": [1.5, 0.0], "to": [1.5, H]},
        {"name": "fluid_area", "type": "fluid_area", "body": "water"},
        {"name": "max_speed", "type": "max_speed", "body": "water"},
    ]
    return {
        "name": "turek_hron_cfd1",
        "description": "Turek & Hron (2006) CFD1: channel 2.5 x 0.41 m, a rigid cylinder (r = 0.05 m) with its flag as a rigid "
                       "wall, parabolic inflow of mean 0.2 m/s (Re = 20), drag and lift (%s)" % tag,
        "analysis": {"type": "dynamic", "dt": dt, "end_time": end_time},
        "gravity": [0.0, 0.0],
        "bodies": [body],
        "probes": probes,
        "output": {"every": 100},
    }


NUM = r"-?[0-9.e+-]+"
PAIR = r"\[%s, %s\]" % (NUM, NUM)


def compact(text):
    """json.dumps(indent=2) with each point [x, y] on one line, the lists of points filled into lines of at most
    118 characters and the small objects on one line."""
    text = re.sub(r"\[\s*(%s),\s*(%s)\s*\]" % (NUM, NUM), r"[\1, \2]", text)

    def fill(m):
        indent, items = m.group(1), re.findall(PAIR, m.group(2))
        lines, line = [], ""
        for it in items:
            if line and len(indent) + len(line) + len(it) + 2 > 118:
                lines.append(line + ",")
                line = ""
            line = it if not line else line + ", " + it
        lines.append(line)
        return "[\n" + "\n".join(indent + x for x in lines) + "\n" + indent[:-2] + "]"

    text = re.sub(r"\[\n( *)(%s(?:,\s*%s)*)\s*\]" % (PAIR, PAIR), fill, text)
    return re.sub(r"\{\n\s*([^{}\[\]]*?)\n\s*\}",
                  lambda m: "{" + " ".join(x.strip() for x in m.group(1).split("\n")) + "}"
                  if len(m.group(1)) < 100 else m.group(0), text)


if __name__ == "__main__":
    for name, h, dt in (("case.json", 0.01, 0.01), ("case_coarse.json", 0.02, 0.01), ("case_fine.json", 0.007, 0.007)):
        with open(os.path.join(here, name), "w") as f:
            f.write(compact(json.dumps(case(h, dt, 5.0, "h = %g m, dt = %g s" % (h, dt)), indent=2)) + "\n")
