#!/usr/bin/env python3
"""Why siconos-lemke's pivots on P1 move with rounding: the LCP it is given, rebuilt.

Rebuilds P1 `block` (src/problems/block.cc: n x n plane-stress Q4, wall and floor pairs, the
right edge's traction) and the reduction of formulations/siconos/siconos_lcp.h for a body held
by its contacts only (kEliminatedWithRigidModes: K_c = K + c G^T G, A = G K_c^-1 G^T, the
rigid gaps V1 = the eigenvectors of c A with eigenvalue 1, the LCP in (z^, a+^, a-^)), then runs
Lemke's method as Siconos's lcp_lexicolemke does it (tableau [q | I | -d | -M]; the
lexicographic rule only among ratios that are exactly equal) on:
  1. the LCP as built;
  2. the same LCP with V1 turned within the rigid space (a basis change: the same problem);
  3. A perturbed by 1e-11 relative (the size of its rounding: c A's triple eigenvalue 1 comes
     out spread by ~5e-11), with V1 from the eigensolver or canonical (the rigid gaps G N of
     the translations and the rotation, orthonormalised in that order), and the split equality
     V1^T z^ = e / R relaxed by delta on both sides or not;
and, for comparison, Lemke with z0 leaving whenever its row ties (to 1e-9) with the minimum
ratio. Counts pivots and says whether each ended at a solution (info 0), on a ray (2: no
positive entry in the entering column; Siconos's driver reports it as info 1, the code of its
pivot limit, from its check of the answer's error) or at the limit. Needs numpy. issue 25,
docs/findings.md ("What moves with rounding").

Usage: p1_lemke.py [N]   (N elements per side, default 50; N = 50 takes ~10 s)
"""
import sys

import numpy as np

E_MOD, NU, THICK, SIDE, TRACTION = 1e8, 0.3, 0.01, 2.0, -5e5
L_SCALE, R_SCALE = 1e-2, 1e2


def build(n):
    """K (dense), f, G = grad phi (nc x d), and the nodes' coordinates of P1 at n x n."""
    h = SIDE / n
    npn = n + 1
    d = 2 * npn * npn
    D = E_MOD / (1 - NU * NU) * np.array([[1, NU, 0], [NU, 1, 0], [0, 0, (1 - NU) / 2]])
    corners = np.array([[0, 0], [h, 0], [h, h], [0, h]], float)
    Ke = np.zeros((8, 8))
    for xi in (-1 / np.sqrt(3), 1 / np.sqrt(3)):
        for eta in (-1 / np.sqrt(3), 1 / np.sqrt(3)):
            dN = 0.25 * np.array([[-(1 - eta), 1 - eta, 1 + eta, -(1 + eta)],
                                  [-(1 - xi), -(1 + xi), 1 + xi, 1 - xi]])
            J = dN @ corners
            dNx = np.linalg.solve(J, dN)
            B = np.zeros((3, 8))
            B[0, 0::2] = dNx[0]
            B[1, 1::2] = dNx[1]
            B[2, 0::2] = dNx[1]
            B[2, 1::2] = dNx[0]
            Ke += B.T @ D @ B * THICK * np.linalg.det(J)
    K = np.zeros((d, d))
    for j in range(n):
        for i in range(n):
            nodes = [j * npn + i, j * npn + i + 1, (j + 1) * npn + i + 1, (j + 1) * npn + i]
            dofs = np.ravel([[2 * a, 2 * a + 1] for a in nodes])
            K[np.ix_(dofs, dofs)] += Ke
    f = np.zeros(d)
    for j in range(n):
        for a in (j * npn + n, (j + 1) * npn + n):
            f[2 * a:2 * a + 2] += 0.5 * TRACTION * h * THICK
    pairs = [(j * npn, 0) for j in range(npn)] + [(i, 1) for i in range(npn)]
    G = np.zeros((len(pairs), d))
    for p, (a, axis) in enumerate(pairs):
        G[p, 2 * a + axis] = -1.0  # phi = -g; the wall's gap is x + u_x, the floor's y + u_y
    X = np.array([[i * h, j * h] for j in range(npn) for i in range(npn)])
    return K, f, G, X


