"""Writes the case file of turek_hron_fsi2: turek_hron_fsi1's (its make_case.py: turek_hron_cfd1's channel with the
flag an elastic solid coupled to the fluid) with the inflow's mean speed 1 m/s (Re = 100), the flag's density
10000 kg/m^3 and a time step for the Courant number (peak speed 1.5 m/s: 1.5 dt / h = 0.375): case.json (h = 0.01 m,
dt = 0.0025 s, 12 s of flow: the flag's oscillation grows from the remeshing's noise and becomes periodic), and
case_shell.json, the same with the flag as shell elements (shell_case).
Usage: /usr/bin/python3 cases/turek_hron_fsi2/make_case.py (rewrites it)."""
import importlib.util
import json
import os

here = os.path.dirname(os.path.abspath(__file__))


def load(name):
    spec = importlib.util.spec_from_file_location(name, os.path.join(here, "..", "turek_hron_" + name, "make_case.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


cfd1, fsi1 = load("cfd1"), load("fsi1")
U = 1.0  # m/s, the inflow's mean speed (peak 1.5 U)
RHO_S = 10000.0  # kg/m^3, the flag's density (ten times the fluid's)


def case(h, dt, end_time, tag):
    return fsi1.variant("FSI2", 100, U, {"density": RHO_S}, "SVK, rho = 10000, mu = 0.5 MPa, nu = 0.4", h, dt,
                        end_time, tag)


def shell_case(h, dt, end_time, tag, elements=10):
    """FSI2 with the flag as 10 cubic positional shell elements along its centre line (fsi1.to_shell)."""
    return fsi1.named_shell(fsi1.to_shell(case(h, dt, end_time, tag), elements), "FSI2", elements,
                            "rho = 10000, mu = 0.5 MPa, nu = 0.4", "1 m/s (Re = 100)",
                            "the flag's periodic oscillation, drag, lift, the tip's displacement", tag)


if __name__ == "__main__":
    with open(os.path.join(here, "case.json"), "w") as f:
        f.write(cfd1.compact(json.dumps(case(0.01, 0.0025, 12.0, "h = 0.01 m, dt = 0.0025 s"), indent=2)) + "\n")
    with open(os.path.join(here, "case_shell.json"), "w") as f:
        f.write(cfd1.compact(json.dumps(shell_case(0.01, 0.0025, 12.0, "h = 0.01 m, dt = 0.0025 s"), indent=2)) + "\n")
