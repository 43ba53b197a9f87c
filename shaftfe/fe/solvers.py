"""Linear-solver factory for symmetric positive-definite FE systems.

``factorize(A, method)`` returns an object with ``.solve(b)`` (b of shape (n,) or (n, k)),
``.name`` and ``.seconds`` (factorisation wall time). It is made once per model and reused
for every right-hand side (load cases, Woodbury columns, error estimates).

Methods
-------
``"superlu"``  SciPy's SuperLU (always available). Symmetric mode: minimum degree on AᵀA+A
               ordering and diagonal pivoting, which suits an SPD matrix.
``"pardiso"``  Intel MKL PARDISO through ``pypardiso`` (optional extra ``shaftfe[fast]``).
``"amg"``      Conjugate gradients preconditioned with smoothed-aggregation AMG (``pyamg``,
               optional); tolerance 1e-12 relative, so not a direct solve.
``"auto"``     PARDISO if ``pypardiso`` imports, else SuperLU.

A requested optional backend that is not installed falls back to SuperLU with a note
(``.note``), never a crash. No solver is trusted to detect singularity (FINDINGS pitfall 8):
the static model checks its supports on the rigid-body modes before factorising and checks the
residual of every solve after.
"""

from __future__ import annotations

import os
import time

import numpy as np

# MKL's conditional numerical reproducibility (PARDISO): without it a solve may differ in the
# last bits from one process to the next (measured: the refinement solve of
# ``static.solve_model``), which breaks bit-identical summaries (tests/test_determinism.py).
# Set before pypardiso loads MKL; a value the user set wins.
os.environ.setdefault("MKL_CBWR", "AUTO,STRICT")
import scipy.sparse as sp

METHODS = ("auto", "superlu", "pardiso", "amg")


def _with_diag(A, diag_add):
    """A + diag (a new matrix); ``diag_add`` = (indices, values) or None."""
    if diag_add is None:
        return A
    idx, val = diag_add
    d = np.zeros(A.shape[0])
    np.add.at(d, np.asarray(idx), val)
    return (A + sp.diags(d)).tocsr()


def upper_triangle(A, diag_add=None) -> sp.csr_matrix:
    """The upper triangle (diagonal included) of the square sparse matrix A as canonical CSR,
    with ``diag_add`` = (indices, values) added to its diagonal: one pass over A's CSR arrays,
    no full-size copy of A (``scipy.sparse.triu`` goes through COO: 208 MB of temporaries
    at 13 M entries)."""
    A = sp.csr_matrix(A)
    if not A.has_canonical_format:
        A = A.copy()
        A.sum_duplicates()
    n = A.shape[0]
    rows = np.repeat(np.arange(n, dtype=A.indices.dtype), np.diff(A.indptr))
    keep = A.indices >= rows
    counts = np.bincount(rows[keep], minlength=n)
    del rows
    indptr = np.zeros(n + 1, dtype=A.indptr.dtype)
    np.cumsum(counts, out=indptr[1:])
    U = sp.csr_matrix((A.data[keep], A.indices[keep], indptr), shape=A.shape)
    if diag_add is not None:
        idx, val = np.asarray(diag_add[0]), diag_add[1]
        first = U.indptr[idx]                       # sorted rows: the diagonal comes first
        if np.all(np.diff(U.indptr)[idx] > 0) and np.all(U.indices[first] == idx):
            np.add.at(U.data, first, val)
        else:                                       # a structurally missing diagonal entry
            U = upper_triangle(_with_diag(A, diag_add))
    return U


class _SuperLU:
    name = "superlu"

    def __init__(self, A, diag_add=None):
        from scipy.sparse.linalg import splu
        t0 = time.perf_counter()
        self._lu = splu(sp.csc_matrix(_with_diag(A, diag_add)), permc_spec="MMD_AT_PLUS_A",
                        diag_pivot_thresh=0.0,
                        options={"SymmetricMode": True})
        self.seconds = time.perf_counter() - t0

    def solve(self, b):
        return self._lu.solve(np.asarray(b, dtype=float))


