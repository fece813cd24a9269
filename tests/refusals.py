"""The one-line refusal of a public entry point given a wrong argument: the package's InputError
(no TypeError or AttributeError from deep inside), one line of at most 250 characters that
names the argument."""
import re

import pytest

from pollard_pin.errors import InputError


def refused(call, name: str) -> str:
    """``call()``'s InputError message, checked: one line, ≤ 250 characters, naming ``name``."""
    with pytest.raises(InputError) as exc:
        call()
    msg = str(exc.value)
    assert "\n" not in msg and len(msg) <= 250, msg
    assert re.search(rf"(^|\W){re.escape(name)}(\W|$)", msg), (name, msg)
    return msg


# wrong values every argument gets: None, the wrong types, NaN
WRONG = [None, 3, float("nan"), "text", [1, 2], {"a": 1}, b"bytes"]
