"""Versions of the installed packages, for the provenance block of every summary.json."""

from __future__ import annotations


def package_versions(*packages: str) -> dict[str, str | None]:
    """Installed versions of shaftfe, numpy, scipy, scikit-fem, gmsh, meshio and ``packages``
    (None when not installed), for the provenance block of a summary.json."""
    import importlib.metadata as md

    out: dict[str, str | None] = {}
    for pkg in ("shaftfe", "numpy", "scipy", "scikit-fem", "gmsh", "meshio", *packages):
        try:
            out[pkg] = md.version(pkg)
        except md.PackageNotFoundError:
            out[pkg] = None
    return out
