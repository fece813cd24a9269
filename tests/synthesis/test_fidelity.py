"""How the study's search plans (synthesis/fidelity.py, docs/model.md §31.5): the options it
hands the planner, never finer than the full level's; its fields checked once."""
import pytest

import pollard_pin as pp
from pollard_pin.errors import InputError
from pollard_pin.painting.policy import PlannerPolicy
from pollard_pin.synthesis import SearchFidelity


def test_the_search_options_are_coarser_never_finer():
    f = SearchFidelity()
    assert (f.film, f.clearance_stride, f.check_refine, f.name_speeds) == (0.5, 4, 1, False)
    exact = pp.PaintOptions(compliance=False)
    o = f.options(exact, 0.01)
    assert o.resolution == pytest.approx(0.005) and o.compliance is False
    assert (o.policy.clearance_stride, o.policy.check_refine) == (4, 1)
    # a refused line speed: its binding constraint read, the interval that paints not sought
    assert exact.policy.name_speeds is True and o.policy.name_speeds is False
    assert SearchFidelity(name_speeds=True).options(exact, 0.01).policy.name_speeds is True
    assert o.policy.utilisation == exact.policy.utilisation  # the planner's own knobs kept
    # a full level coarser than the search's: the search takes it
    coarse = pp.PaintOptions(resolution=0.008, policy=PlannerPolicy(clearance_stride=8,
                                                                     check_refine=1))
    o = SearchFidelity(film=1 / 3, clearance_stride=2, check_refine=4).options(coarse, 0.01)
    assert (o.resolution, o.policy.clearance_stride, o.policy.check_refine) == (0.008, 8, 1)


@pytest.mark.parametrize("field, value, rule", [
    ("film", 0.0, "in (0, 1]"), ("film", 1.5, "in (0, 1]"), ("film", True, "in (0, 1]"),
    ("film", "0.5", "in (0, 1]"), ("clearance_stride", 0, ">= 1"),
    ("clearance_stride", 2.0, ">= 1"), ("check_refine", False, ">= 1"),
    ("name_speeds", 0, "true or false")])
def test_a_bad_field_is_one_line(field, value, rule):
    with pytest.raises(InputError) as exc:
        SearchFidelity(**{field: value})
    msg = str(exc.value)
    assert f"SearchFidelity.{field}" in msg and rule in msg and "\n" not in msg, msg


def test_the_study_options_take_a_fidelity_or_none():
    from pollard_pin.synthesis import DesignOptions

    assert DesignOptions().search == SearchFidelity() and DesignOptions().stage == "search"
    assert DesignOptions(search=None).stage == "full"
    assert DesignOptions(screen_only=True).stage == "screen"
    with pytest.raises(InputError, match="DesignOptions.search: expected a SearchFidelity"):
        DesignOptions(search={"film": 0.5})
