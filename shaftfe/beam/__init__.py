"""Stepped Timoshenko beam model of a balancer-shaft variant: the fast static cross-check of the
3D FE, and the shaft model of the beam rotor (``shaftfe.rotordynamics.beam_rotor``).

Modules, in pipeline order:

* ``elements``: dof layout (6 per node), section properties (Cowper κ, circle minus hexagon at
  the hex socket) and the two-node IIE Timoshenko element stiffness and consistent mass.
* ``scf``: stress-concentration factors Kt of the shoulder fillets (bending, tension and
  torsion fits).
* ``model``: ``build_model`` (nodes, sections, supports, every load of the variant as load
  columns from ``shaftfe.model.loads.actions``, stations, notches) into a ``BeamModel``;
  assembled stiffness, mass and support matrices, rigid-body modes and the support check.
* ``solve``: one factorisation and one solve per load column (``solve_unit``), superposed per
  rpm or load case (``result_at``, ``solve``, ``solve_cases``, ``analyse``) into ``BeamResult``
  (reactions, L10h, deflections, bending moment, axial force, torque, nominal and Kt-corrected
  stresses).

Importing this package imports none of its modules; they load NumPy (SciPy inside the solve).
"""
