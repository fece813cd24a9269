"""The layout tests' shared fixture: one robot's band remembered by its arguments."""
import pytest


@pytest.fixture(scope="module")
def bands_remembered(request):
    """robot_band remembered by its arguments in the layout, the split and the using module's
    checks (check_zones, tests/cell_split_jobs.py, reads cell.bands' at each call), for that
    module (it is a function of them: the same bands, computed once). Layouts of one job
    share a reference band, the split of a layout asks again for the bands its proposal
    just moved, the checks ask for the bands the split held, and several tests lay out the
    same panel."""
    import hashlib
    import pickle

    from pollard_pin.painting.cell import bands as cell_bands
    from pollard_pin.painting.cell import split as cell_split
    from pollard_pin.painting.layout import cell as cell_layout

    band, seen = cell_layout.robot_band, {}

    def remembered(robot, cell_robot, strokes, **options):
        key = (id(robot), cell_robot, hashlib.sha1(pickle.dumps(strokes)).digest(),
               tuple(sorted(options.items())))
        if key not in seen:
            seen[key] = got = band(robot, cell_robot, strokes, **options)
            for a in got.grid or ():  # read-only: a caller writing into one fails
                a.flags.writeable = False
        return seen[key]

    with pytest.MonkeyPatch.context() as m:
        m.setattr(cell_layout, "robot_band", remembered)
        m.setattr(cell_split, "robot_band", remembered)
        m.setattr(cell_bands, "robot_band", remembered)
        if hasattr(request.module, "robot_band"):
            m.setattr(request.module, "robot_band", remembered)
        yield