def reduce(K, f, G):
    """A = G K_c^-1 G^T, h = -G K_c^-1 f (phi(0) = 0, lambda = 1) and c, as siconos_lcp.cc."""
    contact = np.nonzero(G)[1]
    c = 1e-3 * np.diag(K)[contact].min()
    Kc = K + c * G.T @ G
    X = np.linalg.solve(Kc, np.column_stack([G.T, f]))
    A = G @ X[:, :-1]
    return 0.5 * (A + A.T), -G @ X[:, -1], c


def lcp(A, h, c, basis=None, delta=0.0):
    """The LCP (M, q) of siconos_lcp.h; V1 from the eigensolver, or `basis` (a function of the
    eigensolver's V1 returning another orthonormal basis of its span); the two rows of each
    rigid equality relaxed by delta."""
    s, V = np.linalg.eigh(A)
    rigid = int((c * s > 0.5).sum())
    nc = len(h)
    el = nc - rigid
    V2, V1, s2 = V[:, :el], V[:, el:], s[:el]
    if basis is not None:
        V1 = basis(V1)
    one_minus = 1 - c * s2
    e = -np.linalg.solve(V1.T @ A @ V1, V1.T @ h)  # -diag(1 / s1) V1^T h for eigenvectors
    m = nc + 2 * rigid
    M = np.zeros((m, m))
    M[:nc, :nc] = R_SCALE / L_SCALE * (V2 * (s2 / one_minus)) @ V2.T
    M[:nc, nc:nc + rigid] = V1
    M[:nc, nc + rigid:] = -V1
    M[nc:nc + rigid, :nc] = -V1.T
    M[nc + rigid:, :nc] = V1.T
    q = np.concatenate([V2 @ ((V2.T @ h) / one_minus) / L_SCALE, e / R_SCALE + delta,
                        -e / R_SCALE + delta])
    return M, q, rigid, s


def lemke(M, q, itermax=10000, z0_first=False, tie=1e-9):
    """Lemke's method with Siconos's lexicographic rule; returns (pivots, z or None, info)."""
    dim = len(q)
    T = np.zeros((dim, 2 * (dim + 1)))
    T[:, 0] = q
    T[:, 1:dim + 1] = np.eye(dim)
    T[:, dim + 1] = -1.0
    T[:, dim + 2:] = -M
    tol = np.abs(M).max() * np.finfo(float).eps
    basis = np.arange(1, dim + 1)

    def pivot(row, col):
        T[row] /= T[row, col]
        other = T[:, col].copy()
        other[row] = 0.0
        T[:] -= np.outer(other, T[row])

    block = int(np.argmin(T[:, 0]))
    pivot(block, dim + 1)
    leaving = basis[block]
    basis[block] = dim + 1
    for it in range(1, itermax + 1):
        drive = leaving + dim + 1 if leaving < dim + 1 else leaving - (dim + 1)
        rows = np.where(T[:, drive] > 0.0)[0]
        if len(rows) == 0:
            return it, None, 2
        ratios = T[rows, 0] / T[rows, drive]
        best = ratios.min()
        ties = rows[ratios == best]
        if z0_first:
            near = rows[np.abs(ratios - best) <= tie * max(abs(best), 1e-300)]
            z0 = [i for i in near if basis[i] == dim + 1]
            ties = np.array(z0) if z0 else ties
        block = ties[0]
        for var in ties[1:]:
            for jc in range(1, dim + 1):
                ab, av = T[block, jc], T[var, jc]
                if abs(ab) < tol or abs(av) < tol:
                    lower = (av < -tol) if abs(ab) < tol else (ab > tol)
                    higher = (av > tol) if abs(ab) < tol else (ab < -tol)
                else:
                    delta = ab * T[var, drive] - av * T[block, drive]
                    lower, higher = delta > tol, delta < -tol
                if lower:
                    block = var
                    break
                if higher:
                    break
        done = basis[block] == dim + 1
        pivot(block, drive)
        leaving = basis[block]
        basis[block] = drive
        if done:
            z = np.zeros(dim)
            for row, b in enumerate(basis):
                if b > dim + 1:
                    z[b - dim - 2] = T[row, 0]
            return it, z, 0
    return itermax, None, 1


