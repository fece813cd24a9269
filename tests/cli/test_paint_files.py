"""What paint says (cli/paint_files.py): one motor-use order for every kind of job."""
from pollard_pin.cli.paint_files import motor_use_line


def test_one_motor_use_order():
    rep = {"motors": {"a": {"peak_torque": 0.5, "rms_torque": 0.25, "speed": 0.125}}}
    assert motor_use_line(rep, ["a"]) == "motor peak torque/RMS torque/speed use [%]: a 50/25/12"
