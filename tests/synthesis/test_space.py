"""The design space (synthesis/space.py, docs/model.md §31.2): the example, the variables the
optimiser samples, the fingerprint, and each refusal in one line."""
import copy

import pytest

from pollard_pin.synthesis.catalogue import load_catalogue
from pollard_pin.synthesis.space import SpaceError, load_space, space_from_dict


@pytest.fixture(scope="module")
def cat():
    return load_catalogue("examples/design/motors.toml")


BASE = {"robots": [1, 3], "bounds": {"leg1.x87": [0.3, 0.4]},
        "scale": [{"name": "arms", "keys": ["chain0.x32", "leg1.x43", "leg2.x43"],
                   "range": [1.0, 1.5]}],
        "motors": {"base": ["theta21", "theta21_1", "theta21_2"]}}


def space(cat, **change):
    d = copy.deepcopy(BASE)
    d.update(change)
    return space_from_dict(d, "S.toml", catalogue=cat)


def test_example_space():
    sp = load_space("examples/design/space.toml")
    names = [v.name for v in sp.variables()]
    assert names == ["limits.theta21.upper", "scale.arms", "scale.links", "motor.base",
                     "ratio.base", "motor.wrist", "ratio.wrist", "place.back", "robots"]
    assert sp.robots == (1, 3) and sp.back == (0.0, 0.4)
    assert sp.fingerprint() == load_space("examples/design/space.toml").fingerprint()


def test_variables_and_values(cat):
    sp = space(cat)
    v = {x.name: x for x in sp.variables()}
    assert (v["leg1.x87"].low, v["leg1.x87"].high, v["leg1.x87"].kind) == (0.3, 0.4, "float")
    assert v["motor.base"].kind == "categorical" and v["motor.base"].choices == cat.names
    assert v["ratio.base"].choices == (50.0, 100.0, 160.0)
    # actuators not grouped get one choice each
    assert "motor.theta1615" in v and "motor.theta1817" in v
    assert (v["robots"].low, v["robots"].high, v["robots"].kind) == (1, 3, "int")
    o = sp.overrides({"leg1.x87": 0.31, "scale.arms": 1.2})
    assert o == {"leg1.x87": 0.31, "chain0.x32": pytest.approx(0.396),
                 "leg1.x43": pytest.approx(0.396), "leg2.x43": pytest.approx(0.396)}
    m = sp.motors({"motor.base": 1, "ratio.base": 2})
    assert m["theta21_2"][0].name == "S40" and m["theta21_2"][1] == 160.0
    assert m["theta1615"][0].name == "S20"  # index 0 by default
    # a ratio the motor does not offer: the nearest it does (W5: 50, 100)
    assert sp.motors({"motor.base": 4, "ratio.base": 2})["theta21"][1] == 100.0
    with pytest.raises(SpaceError, match="motor.base"):
        sp.motors({"motor.base": 6})
    with pytest.raises(SpaceError, match="robots"):
        sp.robot_count({"robots": 4})


def test_fingerprint_changes_with_the_space(cat):
    assert space(cat).fingerprint() == space(cat).fingerprint()
    assert space(cat).fingerprint() != space(cat, robots=2).fingerprint()
    assert space(cat).fingerprint() != space(cat, bounds={"leg1.x87": [0.3, 0.41]}).fingerprint()


@pytest.mark.parametrize("change, match", [
    ({"bounds": {"leg1.x78": [0.3, 0.4]}}, "names no parameter.*leg1.x87"),
    ({"bounds": {"leg1.x87": [-0.1, 0.4]}}, "below zero"),
    ({"bounds": {"leg1.x87": [0.4, 0.4]}}, "empty bound"),
    ({"bounds": {"leg1.x87": [0.4]}}, r"\[low, high\]"),
    ({"bounds": {"bodies.gun.mass": [0.1, 0.2]}}, "mass model"),
    ({"bounds": {"home.tip": [0.1, 0.2]}}, "a list"),
    ({"bounds": {"limits.theta21.effort": [1, 2]}}, "motor sets it"),
    ({"robots": [0, 3]}, "robots"),
    ({"robots": 17}, "robots"),
    ({"scale": [{"keys": ["chain0.x32"], "range": [0.0, 1.0]}]}, "below zero"),
    ({"scale": [{"keys": ["chain0.x32"], "range": [1.2, 1.0]}]}, "empty bound"),
    ({"motors": {"a": ["theta43"]}}, "not an actuator"),
    ({"place": {"back": [-0.1, 0.2]}}, "place.back"),
    ({"robot": 2}, "unknown key.*robots"),
    # the legs' links far too short: the home pose out of reach at every corner
    ({"bounds": {"leg1.x87": [0.05, 0.1], "leg2.x87": [0.05, 0.1]}}, "home pose is unreachable"),
])
def test_refusals_are_one_line(cat, change, match):
    with pytest.raises(SpaceError, match=match) as e:
        space(cat, **change)
    assert "\n" not in str(e.value) and len(str(e.value)) <= 250


