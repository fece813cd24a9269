"""Design studies of the stand-in evaluator (tests/synthesis_stub.py) shared by the design tests:
run once per session, in this process (workers=1), each stored in its own study file."""
import pytest
import synthesis_stub as stub

from pollard_pin.synthesis.api import design
from pollard_pin.synthesis.study import DesignOptions


def run_stub(study, trials: int, *, resume: bool = False, space=None, **options):
    """The stand-in's study in the file ``study`` (None: in memory), this process; every
    design planned exactly unless ``search`` is given (a SearchFidelity)."""
    options.setdefault("search", None)
    evaluator = options.pop("evaluator", stub)
    return design(stub.StubJob(), space or stub.StubSpace(),
                  DesignOptions(trials=trials, workers=options.pop("workers", 1), study=study,
                                resume=resume, population=options.pop("population", 8),
                                **options), evaluator=evaluator)


@pytest.fixture(scope="session")
def stub_result():
    """A 40-design study of the stand-in, in memory (the stored studies: test_study.py)."""
    return run_stub(None, 40)
