"""The warning of values that are possible but probably wrong (a unit mistake) or outside a
model's assumptions: the sentences a study's node would flag its row with, raised at the call
that took the value."""

from __future__ import annotations

import os
import sys
import warnings
from typing import Iterable


class PlausibilityWarning(UserWarning):
    """A value is possible but probably in the wrong unit, or outside a model's assumptions: the
    sentence says which value, why, and the fix. ``warnings.simplefilter("error",
    asperity.PlausibilityWarning)`` turns these into errors."""


_PACKAGE = os.path.dirname(os.path.abspath(__file__))


def _caller_level() -> int:
    """The stack level of the first frame outside this package (the user's call)."""
    level = 1
    frame = sys._getframe(1)
    while frame is not None and os.path.dirname(os.path.abspath(frame.f_code.co_filename)) == _PACKAGE:
        frame = frame.f_back  # type: ignore[assignment]
        level += 1
    return level


def warn(sentences: Iterable[str]) -> None:
    """Each sentence as a :class:`PlausibilityWarning` pointing at the user's call."""
    for sentence in sentences:
        warnings.warn(sentence, PlausibilityWarning, stacklevel=_caller_level())
