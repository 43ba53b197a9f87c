"""shaftfe — balancer-shaft design and assessment for low-cylinder-count engines.

Stages, one module each: balancing (``shaftfe.balance``), variant files (``shaftfe.model.variant``),
beam model (``shaftfe.beam.model``), Gmsh solid and mesh (``shaftfe.solid.mesh``), and later the 3D static,
modal and fatigue analyses. Importing the package has no side effects and loads no FE stack.

Units inside the solvers: mm, N, MPa, t/mm³, s. Input files state their units in key names.
"""

__version__ = "0.1.0"
