"""Where the shipped model files live: the repo's top-level models/, or the installed copy."""
from __future__ import annotations

from importlib import resources
from pathlib import Path


def models_dir() -> Path:
    repo = Path(__file__).resolve().parents[2] / "models"
    if (repo / "pollard.toml").is_file():
        return repo
    # Installed wheel: models/ is shipped as the data package pollard_pin.models.
    return Path(str(resources.files("pollard_pin.models")))
