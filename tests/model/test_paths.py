"""Where the shipped model files are found (model/paths.py): in a checkout the repository's
models/, whose parameter file the package loads."""
from pathlib import Path

from pollard_pin.model.paths import models_dir

ROOT = Path(__file__).resolve().parents[2]


def test_in_a_checkout_the_models_are_the_repositorys():
    d = models_dir()
    assert d == ROOT / "models"
    for name in ("pollard.toml", "pollard.urdf", "pollard.srdf", "actuators.toml"):
        assert (d / name).is_file(), name


def test_installed_copy_is_the_data_package(monkeypatch, tmp_path):
    """Without a models/ beside the package (an installed wheel), the data package
    pollard_pin.models is the answer, wherever the install put it."""
    import importlib

    import pollard_pin.model.paths as P

    fake = tmp_path / "site" / "pollard_pin" / "model" / "paths.py"
    fake.parent.mkdir(parents=True)
    monkeypatch.setattr(P, "__file__", str(fake))
    d = P.models_dir()
    assert d == Path(importlib.import_module("pollard_pin.models").__path__[0])
    assert not d.is_relative_to(tmp_path) and (d / "pollard.toml").is_file()
