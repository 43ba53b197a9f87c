"""The linear-solver factory: the upper-triangle extraction PARDISO gets and the diagonal shift
(`diag_add`) that `static.solve_model` uses instead of forming K + kp Σ e eᵀ as a full copy."""

import numpy as np
import pytest
import scipy.sparse as sp

from shaftfe.fe import solvers


def _spd(n=300, seed=0):
    A = sp.random(n, n, density=0.03, random_state=seed, format="csr")
    return (A @ A.T + sp.identity(n) * 0.5).tocsr()


def test_upper_triangle_matches_scipy_triu_with_the_diagonal_shift():
    """Reference: scipy.sparse.triu of A + diag (repeated indices add up)."""
    A = _spd()
    idx, val = np.array([3, 7, 7, 299]), np.array([1.0, 2.0, 0.5, 4.0])
    U = solvers.upper_triangle(A, (idx, val))
    d = np.bincount(idx, weights=val, minlength=A.shape[0])
    ref = sp.triu(A + sp.diags(d), format="csr")
    assert U.has_canonical_format
    assert abs(U - ref).max() == 0.0


def test_upper_triangle_with_empty_rows_and_a_missing_diagonal():
    """Rows without entries (first, middle, last) and a diagonal entry that is not stored."""
    B = sp.lil_matrix((6, 6))
    B[1, 1], B[1, 4], B[4, 1], B[3, 3] = 2.0, 1.0, 1.0, 5.0
    B = B.tocsr()
    U = solvers.upper_triangle(B, (np.array([0, 3]), np.array([7.0, 1.0])))
    ref = sp.triu(B + sp.diags([7.0, 0, 0, 1.0, 0, 0]), format="csr")
    assert abs(U - ref).max() == 0.0


@pytest.mark.parametrize("method", [m for m, ok in solvers.available().items()
                                    if ok and m != "amg"])
def test_factorize_with_diag_add_solves_the_shifted_system(method):
    """x from factorize(A, diag_add) against a dense solve of A + diag (1e-12)."""
    A = _spd()
    idx, val = np.array([0, 5, 11]), np.array([10.0, 20.0, 30.0])
    b = np.random.default_rng(1).standard_normal((A.shape[0], 3))
    x = solvers.factorize(A, method, diag_add=(idx, val)).solve(b)
    d = np.zeros(A.shape[0])
    d[idx] = val
    ref = np.linalg.solve(A.toarray() + np.diag(d), b)
    # cond₂(A + diag) = 71: both solves are within a few eps·cond ≈ 1e-14 of max |x|
    # (measured 1.4e-15 SuperLU / 1.2e-15 PARDISO, elementwise ≤ 4e-12 on small entries);
    # 1e-12 leaves ≥ 70× (was 1e-10)
    np.testing.assert_allclose(x, ref, rtol=1e-12, atol=1e-12 * np.abs(ref).max())


@pytest.mark.skipif(not solvers.available()["pardiso"], reason="PARDISO (mkl_rt) not installed")
def test_pardiso_ordering_cache_gives_the_same_solution_bit_for_bit(tmp_path, monkeypatch):
    """The fill-reducing ordering cached by pattern (solvers._ordering_file) is PARDISO's own:
    a run that reads it factorises with the same permutation, so the solution is identical to
    the last bit to one without the cache (exact: the same operations in the same order). A
    corrupt file is recomputed, and a different pattern gets its own file."""
    monkeypatch.setenv("SHAFTFE_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(solvers, "ORDERING_MIN_DOFS", 0)
    A = _spd(n=2000, seed=3)
    b = np.random.default_rng(2).standard_normal((A.shape[0], 4))
    monkeypatch.setenv("SHAFTFE_ORDERING_CACHE", "0")
    x_plain = solvers.factorize(A, "pardiso").solve(b)
    assert not list(tmp_path.glob("ordering-*.npy"))
    monkeypatch.delenv("SHAFTFE_ORDERING_CACHE")
    first = solvers.factorize(A, "pardiso")
    files = list(tmp_path.glob("ordering-*.npy"))
    assert len(files) == 1 and not first._m.ordering_cached
    second = solvers.factorize(A, "pardiso")
    assert second._m.ordering_cached
    for f in (first, second):
        assert np.array_equal(f.solve(b), x_plain)
    files[0].write_bytes(b"not an ordering")
    third = solvers.factorize(A, "pardiso")
    assert not third._m.ordering_cached and np.array_equal(third.solve(b), x_plain)
    solvers.factorize(_spd(n=2000, seed=4), "pardiso")
    assert len(list(tmp_path.glob("ordering-*.npy"))) == 2
    files = sorted(tmp_path.glob("ordering-*.npy"))
    for f in files:
        f.write_bytes(b"")                                     # empty files (EOFError)
    again = solvers.factorize(A, "pardiso")
    assert not again._m.ordering_cached and np.array_equal(again.solve(b), x_plain)
    # unsymmetric (weighted matching: the ordering depends on the values): never cached
    solvers.factorize_unsymmetric(A + sp.triu(A, 1) * 0.5, "pardiso")
    assert len(list(tmp_path.glob("ordering-*.npy"))) == 2
