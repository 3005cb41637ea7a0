"""Your own method beside the built-in ones (docs/your-own-method.md): a semismooth Newton on
the Fischer-Burmeister function, registered as `my-newton`, traces P3 (arch-curved) warm in one
`compare` with implicit-fb, active-set and petsc-ssls; prints the table and writes a
Dolan-More performance profile of the solve times.

  PYTHONPATH=build/python /usr/bin/python3 examples/python/compare_my_newton.py [OUT] [--steps N]
"""

import argparse
import os
import sys

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

try:
    import contactbench as cb
except ImportError:  # not installed: the module of this tree's build (README's set-up)
    sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "build", "python"))
    import contactbench as cb


# ---- the method: F(x) = 0 and FB(g^_p, -r^_p) = 0 for every pair, Newton with Armijo -----------
def my_newton(system, x0, tol=1e-10, max_iter=50):
    a_i, b_i = system.pair_gaps, system.pair_reactions
    rows = np.arange(len(a_i))

    def G(x):  # the square system: F and the FB function of each pair (a = g^, b = -r^)
        a, b = x[a_i], -x[b_i]
        return np.concatenate([system.F(x), np.hypot(a, b) - a - b])

    x, g = x0.copy(), G(x0)
    it = solves = 0
    while np.abs(g).max() > tol and it < max_iter:
        a, b = x[a_i], -x[b_i]
        s = np.hypot(a, b)
        safe = np.where(s > 0, s, 1.0)  # at a = b = 0: the B-subdifferential element along (1, 1)
        da = np.where(s > 0, a / safe, np.sqrt(0.5)) - 1.0
        db = np.where(s > 0, b / safe, np.sqrt(0.5)) - 1.0
        fb = sp.csr_matrix((np.concatenate([da, -db]), (np.concatenate([rows, rows]),
                            np.concatenate([a_i, b_i]))), shape=(len(a_i), system.size))
        dx = spla.spsolve(sp.vstack([system.jacobian(x), fb]).tocsc(), -g)
        solves += 1
        t, merit = 1.0, g @ g
        while True:  # Armijo on 1/2 ||G||^2 (the Newton direction's slope is -||G||^2)
            trial = G(x + t * dx)
            if trial @ trial <= (1 - 1e-4 * t) * merit or t < 1e-10:
                break
            t *= 0.5
        x, g, it = x + t * dx, trial, it + 1
    return x, {"iterations": it, "linear_solves": solves, "converged": np.abs(g).max() <= tol}


# ---- the comparison and its performance profile ------------------------------------------------
def profile(steps, path):
    """Fraction of the steps each formulation solves within tau times the fastest's time."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    accepted = steps[steps["accepted"]]
    times = accepted.pivot_table(index="step", columns="formulation", values="time_s")
    ratios = (times.div(times.min(axis=1), axis=0)).fillna(np.inf)
    taus = np.logspace(0, 3, 300)
    fig, ax = plt.subplots(figsize=(6, 4))
    for name in ratios.columns:
        ax.step(taus, [(ratios[name] <= t).mean() for t in taus], where="post", label=name)
    ax.set(xscale="log", xlabel="tau (time / fastest time)", ylabel="fraction of steps",
           title="P3 arch-curved, warm: performance profile")
    ax.legend()
    fig.savefig(path, dpi=120, bbox_inches="tight")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="my-newton-comparison",
                        help="directory for the profile (default: ./my-newton-comparison)")
    parser.add_argument("--steps", type=int, default=None, help="path steps (default: P3's)")
    args = parser.parse_args()
    cb.register("my-newton", my_newton, description="semismooth Newton on FB (this example)",
                solver="numpy-scipy")
    wanted = ["my-newton", "implicit-fb", "active-set", "petsc-ssls"]
    built = set(cb.formulations().query("available")["name"])
    result = cb.compare(problem="arch-curved", formulations=[f for f in wanted if f in built],
                        starts="warm", steps=args.steps)
    table = result.steps[result.steps["accepted"]].groupby("formulation").agg(
        steps=("step", "count"), iterations=("iterations", "sum"), time_s=("time_s", "sum"))
    print(result.runs[["formulation", "status", "accepted", "message"]].to_string(index=False))
    print(table.to_string())
    os.makedirs(args.out, exist_ok=True)
    figure = os.path.join(args.out, "profile.png")
    profile(result.steps, figure)
    print("profile:", figure)


if __name__ == "__main__":
    main()
