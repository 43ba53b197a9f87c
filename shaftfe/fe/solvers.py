"""Linear-solver factory for symmetric positive-definite FE systems.

``factorize(A, method)`` returns an object with ``.solve(b)`` (b of shape (n,) or (n, k)),
``.name`` and ``.seconds`` (factorisation wall time). It is made once per model and reused
for every right-hand side (load cases, Woodbury columns, error estimates).

Methods
-------
``"superlu"``  SciPy's SuperLU (always available). Symmetric mode: minimum degree on AᵀA+A
               ordering and diagonal pivoting, which suits an SPD matrix.
``"pardiso"``  Intel MKL PARDISO, called directly in mkl_rt (``pardiso_function``; the ``mkl``
               wheel that ``pypardiso`` brings from PyPI on x86-64); its fill-reducing
               ordering is cached on disk by the matrix pattern (``_MKL``).
``"amg"``      Conjugate gradients preconditioned with smoothed-aggregation AMG (``pyamg``,
               optional); tolerance 1e-12 relative, so not a direct solve.
``"auto"``     PARDISO if mkl_rt is found, else SuperLU.

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
# Set before mkl_rt is loaded (``pardiso_function``); a value the user set wins.
os.environ.setdefault("MKL_CBWR", "AUTO,STRICT")
import scipy.sparse as sp

from shaftfe.errors import SolverError
from shaftfe.util.atomic import write_atomic
from shaftfe.util.paths import cache_dir

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


def _explicit_iparm(iparm: np.ndarray, symmetric: bool, indefinite: bool = False) -> None:
    """Set PARDISO's iparm explicitly (iparm(1) = 1) instead of MKL's defaults (iparm(1) = 0):
    the defaults include iparm(8) = 2, two steps of iterative refinement inside every solve,
    which triples its cost (measured: 20 right-hand sides at 170k dofs 1.42 s → 0.37 s). The
    static solve refines itself (``static.solve_model``: one step on the whole bordered system,
    residual checked), the block eigen-solver checks its residuals, and the full-size check
    (``full_qep``) is compared with the reduced sweep (1.8e-7 on x2_57). The rest are
    MKL's documented defaults for the matrix type: METIS nested dissection (iparm(2) = 2),
    pivot perturbation 1e-8 (symmetric; with scaling and weighted matching if indefinite) /
    1e-13 with scaling and weighted matching (nonsymmetric), one-based indices. iparm(8) = 0
    keeps two refinement steps only if pivots were perturbed."""
    iparm[:] = 0
    iparm[0] = 1                    # iparm(1): the values below, not the defaults
    iparm[1] = 2                    # iparm(2): METIS nested dissection
    if symmetric:
        iparm[9] = 8                # iparm(10): perturb pivots to 1e-8 · ‖A‖
        iparm[10] = iparm[12] = 1 if indefinite else 0   # iparm(11), (13): for mtype −2
    else:
        iparm[9] = 13               # iparm(10): 1e-13 · ‖A‖
        iparm[10] = 1               # iparm(11): scaling
        iparm[12] = 1               # iparm(13): weighted matching


_PARDISO_FN: list = []      # the ``pardiso`` entry point of mkl_rt, found once per process


def _mkl_rt_candidates() -> list[str]:
    """Where mkl_rt may be: $PYPARDISO_MKL_RT, the environment's lib/ (the ``mkl`` wheel that
    the PyPI install brings puts it there), then the system's library path."""
    import glob
    import sys
    env = os.environ.get("PYPARDISO_MKL_RT")
    if env:
        return [env]
    found = sorted(glob.glob(os.path.join(sys.prefix, "lib", "libmkl_rt.so*"))
                   + glob.glob(os.path.join(sys.prefix, "Library", "bin", "mkl_rt*.dll")),
                   key=len)
    if found:
        return found
    # only when needed: the import alone is 35 ms of a warm run
    from ctypes.util import find_library
    return [x for x in (find_library("mkl_rt"), find_library("mkl_rt.1")) if x]


