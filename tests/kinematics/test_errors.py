"""The kinematics' errors (kinematics/errors.py): their families, where they say it happened,
and ``shifted`` for windows of a longer trajectory."""
import pytest

from pollard_pin.errors import InputError, SolveError
from pollard_pin.kinematics import errors as E


def test_families():
    for cls in (E.ClosureError, E.KinematicsError, E.UnreachablePoseError, E.SingularityError,
                E.ClosureSingularError, E.BranchFlipError):
        assert issubclass(cls, SolveError) and not issubclass(cls, InputError), cls
    # bad arguments are an InputError (so a ValueError) that says where as the solve's errors
    # do (sample, time, chain: AtSample), not a KinematicsError: nothing was solved
    assert issubclass(E.KinematicsInputError, InputError)
    assert issubclass(E.KinematicsInputError, ValueError)
    assert not issubclass(E.KinematicsInputError, SolveError | E.KinematicsError)
    assert issubclass(E.KinematicsInputError, E.AtSample) and issubclass(E.KinematicsError,
                                                                          E.AtSample)
    assert set(E.SAMPLE_ERRORS) == {E.KinematicsError, E.KinematicsInputError}
    assert issubclass(E.ClosureSingularError, E.ClosureError)


@pytest.mark.parametrize("where, prefix", [({}, ""), ({"sample": 7}, "sample 7: "),
                                           ({"sample": 7, "time": 0.25},
                                            "sample 7 (t = 0.25 s): ")])
def test_message_says_where(where, prefix):
    e = E.UnreachablePoseError("leg 1 cannot reach", chain="leg 1", amount=0.003, **where)
    assert str(e) == prefix + "leg 1 cannot reach" and e.detail == "leg 1 cannot reach"
    assert (e.chain, e.amount) == ("leg 1", 0.003)


def test_closure_singular_error_carries_both():
    e = E.ClosureSingularError("singular", leg=2, residual=1e-3, sigma=1e-17, sample=3)
    assert (e.leg, e.residual, e.sigma, e.sample) == (2, 1e-3, 1e-17, 3)
    assert str(e) == "sample 3: singular"


def test_shifted_moves_every_sample_number():
    from pollard_pin.kinematics.errors import BranchFlipError

    e = BranchFlipError("assembly branch flip between samples 3 and 4: sin θ1716 changed sign",
                        sample=4, time=0.5, chain="wrist", amount=0.1)
    s = e.shifted(1000)
    assert type(s) is BranchFlipError and (s.sample, s.time, s.chain) == (1004, 0.5, "wrist")
    assert str(s) == ("sample 1004 (t = 0.5 s): assembly branch flip between samples 1003 and "
                      "1004: sin θ1716 changed sign")
    assert e.sample == 4 and e.shifted(0) is e  # the original is left alone


def test_an_input_error_says_where_and_shifts():
    e = E.KinematicsInputError("d_psi is not finite", sample=3, time=0.25, chain="d_psi")
    assert str(e) == "sample 3 (t = 0.25 s): d_psi is not finite" and e.chain == "d_psi"
    s = e.shifted(100)
    assert type(s) is E.KinematicsInputError and s.sample == 103
    assert str(s) == "sample 103 (t = 0.25 s): d_psi is not finite"
