"""The job's [gun] table with a spray model (paint/gun_table.py, docs/model.md §20): each model
reads, writes back as the file says it and plans with its own spot; every bad key or value is
one line naming the key and the file."""
import math
from pathlib import Path

import pytest

from pollard_pin.painting.errors import JobError
from pollard_pin.painting.gun_table import MAX_APEX, MAX_BETA, MAX_ELONGATION, job_spot
from pollard_pin.painting.job import job_from_dict, load_job
from pollard_pin.painting.spray.deposition import gun_of
from pollard_pin.painting.spray.spots import BetaSpot, EllipticGaussian, RoundGaussian

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "paint.toml"


def _job(gun: dict, part: bool = False) -> dict:
    where = ({"part": {"mesh": "plate.stl", "position": [0.7, 0.0, 0.16]}} if part else
             {"panel": {"center": [0.70, 0.0, 0.16], "normal": [-1.0, 0.0, 0.0],
                        "width": 0.26, "height": 0.12}})
    return {**where, "gun": {"standoff": 0.15, "flow": 1.5e-7, **gun},
            "job": {"thickness": 25e-6}}


def test_the_default_gun_is_the_round_gaussian_as_before():
    """No model: the job's spot is None (the round Gaussian of sigma), its gun table written
    back key for key as before, and gun.model = "gaussian" reads the same job."""
    job = load_job(EXAMPLE)
    assert job.spot is None and job.apex is None
    assert list(job.to_dict()["gun"]) == ["standoff", "sigma", "flow"]
    assert job_spot(job) == RoundGaussian(0.010) == gun_of(job).spot
    same = job_from_dict(_job({"model": "gaussian", "sigma": 0.010}), str(EXAMPLE))
    assert same.spot is None and same.sigma == 0.010


@pytest.mark.parametrize("part", [False, True])
@pytest.mark.parametrize("gun, spot", [
    ({"model": "elliptic", "sigma_long": 0.02, "sigma_short": 0.008},
     EllipticGaussian(0.02, 0.008)),
    ({"model": "beta", "radius": 0.03, "beta": 2.5, "apex": -0.05}, BetaSpot(0.03, 2.5)),
    ({"sigma": 0.01, "apex": 0.02}, None),
])
def test_each_model_reads_and_writes_back(gun, spot, part):
    """The job's spot and apex, sigma its width; to_dict gives the table back (model, its
    keys, apex) and reads to the same job; the gun has the spot and apex."""
    job = job_from_dict(_job(gun, part), "job.toml")
    assert job.spot == spot and job.apex == gun.get("apex")
    assert job.sigma == (gun["sigma"] if spot is None else spot.width)
    table = job.to_dict()["gun"]
    assert table == {"standoff": 0.15, **gun, "flow": 1.5e-7}
    again = job.to_dict()
    for k in ("panel", "part"):
        if k in again:
            again[k] = {key: list(v) if isinstance(v, tuple) else v
                        for key, v in again[k].items()}
    assert job_from_dict(again, "job.toml") == job
    g = gun_of(job)
    assert g.spot == job_spot(job) and g.apex == gun.get("apex", 0.0)


@pytest.mark.parametrize("gun, words", [
    ({"model": "elliptc", "sigma_long": 0.02, "sigma_short": 0.01},
     ["'gun.model'", "did you mean 'elliptic'"]),
    ({"model": 2, "sigma": 0.01}, ["'gun.model'", "'gaussian', 'elliptic', 'beta'"]),
    ({"model": "elliptic", "sigma": 0.01}, ["'gun.sigma_long' is missing",
                                            "standoff, sigma_long, sigma_short, flow"]),
    ({"model": "beta", "radius": 0.03}, ["'gun.beta' is missing"]),
    ({"sigma": 0.01, "radius": 0.03}, ["'gun.radius'", "not a key of model 'gaussian'",
                                       "takes sigma"]),
    ({"model": "elliptic", "sigma_long": 0.02, "sigma_short": 0.01, "sigma": 0.01},
     ["'gun.sigma'", "not a key of model 'elliptic'"]),
    ({"sigma": 0.01, "radus": 0.03}, ["'gun.radus'", "unknown key", "did you mean 'radius'"]),
    ({"model": "elliptic", "sigma_long": 0.02, "sigma_short": -0.01},
     ["'gun.sigma_short'", "must be > 0"]),
    ({"model": "elliptic", "sigma_long": "wide", "sigma_short": 0.01},
     ["'gun.sigma_long'", "must be a number"]),
    ({"model": "elliptic", "sigma_long": 0.01, "sigma_short": 0.02},
     ["'gun.sigma_short'", "must not exceed gun.sigma_long"]),
    ({"model": "elliptic", "sigma_long": 0.06, "sigma_short": 0.01},
     ["'gun.sigma_short'", f"at least 1/{MAX_ELONGATION:g} of gun.sigma_long"]),
    ({"model": "beta", "radius": 30.0, "beta": 2.0}, ["'gun.radius'", "metres, not mm"]),
    ({"model": "beta", "radius": 0.03, "beta": 1.0}, ["'gun.beta'", "must be > 1"]),
    ({"model": "beta", "radius": 0.03, "beta": 0.5}, ["'gun.beta'", "must be > 1"]),
    ({"model": "beta", "radius": 0.03, "beta": 2 * MAX_BETA}, ["'gun.beta'", "at most"]),
    ({"model": "beta", "radius": 0.03, "beta": math.nan}, ["'gun.beta'", "finite"]),
    ({"model": "beta", "radius": 0.03, "beta": True}, ["'gun.beta'", "must be a number"]),
    ({"sigma": 0.01, "apex": 0.15}, ["'gun.apex'", "before the standoff"]),
    ({"sigma": 0.01, "apex": 0.1499999}, ["'gun.apex'", f"at most {MAX_APEX:g} of it"]),
    ({"sigma": 5}, ["'gun.sigma' = 5", "makes a spot 5 m wide", "0.15 m", "not mm"]),
    ({"model": "elliptic", "sigma_long": 0.2, "sigma_short": 0.1},
     ["'gun.sigma_long' = 0.2", "wider than the 0.15 m"]),
    ({"model": "beta", "radius": 0.4, "beta": 2.0, "apex": 0.05},
     ["'gun.radius' = 0.4", "makes a spot 0.1633 m wide", "the 0.1 m it flies"]),
    ({"sigma": 0.01, "apex": "x"}, ["'gun.apex'", "must be a number"]),
    ({"sigma": 0.01, "apex": -50.0}, ["'gun.apex'", "at most 10 m"]),
])
def test_each_bad_gun_is_one_line(gun, words):
    with pytest.raises(JobError) as info:
        job_from_dict(_job(gun), "job.toml")
    msg = str(info.value)
    assert "\n" not in msg and msg.startswith("job.toml: ") and len(msg) <= 250, msg
    for w in words:
        assert w in msg, (w, msg)


