"""The URDF and SRDF generated from the parameters (model/urdf.py): the committed files are
the generator's output, and Pinocchio reads them without a warning, every geometry included.
(yourdfpy and MuJoCo reading them against the spec numbers: tests/model/test_build.py.)"""
import json
import xml.etree.ElementTree as ET
from pathlib import Path

from clean_run import run_clean

from pollard_pin.model.build import generate
from pollard_pin.model.params import load_params

MODELS = Path(__file__).resolve().parents[2] / "models"
URDF_PATH = MODELS / "pollard.urdf"
SRDF_PATH = MODELS / "pollard.srdf"


def test_committed_urdf_and_srdf_are_generated():
    urdf, srdf = generate(load_params())
    assert urdf == URDF_PATH.read_text(), "stale: run `make urdf`"
    assert srdf == SRDF_PATH.read_text(), "stale: run `make urdf`"
    assert generate(load_params()) == (urdf, srdf)  # deterministic


def _xml_counts(tag):
    root = ET.parse(URDF_PATH).getroot()
    return {link.get("name"): len(link.findall(tag)) for link in root.findall("link")}


def test_urdf_loads_in_pinocchio_without_warnings(tmp_path):
    stdout = run_clean(tmp_path, f"""
        import json, pinocchio as pin, pollard_pin
        urdf, srdf = {str(URDF_PATH)!r}, {str(SRDF_PATH)!r}
        m = pin.buildModelFromUrdf(urdf)
        vis = pin.buildGeomFromUrdf(m, urdf, pin.GeometryType.VISUAL)
        col = pin.buildGeomFromUrdf(m, urdf, pin.GeometryType.COLLISION)
        pin.loadReferenceConfigurations(m, srdf, False)
        r = pollard_pin.load()
        print(json.dumps(dict(nq=m.nq, vis=vis.ngeoms, col=col.ngeoms,
                              home=list(m.referenceConfigurations["home"]),
                              rvis=r.visual_model.ngeoms, rcol=r.collision_model.ngeoms)))
    """)
    res = json.loads(stdout)
    assert res["nq"] == 12 and len(res["home"]) == 12
    assert res["vis"] == res["rvis"] == sum(_xml_counts("visual").values())
    assert res["col"] == res["rcol"] == sum(_xml_counts("collision").values())
