"""Writes the case files of turek_hron_cfd3: turek_hron_cfd2's (its make_case.py, from turek_hron_cfd1's: the
obstacle's outline cut into segments of about h, the fluid region's hole following the same points) with the
inflow's mean speed 2 m/s (Re = 200: vortex shedding) and a time step for its Courant number (peak speed 3 m/s:
3 dt / h = 0.375); one file per resolution: case.json (h = 0.01 m, dt = 0.00125 s), case_coarse.json (h = 0.02 m,
dt = 0.0025 s), each with 6 s of flow (the shedding settles by about 3 s).
Usage: /usr/bin/python3 cases/turek_hron_cfd3/make_case.py (rewrites the two)."""
import importlib.util
import json
import os

here = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location("cfd2", os.path.join(here, "..", "turek_hron_cfd2", "make_case.py"))
cfd2 = importlib.util.module_from_spec(spec)
spec.loader.exec_module(cfd2)


def case(h, dt, end_time, tag):
    return cfd2.case(h, dt, end_time, tag, test="CFD3", u=2.0, what="periodic drag and lift")


if __name__ == "__main__":
    for name, h, dt in (("case.json", 0.01, 0.00125), ("case_coarse.json", 0.02, 0.0025)):
        with open(os.path.join(here, name), "w") as f:
            f.write(cfd2.cfd1.compact(json.dumps(case(h, dt, 6.0, "h = %g m, dt = %g s" % (h, dt)), indent=2)) + "\n")