def test_the_smallest_panel_is_in_the_spots_width():
    """MIN_PANEL_SIGMAS compares the panel with the spot's width: a β spot of R = 0.3 m
    (width 0.3/√7 = 0.113 m) fits the 0.12 m high panel, one of R = 0.35 m (0.132 m) not."""
    job_from_dict(_job({"model": "beta", "radius": 0.3, "beta": 2.5}), "job.toml")
    with pytest.raises(JobError, match="smaller than the spray spot"):
        job_from_dict(_job({"model": "beta", "radius": 0.35, "beta": 2.5}), "job.toml")


def test_spot_keys_read_back_as_the_spot():
    """spot_keys gives a [gun] table's keys for a spot; the job they make has that spot."""
    from pollard_pin.painting.gun_table import spot_keys

    for spot in (RoundGaussian(0.012), EllipticGaussian(0.02, 0.008), BetaSpot(0.03, 2.5)):
        keys = spot_keys(spot, apex=-0.04)
        job = job_from_dict(_job(keys), "gun.toml")
        assert job_spot(job) == spot and job.apex == -0.04
    assert spot_keys(None, 0.01) == {"sigma": 0.01}


@pytest.mark.parametrize("changes, words", [
    ({"spot": BetaSpot(0.03, 2.0)}, ["'sigma' = 0.01", "not the beta spot's width 0.01224",
                                     "sigma=None"]),
    ({"spot": RoundGaussian(0.02)}, ["'sigma' = 0.01", "gaussian spot's width 0.02"]),
    ({"spot": "beta"}, ["'spot' = 'beta'", "must be a spray spot"]),
    ({"spot": EllipticGaussian(0.02, 0.002), "sigma": None}, ["'gun.sigma_short'", "1/5"]),
    ({"spot": BetaSpot(0.03, 5000.0), "sigma": None}, ["'gun.beta'", "at most 1000"]),
    ({"apex": 0.2}, ["'gun.apex' = 0.2", "before the standoff (0.15 m)"]),
])
@pytest.mark.parametrize("part", [False, True])
def test_a_python_job_with_a_spot_is_checked_when_made(changes, words, part):
    """A job built in Python (dataclasses.replace) meets the [gun] rules when it is made, one
    JobError line (not a ValueError from the gun when it paints); sigma=None takes the
    spot's width, and a round Gaussian spot is the job of its sigma."""
    from dataclasses import replace

    job = job_from_dict(_job({"sigma": 0.01}, part), "job.toml")
    with pytest.raises(JobError) as info:
        replace(job, **changes)
    msg = str(info.value)
    assert "\n" not in msg and msg.startswith("job.toml: ") and len(msg) <= 250, msg
    for w in words:
        assert w in msg, (w, msg)
    beta = replace(job, spot=BetaSpot(0.03, 2.0), sigma=None)
    assert beta.sigma == BetaSpot(0.03, 2.0).width == gun_of(beta).sigma
    assert beta == job_from_dict(_job({"model": "beta", "radius": 0.03, "beta": 2.0}, part),
                                 "job.toml")
    assert replace(job, spot=RoundGaussian(0.01)) == job