def pardiso_function():
    """MKL's ``pardiso`` with its argument types, or None when mkl_rt is not installed. Found
    with our own search (``_mkl_rt_candidates``, the places pypardiso looks first) instead of
    importing pypardiso, whose SciPy aliases cost 0.2 s of every run's start-up; pypardiso's
    own locator is the last resort."""
    if _PARDISO_FN:
        return _PARDISO_FN[0]
    import ctypes
    fn = None
    for path in _mkl_rt_candidates():
        try:
            fn = ctypes.CDLL(path).pardiso
            break
        except (OSError, AttributeError):
            continue
    if fn is None:
        try:
            import pypardiso
            fn = pypardiso.PyPardisoSolver(mtype=2)._mkl_pardiso
        except Exception:
            return None
    i32 = ctypes.POINTER(ctypes.c_int32)
    fn.argtypes = [ctypes.POINTER(ctypes.c_int64), i32, i32, i32, i32, i32,
                   ctypes.POINTER(ctypes.c_double), i32, i32, i32, i32, i32, i32,
                   ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double), i32]
    fn.restype = None
    _PARDISO_FN.append(fn)
    return fn


# below this the ordering is not cached: METIS takes < 0.05 s there. Measured on x2_57's
# gear-seat zone (18 777 dofs, 2 threads): factorisation 0.28 s with METIS, 0.19 s with the
# cached ordering
ORDERING_MIN_DOFS = 10_000
ORDERING_FORMAT = 1         # bump when the way the ordering is asked for changes


def _ordering_file(ia: np.ndarray, ja: np.ndarray, mtype: int, iparm: np.ndarray):
    """The cache file of PARDISO's fill-reducing ordering for this sparsity pattern, or None
    if it is not cached: ``$SHAFTFE_CACHE_DIR`` (or ~/.cache/shaftfe) / ``ordering-<blake2b of
    the format, n, mtype, the other iparm settings, ia, ja>.npy``. Only for the SPD type
    (mtype 2): there METIS sees the pattern alone, so the ordering is a function of the key;
    the indefinite and unsymmetric types use weighted matching, whose ordering depends on the
    values (measured: a reused one cost 40× the factorisation time). Set
    ``SHAFTFE_ORDERING_CACHE=0`` to switch it off."""
    if mtype != 2 or ia.size - 1 < ORDERING_MIN_DOFS \
            or os.environ.get("SHAFTFE_ORDERING_CACHE") == "0":
        return None
    import hashlib

    settings = iparm.copy()
    settings[4] = 0                                  # iparm(5): how the ordering is passed
    h = hashlib.blake2b(digest_size=16)
    for part in (np.array([ORDERING_FORMAT, ia.size - 1, mtype], dtype=np.int64), settings,
                 ia, ja):
        h.update(np.ascontiguousarray(part).view(np.uint8))
    return cache_dir() / f"ordering-{h.hexdigest()}.npy"


def _load_ordering(path, n: int):
    if path is None:
        return None
    try:
        perm = np.load(path, allow_pickle=False)
    except Exception:                          # missing, empty (EOFError), truncated, foreign
        return None
    ok = (perm.dtype == np.int32 and perm.shape == (n,)
          and np.array_equal(np.sort(perm), np.arange(1, n + 1, dtype=np.int32)))
    return perm if ok else None                # a corrupt file is recomputed, never trusted


def _save_ordering(path, perm: np.ndarray) -> None:
    if path is None:
        return
    import io

    buf = io.BytesIO()
    np.save(buf, perm, allow_pickle=False)
    try:
        write_atomic(path, buf.getvalue())
    except OSError:                            # a read-only cache: recompute next time
        pass


