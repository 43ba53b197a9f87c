"""The axisymmetric Fourier-harmonic solver (``--model axisymmetric``): the shaft as a body of
revolution, each harmonic an uncoupled 2D problem on the meridian plane. Entry points:
``solve.solve_axisymmetric`` (the product path), ``kt.converged`` (stepped-bar Kt with error
bars); the pieces in ``mesh``, ``kernels``, ``harmonic``, ``recovery``, ``model``, ``outputs``.
Nothing is imported here (Gmsh and SciPy load inside the functions that need them)."""
