"""The sweep grid shared by tests/sweep/ and tests/cli/test_sweep.py: four grid variants and
three explicit ones, two of them infeasible."""

SAMPLES = 201  # the fewest the thesis curve needs without tripping the branch-jump check

GRID = f"""
trajectory = "thesis"
duration = 20.0
samples = {SAMPLES}
[grid]
"chain0.x32" = [0.32, 0.34]
bodies.gun.mass = [0.035, 0.05]    # unquoted dotted key: a nested TOML table, flattened
[[variant]]
name = "short leg 1"               # home reachable, painting curve not: infeasible mid-way
"leg1.x87" = 0.31
[[variant]]
name = "no home"                   # home pose unreachable: invalid parameter set
"leg1.x87" = 0.2
[[variant]]
name = "gun cog"
"bodies.gun.com[0]" = 0.045
"""
