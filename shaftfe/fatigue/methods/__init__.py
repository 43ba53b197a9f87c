"""The fatigue methods by name: ONE registry (``METHODS``), read by ``shaftfe fatigue`` (its
``--method``, its options' refusals and ``--help``: ``fatigue.method_options``), the report and
the studies. Each method is one module answering ``protocol.FatigueMethod``; a new method is
one module and one line below.

Stdlib only at import (the method modules import numpy and the FE stack inside their
functions): the command's ``--help`` lists the methods without loading them.
"""

from __future__ import annotations

from shaftfe.errors import InputError
from shaftfe.fatigue.methods import din743, fkm, seed
from shaftfe.fatigue.methods.protocol import (
    AssessmentInputs,
    FatigueAssessment,
    FatigueMethod,
    LoadChannel,
    Location,
)

__all__ = ["DEFAULT_METHOD", "METHODS", "OUTPUT_FILES", "AssessmentInputs", "FatigueAssessment",
           "FatigueMethod", "LoadChannel", "Location", "get_method"]

# the order of --help and of every listing (the seed's first: the original method)
METHODS: dict[str, FatigueMethod] = {
    "seed": seed.METHOD,
    "fkm": fkm.METHOD,
    "din743": din743.METHOD,
}
DEFAULT_METHOD = "fkm"
# the files each method writes (each method's ``files``); `shaftfe fatigue --help` names them
OUTPUT_FILES = {n: m.files for n, m in METHODS.items()}


def get_method(name: str, source: str = "command line",
               field: str = "--method") -> FatigueMethod:
    """The method registered as ``name``; InputError listing the registered names."""
    if name not in METHODS:
        raise InputError(source, field, " | ".join(METHODS), got=name)
    return METHODS[name]
