"""A paint job's tables as a parsed job file gives them (tests of painting/job.py and
painting/job_tables.py edit them)."""


def good_panel() -> dict:
    """examples/paint.toml's panel job's tables, a fresh copy to edit."""
    return {"panel": {"center": [0.70, 0.0, 0.16], "normal": [-1.0, 0.0, 0.0],
                      "width": 0.26, "height": 0.12},
            "gun": {"standoff": 0.15, "sigma": 0.010, "flow": 1.5e-7},
            "job": {"thickness": 25e-6}}
