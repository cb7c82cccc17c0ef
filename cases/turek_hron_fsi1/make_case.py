"""Writes the case files of turek_hron_fsi1: the fluid's side is turek_hron_cfd1's (its make_case.py: the obstacle's
outline cut into segments of about h, the fluid region's hole following the same points), with the flag an
elastic solid coupled to the fluid instead of a rigid wall; one file per resolution: case.json (h = 0.01 m),
case_coarse.json (h = 0.02 m), case_fine.json (h = 0.007 m), each with dt = min(h, 0.01) s and 24 s of flow (the flag
settles after about 3.5 s, then swings slowly about its mean: the means take the last 16 s); and case_shell.json,
case.json with the flag as shell elements (shell_case).
Usage: /usr/bin/python3 cases/turek_hron_fsi1/make_case.py (rewrites the four)."""
import importlib.util
import json
import os

here = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location("cfd1", os.path.join(here, "..", "turek_hron_cfd1", "make_case.py"))
cfd1 = importlib.util.module_from_spec(spec)
spec.loader.exec_module(cfd1)

XC, YC, R = cfd1.XC, cfd1.YC, cfd1.R
FLAG_END, FLAG_T = cfd1.FLAG_END, cfd1.FLAG_T
TIP = [FLAG_END, YC]  # point A


def case(h, dt, end_time, tag):
    c = cfd1.case(h, dt, end_time, tag)
    cyl, flag = cfd1.outline(h)
    water = c["bodies"][0]
    # The flag is no longer a wall of the fluid: the coupling's ghost particles carry its three wet faces.
    water["walls"] = [w for w in water["walls"] if w["name"] != "flag"]
    solid = {
        "name": "flag",
        "type": "solid",
        "material": {"type": "svk", "young": 1.4e6, "poisson": 0.4, "density": 1000.0, "hypothesis": "plane_strain"},
        "geometry": {"type": "circle_cut", "points": [[XC, YC - FLAG_T / 2], [FLAG_END, YC - FLAG_T / 2],
                                                      [FLAG_END, YC + FLAG_T / 2], [XC, YC + FLAG_T / 2]],
                     "centre": [XC, YC], "radius": R},
        "mesh": {"type": "unstructured", "size": h, "order": 3},
        "boundary_conditions": [
            {"type": "fixed", "select": {"type": "circle", "centre": [XC, YC], "radius": R, "tolerance": 2e-4}}],
    }
    coupling = {
        "type": "dirichlet_neumann",
        "name": "fsi",
        "fluid": "water",
        "structure": "flag",
        # the lower face, the end and the upper face; not the arc the flag is clamped on (inside the cylinder)
        "interface": {"type": "polyline", "points": flag, "tolerance": 1e-5},
        "ghost_spacing": h,
        "acceleration": {"type": "iqn_imvj"},
        "tolerance": 1e-3,
        "reference_floor": 1e-7,
    }
    c["name"] = "turek_hron_fsi1"
    c["description"] = ("Turek & Hron (2006) FSI1: channel 2.5 x 0.41 m, a rigid cylinder (r = 0.05 m) with an elastic "
                        "flag 0.35 x 0.02 m (SVK, rho = 1000, mu = 0.5 MPa, nu = 0.4, plane strain), parabolic inflow "
                        "of mean 0.2 m/s (Re = 20): drag, lift, the tip's displacement (%s)" % tag)
    c["bodies"] = [water, solid]
    c["couplings"] = [coupling]
    probes = [p for p in c["probes"] if p["name"] not in ("drag_flag", "lift_flag")]
    probes[2:2] = [
        {"name": "drag_flag", "type": "interface_force", "body": "fsi", "component": "x"},
        {"name": "lift_flag", "type": "interface_force", "body": "fsi", "component": "y"},
        {"name": "tip_ux", "type": "displacement", "body": "flag", "at": TIP, "component": "x"},
        {"name": "tip_uy", "type": "displacement", "body": "flag", "at": TIP, "component": "y"},
        {"name": "fsi_iterations", "type": "iterations", "body": "fsi"},
    ]
    c["probes"] = probes
    return c


