#!/usr/bin/env python3
"""The two pieces of a 2-D truss path at a contact pair about to change status.

Rebuilds, from a problem file (`contactbench export`) and a run's final state (solution.csv,
contacts.csv), the truss's tangent stiffness (Biot strain: N = E A (l - L) / L, as
src/model/truss.h) and the gap rows of its pairs (half-spaces and solid balls), checks
equilibrium against the records (f_int - lambda f + G^T r = 0, r <= 0 in contact), and for the
pair PAIR computes the path's tangent on the piece C where it stays closed and on the piece O
where it opens: the load direction O's feasible half takes (its gap must grow), the angle
between the two, the unstable modes of each (negative eigenvalues of K_t on the motions that keep
the closed pairs closed), and a root of the next arc-length step on O for a few theta (Newton
from the predictor along O's tangent, the sphere (33) with w = 1). issue 25, docs/findings.md
("What moves with rounding").

Usage: kink_pieces.py PROBLEM.json RUN_DIR PAIR [--theta T ...]
"""
import argparse
import csv
import json
import os

import numpy as np


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


class Truss:
    def __init__(self, problem):
        self.p = problem
        self.X = np.array([n["x"] for n in problem["nodes"]], float)
        self.ndof = 2 * len(self.X)
        self.f = np.zeros(self.ndof)
        for load in problem["loads"]:
            self.f[2 * load["node"]:2 * load["node"] + 2] += load["force"]
        fixed = {2 * s["node"] + "xy".index(c) for s in problem["supports"] for c in s["fixed"]}
        self.free = np.array([i for i in range(self.ndof) if i not in fixed])
        self.obstacles = {o["id"]: o for o in problem["obstacles"]}

    def evaluate(self, U, r):
        """K_t (with the gaps' curvature times r), f_int, G (gap gradients) and the gaps."""
        x = self.X + U
        K = np.zeros((self.ndof, self.ndof))
        fint = np.zeros(self.ndof)
        for m in self.p["members"]:
            i, j = m["nodes"]
            L0 = np.linalg.norm(self.X[j] - self.X[i])
            d = x[j] - x[i]
            length = np.linalg.norm(d)
            n = d / length
            N = m["E"] * m["A"] * (length - L0) / L0
            k = m["E"] * m["A"] / L0 * np.outer(n, n) + N / length * (np.eye(2) - np.outer(n, n))
            idx = [2 * i, 2 * i + 1, 2 * j, 2 * j + 1]
            K[np.ix_(idx, idx)] += np.block([[k, -k], [-k, k]])
            fint[idx] += np.concatenate([-N * n, N * n])
        pairs = self.p["contact_pairs"]
        G = np.zeros((len(pairs), self.ndof))
        gap = np.zeros(len(pairs))
        for q, c in enumerate(pairs):
            o = self.obstacles[c["obstacle"]]
            a = c["node"]
            if o["type"] == "half-space":
                n = -np.array(o["normal"], float)
                gap[q] = n @ (x[a] - np.array(o["point"], float))
                hess = np.zeros((2, 2))
            elif o["type"] == "ball" and o.get("side", "solid") == "solid":
                d = x[a] - np.array(o["centre"], float)
                dist = np.linalg.norm(d)
                n = d / dist
                gap[q] = dist - o["radius"]
                hess = (np.eye(2) - np.outer(n, n)) / dist
            else:
                raise SystemExit(f"kink_pieces: obstacle type {o['type']} not handled")
            G[q, 2 * a:2 * a + 2] = n
            K[2 * a:2 * a + 2, 2 * a:2 * a + 2] += r[q] * hess
        return K, fint, G, gap


