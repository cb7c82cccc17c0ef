"""Writes the case files of turek_hron_cfd2: turek_hron_cfd1's (its make_case.py: the obstacle's outline cut into
segments of about h, the fluid region's hole following the same points) with the inflow's mean speed 1 m/s
(Re = 100) and a time step for its Courant number (peak speed 1.5 m/s: 1.5 dt / h = 0.375); one file per resolution:
case.json (h = 0.01 m, dt = 0.0025 s), case_coarse.json (h = 0.02 m, dt = 0.005 s), each with 4 s of flow.
Usage: /usr/bin/python3 cases/turek_hron_cfd2/make_case.py (rewrites the two)."""
import importlib.util
import json
import os

here = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location("cfd1", os.path.join(here, "..", "turek_hron_cfd1", "make_case.py"))
cfd1 = importlib.util.module_from_spec(spec)
spec.loader.exec_module(cfd1)

U = 1.0  # m/s, the inflow's mean speed (peak 1.5 U)


def case(h, dt, end_time, tag, test="CFD2", u=U, what="drag and lift"):
    """CFD1's case with the inflow's mean speed u (Re = 100 u), named after `test` (turek_hron_cfd3's make_case.py
    writes CFD3 with it)."""
    c = cfd1.case(h, dt, end_time, tag)
    inflow = c["bodies"][0]["boundaries"][0]
    assert inflow["type"] == "inflow"
    inflow["velocity"] = [u, 0]
    c["name"] = "turek_hron_" + test.lower()
    c["description"] = ("Turek & Hron (2006) %s: channel 2.5 x 0.41 m, a rigid cylinder (r = 0.05 m) with its flag "
                        "as a rigid wall, parabolic inflow of mean %g m/s (Re = %g), %s (%s)"
                        % (test, u, 100 * u, what, tag))
    return c


if __name__ == "__main__":
    for name, h, dt in (("case.json", 0.01, 0.0025), ("case_coarse.json", 0.02, 0.005)):
        with open(os.path.join(here, name), "w") as f:
            f.write(cfd1.compact(json.dumps(case(h, dt, 4.0, "h = %g m, dt = %g s" % (h, dt)), indent=2)) + "\n")
