"""Shared fixtures of the test suite.

The shared test material and the seed's bearing stiffness are defined once, in
``shaftfe.model.examples`` (``STEEL``, ``K_SEED``: also what benchmarks and notebooks use); test
modules import them from there. Every test module gets its own mesh/static cache directory
through ``cache`` (module scope: a module's meshes are built once and never shared with
another module, so no test depends on the order the modules run in).
"""

from __future__ import annotations

import pytest


@pytest.fixture(scope="module")
def cache(tmp_path_factory, request):
    """A mesh and static cache directory of this test module's own."""
    return tmp_path_factory.mktemp(request.module.__name__.rsplit(".", 1)[-1] + "-cache")