def tangent(K, G, f, active):
    """(du per unit dlambda on the free dofs, dr of the active pairs, eigenvalues of K on the
    motions that keep the active pairs closed)."""
    Ga = G[active]
    na = len(active)
    M = np.block([[K, Ga.T], [Ga, np.zeros((na, na))]])
    sol = np.linalg.solve(M, np.concatenate([f, np.zeros(na)]))
    Q, _ = np.linalg.qr(Ga.T, mode="complete")
    Z = Q[:, na:]
    return sol[:len(f)], dict(zip(active, sol[len(f):])), np.linalg.eigvalsh(Z.T @ K @ Z)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("problem")
    parser.add_argument("run")
    parser.add_argument("pair", type=int)
    parser.add_argument("--theta", type=float, nargs="*", default=[0.1, 0.01, 0.003])
    args = parser.parse_args()
    with open(args.problem) as f:
        truss = Truss(json.load(f))
    sol = sorted(rows(os.path.join(args.run, "solution.csv")), key=lambda r: int(r["node"]))
    U = np.array([[float(r["ux"]), float(r["uy"])] for r in sol])
    con = sorted(rows(os.path.join(args.run, "contacts.csv")), key=lambda r: int(r["pair"]))
    r = np.array([float(c["r"]) for c in con])
    lam = float(con[0]["lambda"])
    K, fint, G, gap = truss.evaluate(U, r)
    fr = truss.free
    res = (fint - lam * truss.f + G.T @ r)[fr]
    print(f"state of {args.run}: lambda {lam:.6f}; gaps against the records "
          f"{np.abs(gap - np.array([float(c['g']) for c in con])).max():.1e}; equilibrium "
          f"{np.abs(res).max():.1e} of forces up to {np.abs(fint).max():.1e}")
    k = args.pair
    # closed: a reaction above rounding (the records' open pairs carry r ~ 1e-13)
    closed = sorted(set(np.where(r < -1e-9 * np.abs(r).max())[0]) | {k})
    print(f"closed pairs {closed}; pair {k}: g = {gap[k]:.3e}, r = {r[k]:.6g}")
    Kf, Gf, ff = K[np.ix_(fr, fr)], G[:, fr], truss.f[fr]
    duC, drC, evC = tangent(Kf, Gf, ff, closed)
    opened = [q for q in closed if q != k]
    duO, _, evO = tangent(Kf, Gf, ff, opened)
    dgO = Gf[k] @ duO
    print(f"C (pair {k} closed): dr_{k}/dlambda = {drC[k]:.4e}; unstable modes "
          f"{int((evC < 0).sum())}, smallest eigenvalues {np.round(np.sort(evC)[:3], 3)}")
    print(f"O (pair {k} open):   dg_{k}/dlambda = {dgO:.4e}; unstable modes "
          f"{int((evO < 0).sum())}, smallest eigenvalues {np.round(np.sort(evO)[:3], 3)}")
    tC = np.append(duC, 1.0) * np.sign(drC[k])  # C is left the way r_k grows to 0
    tC /= np.linalg.norm(tC)
    sign = 1.0 if dgO > 0 else -1.0  # O's feasible half: g_k grows
    tO = sign * np.append(duO, 1.0)
    tO /= np.linalg.norm(tO)
    cosine = float(tC @ tO)
    print(f"O's feasible half: dlambda {'> 0' if sign > 0 else '< 0'}; cos(t_C, t_O) = "
          f"{cosine:.4f} ({np.degrees(np.arccos(np.clip(cosine, -1, 1))):.1f} degrees)")
    control = truss.p["control"]
    c_dof = 2 * control["node"] + "xy".index(control["direction"])
    ci = list(fr).index(c_dof)
    print(f"control displacement per unit path length: on C {tC[ci]:.4e}, on O {tO[ci]:.4e}")
    nf = len(fr)
    for theta in args.theta:
        z = np.concatenate([U.reshape(-1)[fr] + theta * tO[:nf], r[opened],
                            [lam + theta * tO[-1]]])

        def system(z):
            u = U.reshape(-1).copy()
            u[fr] = z[:nf]
            rr = np.zeros(len(r))
            rr[opened] = z[nf:-1]
            K2, fint2, G2, gap2 = truss.evaluate(u.reshape(-1, 2), rr)
            dv = np.append(z[:nf] - U.reshape(-1)[fr], z[-1] - lam)
            F = np.concatenate([(fint2 - z[-1] * truss.f + G2.T @ rr)[fr], gap2[opened],
                                [dv @ dv - theta ** 2]])
            return F, K2, G2, gap2, rr, dv

        for it in range(1, 51):
            F, K2, G2, gap2, rr, dv = system(z)
            J = np.zeros((len(F), len(z)))
            J[:nf, :nf] = K2[np.ix_(fr, fr)]
            J[:nf, nf:-1] = G2[opened][:, fr].T
            J[:nf, -1] = -truss.f[fr]
            J[nf:-1, :nf] = G2[opened][:, fr]
            J[-1, :nf] = 2 * dv[:nf]
            J[-1, -1] = 2 * dv[-1]
            step = np.linalg.solve(J, F)
            z -= step
            if np.abs(step).max() < 1e-13 * max(1.0, np.abs(z).max()):
                break
        F, K2, G2, gap2, rr, dv = system(z)
        others = [q for q in range(len(r)) if q not in closed]
        print(f"theta {theta}: a root on O after {it} Newton iterations (equilibrium "
              f"{np.abs(F[:nf]).max():.1e}): lambda {z[-1]:.6f}, control {z[ci]:.6f}; g_{k} = "
              f"{gap2[k]:.3e}, smallest gap of the other open pairs {gap2[others].min():.3e}, "
              f"largest r of the closed pairs {rr[opened].max():.4g}")


if __name__ == "__main__":
    main()