class _MKL:
    """MKL PARDISO called directly (``pardiso_function``; pypardiso checks and hashes the whole
    matrix and converts its index arrays on every solve call: ~0.1 s per call at 170k dofs, as
    much as a 20-column solve). One instance = one factorisation of one CSR matrix (upper
    triangle for mtype 2), kept until ``release``.

    The fill-reducing ordering of an SPD matrix (METIS nested dissection: 0.8 s of the 1.35 s
    analysis at 170k dofs) is cached on disk by the matrix pattern (``_ordering_file``): a later
    run on the same mesh gives PARDISO the same permutation as its own (iparm(5) = 1 instead
    of 2 returning it), so the factor and every solution are the same bit for bit
    (tests/test_solvers.py)."""

    def __init__(self, A: sp.csr_matrix, mtype: int):
        import ctypes
        self._ct = ctypes
        self._fn = pardiso_function()
        if self._fn is None:                                   # pragma: no cover
            raise ImportError("mkl_rt (PARDISO) not found")
        self._pt = np.zeros(64, dtype=np.int64)
        self.iparm = np.zeros(64, dtype=np.int32)
        _explicit_iparm(self.iparm, symmetric=mtype in (2, -2), indefinite=mtype == -2)
        self.mtype = mtype
        A = sp.csr_matrix(A)
        A.sort_indices()
        self.n = A.shape[0]
        self._data = np.ascontiguousarray(A.data, dtype=np.float64)
        self._ia = (A.indptr + 1).astype(np.int32)
        self._ja = (A.indices + 1).astype(np.int32)
        where = _ordering_file(self._ia, self._ja, mtype, self.iparm)
        perm = _load_ordering(where, self.n)
        self.ordering_cached = perm is not None
        if perm is None:
            self._perm = np.zeros(self.n, dtype=np.int32)
            self.iparm[4] = 2 if where is not None else 0   # iparm(5) = 2: return METIS' perm
        else:
            self._perm = perm
            self.iparm[4] = 1                               # iparm(5) = 1: use this perm
        self._call(12, np.zeros(self.n), 1)
        if perm is None and where is not None:
            _save_ordering(where, self._perm.copy())
        self.iparm[4] = 0

    def _call(self, phase: int, b: np.ndarray, nrhs: int) -> np.ndarray:
        ct = self._ct
        i32 = ct.POINTER(ct.c_int32)
        f64 = ct.POINTER(ct.c_double)
        x = np.zeros_like(b)
        err = ct.c_int32(0)
        self._fn(self._pt.ctypes.data_as(ct.POINTER(ct.c_int64)), ct.byref(ct.c_int32(1)),
                 ct.byref(ct.c_int32(1)), ct.byref(ct.c_int32(self.mtype)),
                 ct.byref(ct.c_int32(phase)), ct.byref(ct.c_int32(self.n)),
                 self._data.ctypes.data_as(f64), self._ia.ctypes.data_as(i32),
                 self._ja.ctypes.data_as(i32), self._perm.ctypes.data_as(i32),
                 ct.byref(ct.c_int32(nrhs)), self.iparm.ctypes.data_as(i32),
                 ct.byref(ct.c_int32(0)), b.ctypes.data_as(f64), x.ctypes.data_as(f64),
                 ct.byref(err))
        if err.value != 0:
            exc = SolverError(f"PARDISO failed in phase {phase} with error {err.value}")
            exc.code = err.value
            raise exc
        return x

    def solve(self, b):
        b = np.asarray(b, dtype=float)
        bf = np.asfortranarray(b.reshape(self.n, -1))          # columns contiguous
        x = self._call(33, bf, bf.shape[1])
        return x.reshape(b.shape)

    def release(self) -> None:
        if self._pt.any():
            self._call(-1, np.zeros(self.n), 1)
            self._pt[:] = 0

    def __del__(self):
        try:
            self.release()
        except Exception:                                  # pragma: no cover
            pass


class _Pardiso:
    name = "pardiso"

    def __init__(self, A, diag_add=None):
        t0 = time.perf_counter()
        U = upper_triangle(A, diag_add)
        self.indefinite = False
        try:
            self._m = _MKL(U, mtype=2)                             # real SPD (Cholesky)
        except SolverError as exc:
            if getattr(exc, "code", None) != -4:
                raise
            # zero or negative pivot (error -4): not positive definite (a prestress in
            # compression, a shifted matrix whose constraints, not the matrix, make the
            # problem definite): real symmetric indefinite, Bunch-Kaufman pivoting
            self._m = _MKL(U, mtype=-2)
            self.indefinite = True
        self.seconds = time.perf_counter() - t0

    def solve(self, b):
        return self._m.solve(b)


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
        self._m = _MKL(sp.csr_matrix(A), mtype=11)

    def solve(self, b):
        return self._m.solve(b)


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
    if name == "pardiso":
        return pardiso_function() is not None
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
