"""Stepped Timoshenko beam model of a balancer-shaft variant: the fast static cross-check of the
3D FE, and the shaft model of the beam rotor (``shaftfe.rotordynamics.beam_rotor``).

Modules, in pipeline order:

* ``elements``: dof layout (6 per node), section properties (Cowper κ, circle minus hexagon at
  the hex socket) and the two-node IIE Timoshenko element stiffness and consistent mass.
* ``scf``: stress-concentration factors Kt of the shoulder fillets (bending fits).
* ``model``: ``build_model`` (nodes, sections, supports, centrifugal and static loads, stations,
  shoulders) into a ``BeamModel``; assembled stiffness, mass and support matrices, rigid-body
  modes and the support check.
* ``solve``: one supported solve per unit ω² (``solve_unit``), its scaling and post-processing
  per rpm (``result_at``, ``solve``, ``analyse``) into ``BeamResult`` (reactions, L10h,
  deflections, nominal and Kt-corrected stresses).

Importing this package imports none of its modules; they load NumPy (SciPy inside the solve).
"""