def shell_case(h, dt, end_time, tag, elements=10):
    """FSI1 with the flag as positional shell elements (to_shell)."""
    return named_shell(to_shell(case(h, dt, end_time, tag), elements), "FSI1", elements,
                       "rho = 1000, mu = 0.5 MPa, nu = 0.4", "0.2 m/s (Re = 20)", "drag, lift, the tip's displacement",
                       tag)


def named_shell(c, test, elements, flag_text, flow_text, what, tag):
    """The name and description of a shell variant (to_shell) of the Turek-Hron test `test`."""
    c["name"] = "turek_hron_%s_shell" % test.lower()
    c["description"] = ("Turek & Hron (2006) %s with the flag as shell elements: channel 2.5 x 0.41 m, a rigid "
                        "cylinder (r = 0.05 m) with an elastic flag 0.35 x 0.02 m as %d cubic positional shell "
                        "elements along its centre line, clamped at the cylinder (SVK in the shell's frame, %s, "
                        "plane strain), parabolic inflow of mean %s: %s (%s)"
                        % (test, elements, flag_text, flow_text, what, tag))
    return c


def to_shell(c, elements=10):
    """A Turek-Hron FSI case `c` with its flag as positional shell elements (cases/*_shell): its mid-line y = 0.2 m
    from the root section, whose corners are the flag's on the cylinder (x = 0.2497 m), to the tip (0.6, 0.2),
    thickness 0.02 m, `elements` cubic elements, clamped at the root (position and section held, as the T10 flag's
    arc inside the cylinder). The shell's faces (eta = +-1/2) are the triangles' flag's faces, so that the fluid and
    the interface (the same polyline: lower face, end, upper face) are the main case's."""
    water, solid = c["bodies"]
    root = c["couplings"][0]["interface"]["points"][0][0]
    assert abs(root - c["couplings"][0]["interface"]["points"][-1][0]) < 1e-12
    shell = {
        "name": "flag",
        "type": "shell",
        "material": solid["material"],
        "thickness": FLAG_T,
        "geometry": {"type": "line", "from": [root, YC], "to": TIP},
        "mesh": {"elements": elements, "order": 3},
        "boundary_conditions": [{"type": "fixed", "select": {"type": "point", "at": [root, YC]}}],
    }
    c["bodies"] = [water, shell]
    return c


def variant(test, reynolds, mean_speed, material, flag_text, h, dt, end_time, tag):
    """FSI1's case with another mean inflow speed (m/s) and the flag's material keys changed (`material`): the
    periodic tests FSI2 and FSI3; `flag_text` describes the flag's material."""
    c = case(h, dt, end_time, tag)
    water, flag = c["bodies"]
    inflow = water["boundaries"][0]
    assert inflow["type"] == "inflow" and flag["name"] == "flag"
    inflow["velocity"] = [mean_speed, 0]
    flag["material"].update(material)
    c["name"] = "turek_hron_" + test.lower()
    c["description"] = ("Turek & Hron (2006) %s: channel 2.5 x 0.41 m, a rigid cylinder (r = 0.05 m) with an elastic "
                        "flag 0.35 x 0.02 m (%s, plane strain), parabolic inflow of mean %g m/s (Re = %d): the flag's "
                        "periodic oscillation, drag, lift, the tip's displacement (%s)"
                        % (test, flag_text, mean_speed, reynolds, tag))
    return c


if __name__ == "__main__":
    for name, h, dt in (("case.json", 0.01, 0.01), ("case_coarse.json", 0.02, 0.01), ("case_fine.json", 0.007, 0.007)):
        with open(os.path.join(here, name), "w") as f:
            f.write(cfd1.compact(json.dumps(case(h, dt, 24.0, "h = %g m, dt = %g s" % (h, dt)), indent=2)) + "\n")
    with open(os.path.join(here, "case_shell.json"), "w") as f:
        f.write(cfd1.compact(json.dumps(shell_case(0.01, 0.01, 24.0, "h = 0.01 m, dt = 0.01 s"), indent=2)) + "\n")