@pytest.mark.parametrize("change, says", [
    ({"bounds": {"chain0.x65": [0.3, 400]}},
     "S.toml [bounds]: 'chain0.x65' = [0.3, 400]: its high end: parameter 'chain0.x65' = 400.0: "
     "must be at most 10 m (lengths are in metres, not mm)"),
    ({"bounds": {"limits.theta21.upper": [-35.0, 1e300]}},
     "S.toml [bounds]: 'limits.theta21.upper' = [-35, 1e+300]: its high end: parameter "
     "'limits.theta21.upper' = 1e+300: must be within ±720 deg (two turns)"),
    ({"scale": [{"name": "a", "keys": ["leg1.x43", "chain0.x32"], "range": [1, 1e300]}]},
     "S.toml [[scale]] 1: range = [1, 1e+300]: its high end: parameter 'chain0.x32' = "),
])
def test_both_ends_of_a_bound_keep_the_parameters_rule(cat, change, says):
    """Each end of a bound, and each key a scale's end makes, meets the rule the parameter
    itself has (model/params.py): only the low end was checked, and trials past an absurd high
    end were all infeasible."""
    with pytest.raises(SpaceError) as e:
        space(cat, **change)
    msg = str(e.value)
    assert msg.startswith(says), msg
    assert "\n" not in msg and len(msg) <= 250, msg
    # a sane end is no refusal: the reference's own values scaled within the rules
    space(cat, scale=[{"name": "a", "keys": ["chain0.x32"], "range": [0.9, 1.1]}])


def test_catalogue_is_read_beside_the_space(tmp_path):
    (tmp_path / "S.toml").write_text('catalogue = "none.toml"\nrobots = 1\n')
    with pytest.raises(Exception, match="none.toml"):
        load_space(tmp_path / "S.toml")
    (tmp_path / "S.toml").write_text('robots = 1\n')
    with pytest.raises(SpaceError, match="catalogue"):
        load_space(tmp_path / "S.toml")


@pytest.mark.parametrize("value, says", [
    (["base.toml"], "S.toml: params = ['base.toml']: expected a file path (str or "
                    "pathlib.Path), got list"),
    (3, "S.toml: params = 3: expected a file path"),
    ("", "S.toml: params = '': an empty path"),
])
def test_a_params_entry_that_names_no_file_is_one_line(cat, tmp_path, value, says):
    # the old code read str(value): "parameter file \"['base.toml']\" does not exist", and
    # an empty name read the space's folder
    with pytest.raises(SpaceError) as e:
        space_from_dict({**BASE, "params": value}, "S.toml", tmp_path, catalogue=cat)
    assert str(e.value).startswith(says) and "\n" not in str(e.value), str(e.value)


def test_an_empty_catalogue_name_is_one_line(tmp_path):
    (tmp_path / "S.toml").write_text('catalogue = ""\nrobots = 1\n')
    with pytest.raises(SpaceError, match="^S.toml: catalogue = '': an empty path$"):
        load_space(tmp_path / "S.toml")


def test_reference_design_from_a_partial_file(cat, tmp_path):
    (tmp_path / "base.toml").write_text("[chain0]\nx32 = 0.35\n", encoding="utf-8")
    sp = space_from_dict({**BASE, "params": "base.toml"}, "S.toml", tmp_path, catalogue=cat)
    assert sp.reference["chain0"]["x32"] == 0.35
    assert sp.overrides({"scale.arms": 2.0})["chain0.x32"] == pytest.approx(0.70)
    with pytest.raises(Exception, match="unknown key"):
        (tmp_path / "bad.toml").write_text("[chain0]\nx33 = 0.35\n", encoding="utf-8")
        space_from_dict({**BASE, "params": "bad.toml"}, "S.toml", tmp_path, catalogue=cat)


