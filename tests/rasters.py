"""A smooth rest-to-rest raster painting path (C²: accelerations continuous), for the
time-optimal tests and the benchmark: horizontal passes at x = 0.55 m over a width × height
area around the home tip, reversing on half-cosine speed turns while z steps up by a quintic
smoothstep; a half-cosine speed ramp from and to rest at the ends. Gun orientation (0, 0, 0)."""
import numpy as np

HOME = (0.55, 0.0, 0.16)


def raster(dt=2e-3, v=0.2, width=0.26, height=0.12, passes=12, turn=0.4, ramp=0.75):
    """(t, poses, rates, accelerations) sampled every ``dt`` [s], exact derivatives."""
    pitch = height / (passes - 1)
    w_turn, w_ramp = np.pi / turn, np.pi / ramp
    # segments: (kind, duration, direction); kinds: up, cruise, turn, down
    segs = [("up", ramp, 1)]
    for k in range(passes):
        d = 1 if k % 2 == 0 else -1
        segs.append(("cruise", width / v, d))
        if k < passes - 1:
            segs.append(("turn", turn, d))
    segs.append(("down", ramp, -1 if passes % 2 == 0 else 1))
    starts = np.cumsum([0.0] + [dur for _, dur, _ in segs])
    t = np.linspace(0.0, starts[-1], int(round(starts[-1] / dt)) + 1)
    y, z = np.zeros((3, len(t))), np.zeros((3, len(t)))  # position, rate, acceleration
    y0, z0 = -width / 2 - v * ramp / 2, -height / 2
    seg = np.clip(np.searchsorted(starts, t, side="right") - 1, 0, len(segs) - 1)
    for i, (kind, _, d) in enumerate(segs):
        m = seg == i
        tau = t[m] - starts[i]
        if kind == "up":
            y[:, m] = [y0 + d * v * (tau / 2 - np.sin(w_ramp * tau) / (2 * w_ramp)),
                       d * v * (1 - np.cos(w_ramp * tau)) / 2,
                       d * v * w_ramp * np.sin(w_ramp * tau) / 2]
        elif kind == "down":
            y[:, m] = [y0 + d * v * (tau / 2 + np.sin(w_ramp * tau) / (2 * w_ramp)),
                       d * v * (1 + np.cos(w_ramp * tau)) / 2,
                       -d * v * w_ramp * np.sin(w_ramp * tau) / 2]
        elif kind == "cruise":
            y[:, m] = [y0 + d * v * tau, d * v + 0 * tau, 0 * tau]
        else:
            x = tau / turn
            y[:, m] = [y0 + d * v * np.sin(w_turn * tau) / w_turn, d * v * np.cos(w_turn * tau),
                       -d * v * w_turn * np.sin(w_turn * tau)]
            z[:, m] = [pitch * (10 * x**3 - 15 * x**4 + 6 * x**5),
                       pitch * (30 * x**2 - 60 * x**3 + 30 * x**4) / turn,
                       pitch * (60 * x - 180 * x**2 + 120 * x**3) / turn**2]
        z[0, m] += z0
        end = starts[i + 1] - starts[i]  # where this segment leaves y and z
        if kind == "up" or kind == "down":
            y0 += d * v * end / 2
        elif kind == "cruise":
            y0 += d * v * end
        else:
            z0 += pitch
    poses, rates, accelerations = (np.zeros((len(t), 6)) for _ in range(3))
    poses[:, 0] = HOME[0]
    for k, (col, home) in enumerate(((y, HOME[1]), (z, HOME[2]))):
        poses[:, 1 + k], rates[:, 1 + k], accelerations[:, 1 + k] = col
        poses[:, 1 + k] += home
    return t, poses, rates, accelerations
