"""Speed and stress units, once: the reference speed of the solved fields, rpm → rad/s, the
rpm² load scale, and the von Mises stress.

Units inside the solvers are mm, N, MPa, t/mm³, s (docs/ARCHITECTURE.md). A load whose speed law
is ``rpm2`` (an attachment's m·e·ω², the shaft's own centrifugal load) is solved once at
``REF_RPM`` and scaled by ``rpm2_scale``; loads of other laws (``shaftfe.model.loads``) are
solved at their own magnitudes and scaled by their own factors."""

from __future__ import annotations

import math

REF_RPM = 10_000.0          # the speed every rpm² field is solved at (any speed would do)
RPM_TO_RAD_S = 2.0 * math.pi / 60.0


def omega(rpm):
    """Angular speed in rad/s of ``rpm`` (a number or an array)."""
    if isinstance(rpm, int | float):
        return float(rpm) * RPM_TO_RAD_S
    import numpy as np  # not at the top: ``shaftfe --help`` imports this module
    return np.asarray(rpm, dtype=float) * RPM_TO_RAD_S


def rpm2_scale(rpm, ref_rpm: float = REF_RPM):
    """The factor (rpm / ref_rpm)² that takes an rpm² load (or its linear response) solved at
    ``ref_rpm`` to ``rpm`` (a number or an array)."""
    if isinstance(rpm, int | float):
        return (float(rpm) / ref_rpm) ** 2
    import numpy as np
    return (np.asarray(rpm, dtype=float) / ref_rpm) ** 2


def von_mises(s):
    """von Mises stress of Voigt stresses ``s`` with the components on the FIRST axis (6, ...)
    in the order xx, yy, zz, xy, yz, xz."""
    import numpy as np
    xx, yy, zz, xy, yz, xz = s
    return np.sqrt(0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2)
                   + 3.0 * (xy ** 2 + yz ** 2 + xz ** 2))
