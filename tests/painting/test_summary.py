"""The lines pollard-pin paint prints that several kinds share (painting/summary.py): one
motor-use order for every kind of job, the compliance line in its units (a cell's naming
the worst robot), the clearance line, the line speeds that paint (when stated), and the closing
lines only where the report has them."""
from pollard_pin.painting.summary import (
    clearance_line,
    closing_lines,
    compliance_line,
    motor_use_line,
    speeds_lines,
    strokes_line,
)


def test_one_motor_use_order():
    rep = {"motors": {"a": {"peak_torque": 0.5, "rms_torque": 0.25, "speed": 0.125}}}
    assert motor_use_line(rep, ["a"]) == "motor peak torque/RMS torque/speed use [%]: a 50/25/12"


def test_summary_line_states_the_entry():
    """The summary line of ``pollard-pin paint`` carries the entry's figures in its units."""
    line = compliance_line({"recoil_n": 0.5, "stiffness": True, "standoff_error_m": 1.92e-4,
                            "lateral_error_m": 2.16e-4, "tilt_rad": 5.58e-4,
                            "film_error": 3.3e-3})
    assert line == ("compliance (weight, recoil 0.5 N): standoff error 192 µm, lateral 216 µm, "
                    "tilt 0.558 mrad; film changes by at most 0.33 % of the target")


def test_summary_line_names_the_worst_robot():
    line = compliance_line({"recoil_n": 5.0, "stiffness": True, "standoff_error_m": 4.32e-4,
                            "standoff_error_robot": "low", "lateral_error_m": 5.56e-4,
                            "tilt_rad": 1.43e-3, "film_error": 1.66e-2})
    assert line == ("compliance (weight, recoil 5 N): standoff error 432 µm (robot 'low'), "
                    "lateral 556 µm, tilt 1.43 mrad; film changes by at most 1.7 % of the "
                    "target")


def test_summary_line_says_the_points_beside_a_shadows_edge_apart():
    """The points beside a shadow's edge (docs/model.md §27.7) after the rest of the film;
    none, nothing said."""
    entry = {"recoil_n": 0.0, "stiffness": True, "standoff_error_m": 3.18e-5,
             "lateral_error_m": 1.55e-4, "tilt_rad": 3.12e-4, "film_error": 1.53e-3,
             "shadow_edges": {"points": 511, "film_error": 3.99e-3}}
    assert compliance_line(entry).endswith(
        "film changes by at most 0.15 % of the target; 511 points beside a shadow's edge "
        "(its move there counts) by at most 0.4 %")
    assert compliance_line({**entry, "shadow_edges": {"points": 0}}).endswith(
        "0.15 % of the target")


CLEARANCE = {"min_clearance_m": 0.1456, "clearance": {"between_samples_m": 0.0044,
                                                       "required_m": 0.01}}


def test_the_clearance_line():
    assert clearance_line(CLEARANCE) == ("gun body 145.6 mm from the part at its closest "
                                         "(± 4.4 mm between samples; clearance 10 mm)")


def test_closing_lines_only_where_the_report_has_them():
    """No clearance and no compliance: nothing; a note of why no compliance: that line."""
    assert closing_lines({}) == []
    off = {"compliance": {"stiffness": False, "note": "not computed"}}
    assert closing_lines(off) == ["compliance not computed"]
    assert closing_lines({**CLEARANCE, **off}) == [clearance_line(CLEARANCE),
                                                   "compliance not computed"]


def test_a_film_that_misses_its_acceptance_is_said_after_the_rest():
    """A film check that meets its acceptance adds nothing (the examples print what they
    did); one that misses closes the summary with a warning line stating its figures."""
    from pollard_pin.painting.summary import film_miss_line

    check = {"outside_5pct": 0.5, "outside_10pct": 0.384, "min_relative": 1e-5,
             "max_relative": 1.13, "acceptance": {"band": 0.1, "min_share": 0.99},
             "meets": False}
    line = film_miss_line(check)
    assert line == ("warning: the film misses its acceptance: 61.60 % of the area within "
                    "±10 % of the target (needs 99 %), film 1e-05–1.13 × the target")
    assert closing_lines({**CLEARANCE, "film_check": check}) == [clearance_line(CLEARANCE),
                                                                   line]
    assert closing_lines({**CLEARANCE, "film_check": {**check, "meets": True}}) == [
        clearance_line(CLEARANCE)]


