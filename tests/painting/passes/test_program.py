"""A part's program pieces (paint/passes/program.py): a turnaround's quintic meets its end
states with exact derivatives, the gun frame sprays along its axis."""
import numpy as np
import pytest

from pollard_pin.painting.passes.program import Quintic, gun_frame


def test_quintic_meets_its_end_states():
    rng = np.random.default_rng(1)
    start, end = (tuple(rng.normal(size=(3, 6))), tuple(rng.normal(size=(3, 6))))
    q = Quintic("turn", start, end, 0.7)
    for tau, state in ((0.0, start), (0.7, end)):
        got = q.evaluate(np.array([tau]))
        for g, want in zip(got, state):
            assert np.abs(g[0] - want).max() < 1e-12
    # rates and accelerations are the derivatives (central differences, O(h²) ≈ 1e-8)
    tau, h = np.linspace(0.05, 0.65, 7), 1e-5
    p, d, dd = q.evaluate(tau)
    pp, dp, _ = q.evaluate(tau + h)
    pm, dm, _ = q.evaluate(tau - h)
    assert np.abs((pp - pm) / (2 * h) - d).max() < 1e-6
    assert np.abs((dp - dm) / (2 * h) - dd).max() < 1e-5


def test_gun_frame_sprays_along_the_axis():
    a = np.array([[1.0, 0.0, 0.0], [0.9, 0.3, -0.1]])
    a /= np.linalg.norm(a, axis=1, keepdims=True)
    R = gun_frame(a)
    assert np.abs(R[:, :, 0] - a).max() < 1e-15
    assert np.abs(np.einsum("kij,kil->kjl", R, R) - np.eye(3)).max() < 1e-14
    assert np.abs(np.linalg.det(R) - 1).max() < 1e-14


def test_gun_frame_of_a_vertical_axis_refers_to_world_x():
    """A spray axis along ∓z (a table top) with reference x: the frame is the rotation
    [a, c × a, c] with c = x projected off a, by hand; along the reference itself, a
    PlanError line (no division by zero)."""
    from pollard_pin.painting.errors import PlanError

    a = np.array([[0.0, 0.0, -1.0], [0.0, 0.0, 1.0]])
    R = gun_frame(a, (1.0, 0.0, 0.0))
    assert np.abs(R[:, :, 0] - a).max() == 0.0 and np.abs(R[:, :, 2] - [1, 0, 0]).max() == 0.0
    assert np.abs(np.linalg.det(R) - 1.0).max() < 1e-12  # achieved 0
    with pytest.raises(PlanError, match="runs along the gun frame's reference axis"):
        gun_frame(np.array([[1.0, 0.0, 0.0]]), (1.0, 0.0, 0.0))


def test_a_pass_end_state_is_evaluated_once_and_kept():
    # the turnaround search builds the program many times: a pass's end states are those
    # its spline gives there (evaluated afresh), kept read-only, the same arrays every build
    from pollard_pin.painting.passes.program import PassPiece, build_program

    s = np.linspace(0.0, 0.3, 12)
    poses = np.column_stack([0.5 + 0.01 * np.sin(s), s, 0.1 * s ** 2, 0.2 * s, 0.0 * s,
                             0.1 + 0.0 * s])
    a, b = PassPiece(s, poses, 0.2, True, 0), PassPiece(s, poses[::-1], 0.2, False, 1)
    for p in (a, b):
        for end in (False, True):
            fresh = p.evaluate(np.array([p.duration if end else 0.0]))
            got = p.state(end)
            assert all(np.array_equal(x[0], y) for x, y in zip(fresh, got))
            assert p.state(end) is got and not got[0].flags.writeable
    one, two = build_program([a, b], [0.5, 0.7, 0.5]), build_program([a, b], [0.4, 0.9, 0.6])
    t = np.linspace(0.0, one.total, 50)
    again = build_program([PassPiece(s, poses, 0.2, True, 0),
                           PassPiece(s, poses[::-1], 0.2, False, 1)], [0.5, 0.7, 0.5])
    assert all(np.array_equal(x, y) for x, y in zip(one.evaluate(t), again.evaluate(t)))
    assert two.total != one.total


def test_a_program_evaluates_each_piece_at_its_own_times():
    # Program.evaluate groups the times by piece (a slice where they increase, a stable
    # sort's run where not): against each piece evaluated at its times picked by a mask (the
    # brute force), times increasing, shuffled, repeated, on the pieces' joints and outside
    # the program, to the bit
    from pollard_pin.painting.passes.program import PassPiece, build_program

    s = np.linspace(0.0, 0.3, 12)
    poses = np.column_stack([0.5 + 0.01 * np.sin(s), s, 0.1 * s ** 2, 0.2 * s, 0.0 * s,
                             0.1 + 0.0 * s])
    prog = build_program([PassPiece(s, poses, 0.2, True, 0),
                          PassPiece(s, poses[::-1], 0.2, False, 1),
                          PassPiece(s, poses, 0.2, True, 2)], [0.5, 0.7, 0.6, 0.5])
    rng = np.random.default_rng(2)
    t = np.concatenate([[-0.1, 0.0], np.linspace(0.0, prog.total, 301), prog.start,
                        [prog.total, prog.total + 1.0]])
    for times in (np.sort(t), rng.permutation(t), np.repeat(rng.permutation(t)[:40], 3)):
        idx, start = prog.piece_at(times), prog.start
        want = [np.empty((len(times), 6)) for _ in range(3)]
        for i in range(len(prog.pieces)):
            sel = idx == i
            for w, x in zip(want, prog.pieces[i].evaluate(times[sel] - start[i])):
                w[sel] = x
        ends = (times <= 0.0) | (times >= prog.total)
        want[1][ends], want[2][ends] = 0.0, 0.0
        got = prog.evaluate(times)
        assert all(g.tobytes() == w.tobytes() for g, w in zip(got, want))
    assert all(len(a) == 0 for a in prog.evaluate(np.array([])))
