"""Numbers a plot script hands to scripts/claims.py: record(name, value) adds them to the JSON file
named by the environment variable LAGFSI_METRICS, which claims.py sets when it runs the script; without it,
record() does nothing. The script prints its numbers as before; these are the same numbers, unrounded."""
import json
import os


def record(name, value):
    path = os.environ.get("LAGFSI_METRICS")
    if not path:
        return
    data = {}
    if os.path.exists(path):
        with open(path) as f:
            data = json.load(f)
    data[name] = float(value)
    with open(path, "w") as f:
        json.dump(data, f, indent=1)