class _Pardiso:
    name = "pardiso"

    def __init__(self, A, diag_add=None):
        import pypardiso
        t0 = time.perf_counter()
        # real SPD; size_limit_storage=0: pypardiso keeps a hash of the factorised matrix
        # instead of a copy (−80 MB at 170k dofs; the hash costs ~0.1 s per solve call)
        self._s = pypardiso.PyPardisoSolver(mtype=2, size_limit_storage=0)
        self._s.set_phase(12)
        self._A = upper_triangle(A, diag_add)
        self._s.factorize(self._A)
        self.seconds = time.perf_counter() - t0

    def solve(self, b):
        b = np.asarray(b, dtype=float)
        x = self._s.solve(self._A, np.ascontiguousarray(b))
        return np.asarray(x).reshape(b.shape)


class _AMG:
    name = "amg"

    def __init__(self, A, rigid_modes=None, diag_add=None):
        import pyamg
        t0 = time.perf_counter()
        self._A = sp.csr_matrix(_with_diag(A, diag_add))
        kw = {}
        if rigid_modes is not None:
            kw["B"] = rigid_modes
        self._ml = pyamg.smoothed_aggregation_solver(self._A, **kw)
        self._M = self._ml.aspreconditioner()
        self.seconds = time.perf_counter() - t0

    def _one(self, b):
        from scipy.sparse.linalg import cg
        x, _ = cg(self._A, b, M=self._M, rtol=1e-12, maxiter=2000)
        return x

    def solve(self, b):
        b = np.asarray(b, dtype=float)
        if b.ndim == 1:
            return self._one(b)
        return np.column_stack([self._one(b[:, k]) for k in range(b.shape[1])])


class _SuperLUGeneral:
    name = "superlu"

    def __init__(self, A):
        import scipy.sparse as sp
        from scipy.sparse.linalg import splu
        self._lu = splu(sp.csc_matrix(A))

    def solve(self, b):
        return self._lu.solve(np.asarray(b, dtype=float))


class _PardisoGeneral:
    name = "pardiso"

    def __init__(self, A):
        import pypardiso
        import scipy.sparse as sp
        self._s = pypardiso.PyPardisoSolver(mtype=11)
        self._A = sp.csr_matrix(A)
        self._A.sort_indices()
        self._s.factorize(self._A)

    def solve(self, b):
        b = np.asarray(b, dtype=float)
        return np.asarray(self._s.solve(self._A, np.ascontiguousarray(b))).reshape(b.shape)


UNSYMMETRIC_PARDISO_MIN_DOFS = 30_000   # PARDISO's setup costs ~1 s: SuperLU below this


def factorize_unsymmetric(A, method: str = "auto"):
    """Factorise a real nonsymmetric sparse A (a gyroscopic shift of the solid rotor): PARDISO
    if installed and asked for, or ``auto`` on ≥ UNSYMMETRIC_PARDISO_MIN_DOFS, else SuperLU."""
    big = A.shape[0] >= UNSYMMETRIC_PARDISO_MIN_DOFS
    if (method == "pardiso" or (method == "auto" and big)) and _importable("pardiso"):
        return _PardisoGeneral(A)
    return _SuperLUGeneral(A)


_MODULES = {"pardiso": "pypardiso", "amg": "pyamg"}


def _importable(name: str) -> bool:
    if name == "superlu":
        return True
    try:
        __import__(_MODULES[name])
        return True
    except Exception:
        return False


def available() -> dict[str, bool]:
    """Which backends import on this machine."""
    return {name: _importable(name) for name in ("superlu", "pardiso", "amg")}


def factorize(A, method: str = "auto", rigid_modes=None, diag_add=None):
    """Factorise the SPD matrix A (+ diag, ``diag_add`` = (indices, values), without a full
    copy of A on the PARDISO path) with ``method`` (see the module docstring)."""
    if method not in METHODS:
        raise ValueError(f"unknown solver {method!r}; choose one of {METHODS}")
    note = ""
    if method == "auto":
        method = "pardiso" if _importable("pardiso") else "superlu"
    elif not _importable(method):
        note = f"{method} is not installed; fell back to superlu"
        method = "superlu"
    if method == "pardiso":
        f = _Pardiso(A, diag_add)
    elif method == "amg":
        f = _AMG(A, rigid_modes, diag_add)
    else:
        f = _SuperLU(A, diag_add)
    f.note = note
    return f
