"""One plan result type (paint/plan/result.py): the panel's, the part's and the line's plans
share it, with the world path, its trigger and each motor's use read the same way."""
import dataclasses

from pollard_pin.painting.plan.result import PlanResult


def test_every_plan_is_a_plan_result(plan, line_plan, line_part_plan, act):
    for p in (plan, line_plan, line_part_plan, line_part_plan.in_part_frame()):
        assert isinstance(p, PlanResult) and dataclasses.is_dataclass(p)
        assert len(p.spray) == len(p.trajectory.t)
        use = p.motor_use(act.names)
        assert list(use) == list(act.names)
        for i, name in enumerate(act.names):  # each motor's column of the ratios
            assert use[name] == {k: float(v[i]) for k, v in p.ratios.items()}
    assert (plan.spray == 1).all()  # a still panel is sprayed throughout
    on = line_plan.spray > 0
    assert on.any() and not on.all()  # on a line the gun waits and returns closed