def test_the_paint_used_after_the_compliance_before_a_warning():
    """paint.json's ``paint`` (docs/model.md §29): its lines after the clearance and the
    compliance, before a warning of a film that misses its acceptance."""
    from pollard_pin.painting.accounting import material_lines
    from pollard_pin.painting.summary import film_miss_line

    paint = {"paint": {"covered_share": 0.9, "painted_area_m2": 0.03, "target_area_m2": 0.031,
                       "dry_sprayed_l": 1.5e-3, "dry_on_part_l": 7.8e-4, "overspray": 0.48}}
    check = {"outside_5pct": 0.5, "outside_10pct": 0.384, "min_relative": 1e-5,
             "max_relative": 1.13, "acceptance": {"band": 0.1, "min_share": 0.99},
             "meets": False}
    off = {"compliance": {"stiffness": False, "note": "not computed"}}
    lines = material_lines(paint)
    assert lines == ["paint: 0.03 of 0.031 m² at ≥ 90 % of the target; dry film 0.0015 L "
                     "sprayed, 0.00078 L on the part: geometric overspray 48.0 %"]
    assert closing_lines({**CLEARANCE, **off, **paint, "film_check": check}) == [
        clearance_line(CLEARANCE), "compliance not computed", *lines, film_miss_line(check)]


def test_the_speeds_line_only_when_stated():
    rep = {"line": {"speed": 0.03}, "timings": {"plan": 1.0}}
    assert speeds_lines(rep) == []
    rep["line"]["speeds"] = {"min": 0.0031, "max": 0.04017, "resolution": 0.05,
                             "min_bound": "budget floor",
                             "max_bound": "too fast: a motor at 104 % of its rating"}
    rep["timings"]["speeds"] = 41.23
    assert speeds_lines(rep) == [
        "line speeds that paint it: 0.0031–0.04017 m/s (each end to 5 %, found in 41.2 s); "
        "below: budget floor; above: a motor at 104 % of its rating"]


def test_the_strokes_line():
    """paint.json's strokes in one line (docs/model.md §24.2): a line's, a cell's waits."""
    assert strokes_line({"direction": "across", "step_from": "leading", "dwell_s": 0.0}) == (
        "strokes across the travel, stepping from the leading end; waits at the turnarounds "
        "none")
    assert strokes_line({"direction": "across", "step_from": "trailing", "dwell_s": 57.25}
                        ).endswith("trailing end; waits at the turnarounds 57.250 s")
    assert strokes_line({"direction": "along", "step_from": None, "dwell_s": 0.0}) == (
        "strokes along the travel; waits at the turnarounds none")
    assert strokes_line({"direction": "across", "step_from": "leading", "dwell_s": 1.0},
                        "'low' 1.000 s, 'high' 2.000 s").endswith("'low' 1.000 s, 'high' 2.000 s")


def test_a_parts_share_that_lands_is_not_called_the_paints_transfer_efficiency():
    """A part's top-level transfer_efficiency (on the part / sprayed, the geometry's) is said
    as the geometric one, apart from [paint]'s transfer efficiency on the paint line."""
    from pollard_pin.painting.summary import part_summary_lines

    th = {"min": 24e-6, "max": 26e-6, "mean": 25e-6, "within_5pct": 1.0, "within_10pct": 1.0}
    rep = {"passes": 5, "direction": "horizontal", "spacing": 0.018, "speed": 0.3,
           "tip_speed_range": [0.29, 0.31], "coats": 1, "normal_smoothing": 0.01,
           "cycle_time": 8.0, "lower_bound": 4.0, "thickness": th, "target": 25e-6,
           "largest_incidence_deg": 12.8, "transfer_efficiency": 0.552,
           "motors": {"a": {"peak_torque": 0.5, "rms_torque": 0.25, "speed": 0.125}},
           "timings": {"plan": 1.0, "film": 1.0}, "film_points": {"painted": 10},
           "samples": 100}
    lines = part_summary_lines(rep, ["a"])
    assert ("largest incidence 12.8°, geometric transfer efficiency 55.2 % (on the part / "
            "sprayed)") in lines
