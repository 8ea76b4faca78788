"""The all-roots solve of many poses in vectorised NumPy: the reference that
`cargo bench --bench roots_batch` (benches/roots_batch.rs) runs on the coefficients it writes.

    numpy_roots.py COEFFS X_ROOTS

COEFFS: little-endian float64, a pose's p then q, c[i][j] the coefficient of x^i y^j (18 a
pose). X_ROOTS: our x-roots, 8 complex (re, im) a pose, NaN past the last.

For all poses at once: the resultant in y of the two quadratics as a degree-8 polynomial in x
(R = (a2 b0 - a0 b2)^2 - (a2 b1 - a1 b2)(a1 b0 - a0 b1), as src/numeric/mod.rs), the stacked
companion matrices' eigenvalues by np.linalg.eigvals, then y: the roots of both quadratics at
each x, each judged by the other equation's relative residual, the best taken. Prints the CPU
time a pose (time.process_time, the best of five runs) without and with y, and checks that
each of our x-roots is one of NumPy's. Run it with one BLAS thread (OPENBLAS_NUM_THREADS=1).
"""

import sys
import time

import numpy as np


def pmul(u, v):
    """Products of polynomials in x (lowest degree first), one a row."""
    du, dv = u.shape[1], v.shape[1]
    out = np.zeros((u.shape[0], du + dv - 1))
    for i in range(du):
        out[:, i : i + dv] += u[:, i : i + 1] * v
    return out


def x_roots(p, q):
    """The eigenvalues of each pose's monic resultant's companion matrix, (n, 8)."""
    a = [p[:, :, j] for j in range(3)]
    b = [q[:, :, j] for j in range(3)]
    c20 = pmul(a[2], b[0]) - pmul(a[0], b[2])
    c21 = pmul(a[2], b[1]) - pmul(a[1], b[2])
    c10 = pmul(a[1], b[0]) - pmul(a[0], b[1])
    r = pmul(c20, c20) - pmul(c21, c10)
    n = p.shape[0]
    companion = np.zeros((n, 8, 8))
    companion[:, 0, :] = -r[:, 7::-1] / r[:, 8:9]
    companion[:, np.arange(1, 8), np.arange(7)] = 1.0
    return np.linalg.eigvals(companion)


def in_y(c, x):
    """The coefficients of c(x, y) as a quadratic in y at each x: (n, 8, 3)."""
    x = x[..., None]
    return c[:, None, 0, :] + x * (c[:, None, 1, :] + x * c[:, None, 2, :])


def quadratic_roots(c):
    """Both roots of c0 + c1 y + c2 y^2, without cancellation: (n, 8, 2)."""
    c0, c1, c2 = c[..., 0], c[..., 1], c[..., 2]
    d = np.sqrt(c1 * c1 - 4.0 * c2 * c0)
    d = np.where((np.conj(c1) * d).real >= 0.0, d, -d)
    h = -0.5 * (c1 + d)
    return np.stack([h / c2, c0 / h], axis=-1)


def relative(c, y):
    """|c(x, y)| / sum of |terms| at candidates y (n, 8, m), c as in_y gives it."""
    ay = np.abs(y)
    value = c[..., 0:1] + y * (c[..., 1:2] + y * c[..., 2:3])
    size = np.abs(c[..., 0:1]) + ay * (np.abs(c[..., 1:2]) + ay * np.abs(c[..., 2:3]))
    return np.abs(value) / size


def y_roots(p, q, x):
    """At each x, the root of p's or q's quadratic that best satisfies the other: (n, 8)."""
    cp, cq = in_y(p, x), in_y(q, x)
    yp, yq = quadratic_roots(cp), quadratic_roots(cq)
    candidates = np.concatenate([yp, yq], axis=-1)
    residual = np.concatenate([relative(cq, yp), relative(cp, yq)], axis=-1)
    best = np.argmin(np.nan_to_num(residual, nan=np.inf), axis=-1)
    return np.take_along_axis(candidates, best[..., None], axis=-1)[..., 0]


def cpu_us_per_pose(f, n):
    best = np.inf
    for _ in range(5):
        start = time.process_time()
        f()
        best = min(best, time.process_time() - start)
    return best * 1e6 / n


def main():
    coeffs = np.fromfile(sys.argv[1], dtype="<f8").reshape(-1, 2, 3, 3)
    ours = np.fromfile(sys.argv[2], dtype="<f8").reshape(-1, 8, 2)
    p, q = np.ascontiguousarray(coeffs[:, 0]), np.ascontiguousarray(coeffs[:, 1])
    n = p.shape[0]
    eig = cpu_us_per_pose(lambda: x_roots(p, q), n)
    full = cpu_us_per_pose(lambda: y_roots(p, q, x_roots(p, q)), n)
    x = x_roots(p, q)
    y = y_roots(p, q, x)
    # Each of our x-roots is one of NumPy's (relative 1e-6: near-double roots are only that
    # well determined), and NumPy's y there satisfies both equations.
    ours = ours[..., 0] + 1j * ours[..., 1]
    gap = np.abs(ours[:, :, None] - x[:, None, :]).min(axis=-1) / (1.0 + np.abs(ours))
    mine = ~np.isnan(ours)
    missing = int((gap[mine] > 1e-6).sum())
    print(f"  NumPy {np.__version__}, one thread, the same {n} poses:")
    print(f"  eigvals_us {eig:.3f} (resultant + companion matrices + np.linalg.eigvals)")
    print(f"  all_us {full:.3f} (the same, and y from both quadratics)")
    print(
        f"  checked: {int(mine.sum())} x-roots of ours, {missing} not among NumPy's; "
        f"median residual of NumPy's (x, y) {np.median(relative(in_y(p, x), y[..., None])):.1e}"
    )
    if missing:
        sys.exit(f"{missing} of our x-roots are not among NumPy's")


if __name__ == "__main__":
    main()