def test_a_bound_end_is_refused_by_the_rule_the_error_says_is_its_keys(cat):
    """_check_ends asks the ParameterError whose rule it is (its ``key``), not its words: a
    joint's range over one turn is the lower key's rule (model/params.py names it first)."""
    with pytest.raises(SpaceError) as e:
        space(cat, bounds={"limits.theta21.lower": [-400.0, -106.0]})
    assert str(e.value).startswith(
        "S.toml [bounds]: 'limits.theta21.lower' = [-400, -106]: its low end: parameter "
        "'limits.theta21.lower' = -400, 'limits.theta21.upper' = -35: the range 365 deg "
        "exceeds one turn (360)"), str(e.value)
    space(cat, bounds={"limits.theta21.lower": [-300.0, -106.0]})  # within one turn: taken


@pytest.mark.parametrize("change, says", [
    # the upper limit's bound alone: at its high end the range is 505 deg (lower −105)
    ({"bounds": {"limits.theta21.upper": [-35.0, 400.0]}},
     "S.toml: [bounds] 'limits.theta21.upper': the range can reach 505 deg (-105 to 400): "
     "one turn (360) at most, 145 over"),
    # the lower limit's bound alone crosses the reference's upper (−35 deg)
    ({"bounds": {"limits.theta21.lower": [-100.0, 10.0]}},
     "S.toml: [bounds] 'limits.theta21.lower': the upper limit can be -35 deg with the lower "
     "10 deg: upper must exceed lower (off by 45 deg)"),
    # both bounded, each sane at the other's middle, crossing at a corner of the box
    ({"bounds": {"limits.theta21.lower": [-100.0, -20.0],
                 "limits.theta21.upper": [-30.0, 0.0]}},
     "S.toml: [bounds] 'limits.theta21.lower' and [bounds] 'limits.theta21.upper': the upper "
     "limit can be -30 deg with the lower -20 deg: upper must exceed lower (off by 10 deg)"),
])
def test_joint_limits_hold_over_the_whole_box(cat, change, says):
    """A joint's limits varied must keep upper > lower and one turn at most at every corner
    of the box, not only at each end with the others at their middles (_check_ends lets a
    rule that names the other key pass: the design then fails at its first such trial)."""
    with pytest.raises(SpaceError) as e:
        space(cat, **change)
    assert str(e.value) == says
    space(cat, bounds={"limits.theta21.upper": [-35.0, 200.0]})  # 305 deg at most: taken
    # one factor on both limits moves them together: never crossing, 210 deg at most
    space(cat, scale=[{"keys": ["limits.theta21.upper", "limits.theta21.lower"],
                       "range": [1.0, 3.0]}])


@pytest.mark.parametrize("change, says", [
    ({"bounds": {"leg1.x87": [0.3, 10**400]}},
     "S.toml [bounds]: 'leg1.x87' = [0.3, 1e+400 (a 401-digit integer)]: bounds must be "
     "finite"),
    ({"place": {"back": 10**400}},
     "S.toml: place.back = 1e+400 (a 401-digit integer): must be a finite distance"),
    ({"place": {"back": float("nan")}}, "S.toml: place.back = nan: must be a finite distance"),
    ({"bounds": {"leg1.x87": [0.3, 0.4]},
      "scale": [{"keys": ["leg1.x87"], "range": [1.0, 1.5]}]},
     "S.toml: 'leg1.x87' is varied in [bounds] and in [[scale]] 1; give each key one entry"),
    ({"scale": [{"keys": ["chain0.x32", "chain0.x32"], "range": [1.0, 1.5]}]},
     "S.toml: 'chain0.x32' is varied twice in [[scale]] 1; give each key one entry"),
    ({"bounds": {"leg1": {"x87": [0.3, 0.4]}}},  # TOML's bare leg1.x87 = [...]
     'S.toml [bounds]: \'leg1\' holds a table; quote a dotted key: "leg1.KEY" = [low, high]'),
])
def test_absurd_or_doubled_bounds_are_one_line(cat, change, says):
    """An integer beyond a float was an OverflowError; a key in [bounds] and a [[scale]] (or
    twice in one) was taken, its value a product nobody wrote; a bare dotted key was said to
    name no parameter."""
    with pytest.raises(SpaceError) as e:
        space(cat, **change)
    assert str(e.value) == says
