"""Writes the case file of turek_hron_fsi3: turek_hron_fsi1's (its make_case.py: turek_hron_cfd1's channel with the
flag an elastic solid coupled to the fluid) with the inflow's mean speed 2 m/s (Re = 200), the flag's shear modulus
2.0 MPa (E = 5.6 MPa) and a time step for the Courant number (peak speed 3 m/s: 3 dt / h = 0.3): case.json
(h = 0.01 m, dt = 0.001 s, 8 s of flow: the flag's oscillation grows from the remeshing's noise; at this h it stays
irregular, see README.md), and case_shell.json, the same with the flag as shell elements (shell_case).
Usage: /usr/bin/python3 cases/turek_hron_fsi3/make_case.py (rewrites it)."""
import importlib.util
import json
import os

here = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location("fsi2", os.path.join(here, "..", "turek_hron_fsi2", "make_case.py"))
fsi2 = importlib.util.module_from_spec(spec)
spec.loader.exec_module(fsi2)
cfd1, fsi1 = fsi2.cfd1, fsi2.fsi1  # turek_hron_fsi2's make_case.py loads both

U = 2.0  # m/s, the inflow's mean speed (peak 1.5 U)
MU_S = 2.0e6  # Pa, the flag's shear modulus (four times FSI1's and FSI2's)
NU_S = 0.4


def case(h, dt, end_time, tag):
    c = fsi1.variant("FSI3", 200, U, {"young": 2 * MU_S * (1 + NU_S)}, "SVK, rho = 1000, mu = 2 MPa, nu = 0.4", h, dt,
                     end_time, tag)
    material = c["bodies"][1]["material"]
    assert material["poisson"] == NU_S and material["density"] == 1000.0  # FSI1's, as FSI3 has them
    return c


def shell_case(h, dt, end_time, tag, elements=10):
    """FSI3 with the flag as 10 cubic positional shell elements along its centre line (fsi1.to_shell)."""
    return fsi1.named_shell(fsi1.to_shell(case(h, dt, end_time, tag), elements), "FSI3", elements,
                            "rho = 1000, mu = 2 MPa, nu = 0.4", "2 m/s (Re = 200)",
                            "the flag's oscillation, drag, lift, the tip's displacement", tag)


if __name__ == "__main__":
    with open(os.path.join(here, "case.json"), "w") as f:
        f.write(cfd1.compact(json.dumps(case(0.01, 0.001, 8.0, "h = 0.01 m, dt = 0.001 s"), indent=2)) + "\n")
    with open(os.path.join(here, "case_shell.json"), "w") as f:
        f.write(cfd1.compact(json.dumps(shell_case(0.01, 0.001, 8.0, "h = 0.01 m, dt = 0.001 s"), indent=2)) + "\n")
