"""Crank-mechanism balancing model (SPEC.md §1; seed 000 ch. 2, 5, 7; seed 003 ch. 4-6).

Pure NumPy kernels in ``kinematics``; single cylinder and sweeps in ``single`` and ``sweep``;
several cylinders in ``multi``; parts-based ratios in ``parts``; engine files in ``engines``.
"""