def outcome(M, q, z0_first=False, q_judge=None):
    it, z, info = lemke(M, q, z0_first=z0_first)
    if z is None:
        return f"{it} ({'ray' if info == 2 else 'limit'})"
    qj = q if q_judge is None else q_judge
    w = M @ z + qj
    err = (np.maximum(-z, 0).sum() + np.maximum(-w, 0).sum()
           + np.where((z > 0) & (w > 0), z * w, 0).sum()) / (np.linalg.norm(qj) + 1)
    return f"{it}" + ("" if err < 1e-8 else f" (error {err:.1e})")


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 50
    K, f, G, X = build(n)
    A, h, c = reduce(K, f, G)
    M, q, rigid, s = lcp(A, h, c)
    nc = len(h)
    print(f"P1, n = {n}: {nc} pairs, {rigid} rigid modes, an LCP of {len(q)}; c A's rigid "
          f"eigenvalues {np.round(c * s[-rigid:], 12)} (exactly 1 in exact arithmetic; spread "
          f"{np.ptp(c * s[-rigid:]):.1e}), the next {c * s[-rigid - 1]:.4f}")
    print(f"as built: Lemke (Siconos's rule) {outcome(M, q)} pivots; z0 first "
          f"{outcome(M, q, z0_first=True)}")
    rng = np.random.default_rng(3)
    turned = []
    for _ in range(16):
        Q, _ = np.linalg.qr(rng.standard_normal((rigid, rigid)))
        Mr, qr, _, _ = lcp(A, h, c, basis=lambda V1: V1 @ Q)
        turned.append((outcome(Mr, qr), outcome(Mr, qr, z0_first=True)))
    print("V1 turned within the rigid space, 16 random turns (Siconos's rule / z0 first):")
    print("  " + ", ".join(f"{a} / {b}" for a, b in turned))
    N = np.zeros((G.shape[1], 3))
    N[0::2, 0] = 1.0
    N[1::2, 1] = 1.0
    N[0::2, 2] = -X[:, 1]
    N[1::2, 2] = X[:, 0]
    GN = G @ N

    def canonical(V1):
        Q, R = np.linalg.qr(V1 @ (V1.T @ GN))
        return Q * np.sign(np.diag(R))

    print("A perturbed by 1e-11 relative, 8 draws: pivots of Lemke (Siconos's rule) with")
    results = {"eigensolver's V1": [], "canonical V1": [], "eigensolver's V1, delta 1e-12": [],
               "canonical V1, delta 1e-12": []}
    for _ in range(8):
        eps = 1e-11 * rng.standard_normal(A.shape)
        Ap = A * (1 + 0.5 * (eps + eps.T))
        for label in results:
            basis = canonical if label.startswith("canonical") else None
            Mp, qp, _, _ = lcp(Ap, h, c, basis=basis)
            if "delta" in label:
                delta = 1e-12 * max(1.0, np.abs(qp[nc:]).max())
                Md, qd, _, _ = lcp(Ap, h, c, basis=basis, delta=delta)
                results[label].append(outcome(Md, qd, q_judge=qp))
            else:
                results[label].append(outcome(Mp, qp))
    for label, res in results.items():
        print(f"  {label}: " + ", ".join(res))


if __name__ == "__main__":
    main()
