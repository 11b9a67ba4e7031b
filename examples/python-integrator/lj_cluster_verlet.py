"""Stormer-Verlet for a Lennard-Jones cluster in space, in NumPy, for vivv's process protocol.

    L = sum_i |v_i|^2 / 2 - 4 eps sum_{i<j} ((sigma/r_ij)^12 - (sigma/r_ij)^6)    (unit masses, p = v)

The forces of all pairs at once, vectorised: O(N^2) a step for N atoms, no Python loop over
atoms. Greeted with a formula system whose coordinates are a family x[N, 3] and whose
parameters include eps and sigma, it steps that cluster; any other system is declined.

    python3 lj_cluster_verlet.py [--jacobian] [--kick K] [--no-batch]

--jacobian sends the map's own Jacobian (2n x 2n, from the force's derivative, the pairs'
3 x 3 blocks assembled at once). --kick K (default 1/2) is the first kick's fraction of h:
0.5 + 1e-3 is the bug this example's negative case plants (order 1, still symplectic).
--no-batch declines the extension "steps" (every step of a run crosses the pipe: what the extension
saves, measured in docs/process-protocol.md).
"""
import argparse
import os
import sys

import numpy as np

try:
    import vivv_map
except ImportError:  # run from vivv's source tree: the package beside the examples
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
    import vivv_map


class Cluster:
    def setup(self, system, dimension, number):
        params = system.get("params", {})
        if dimension % 3 != 0 or "eps" not in params or "sigma" not in params:
            raise vivv_map.Decline("this integrator steps a Lennard-Jones cluster in space: 3N coordinates "
                                   f"and parameters eps and sigma, not {dimension} coordinates with "
                                   f"parameters {sorted(params)}")
        self.atoms = dimension // 3
        self.eps, self.sigma = float(params["eps"]), float(params["sigma"])

    def _pairs(self, q):
        x = q.reshape(self.atoms, 3)
        d = x[:, None, :] - x[None, :, :]               # d_ij = x_i - x_j
        r2 = np.einsum("ijk,ijk->ij", d, d)
        np.fill_diagonal(r2, 1.0)
        s6 = (self.sigma ** 2 / r2) ** 3
        return d, r2, s6

    def force(self, q):
        d, r2, s6 = self._pairs(q)
        # -dV/dx_i = sum_j 24 eps (2 s^12 - s^6) / r^2 · d_ij
        c = 24 * self.eps * (2 * s6 * s6 - s6) / r2
        np.fill_diagonal(c, 0.0)
        return np.einsum("ij,ijk->ik", c, d).reshape(-1)

    def stiffness(self, q):
        """dF/dq, 3N x 3N. F_i = sum_j a_ij d_ij with a = 24 eps (2 s^12 - s^6)/r^2, so for j != i
        dF_i/dx_j = -(a_ij I - b_ij d_ij d_ij^T), b = -(1/r) da/dr = 24 eps (28 s^12 - 8 s^6)/r^4, and
        dF_i/dx_i = -sum_{j != i} dF_i/dx_j."""
        d, r2, s6 = self._pairs(q)
        a = 24 * self.eps * (2 * s6 * s6 - s6) / r2
        b = 24 * self.eps * (28 * s6 * s6 - 8 * s6) / (r2 * r2)
        np.fill_diagonal(a, 0.0)
        np.fill_diagonal(b, 0.0)
        blocks = -(a[:, :, None, None] * np.eye(3) - b[:, :, None, None] * d[:, :, :, None] * d[:, :, None, :])
        n = self.atoms
        atoms = np.arange(n)
        blocks[atoms, atoms] = -blocks.sum(axis=1)
        return blocks.transpose(0, 2, 1, 3).reshape(3 * n, 3 * n)


def options(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--jacobian", action="store_true", help="send the map's own Jacobian")
    parser.add_argument("--kick", default="0.5", help="the first kick's fraction of h (0.5 is Verlet)")
    parser.add_argument("--no-batch", action="store_true", help="one request a step (decline \"steps\")")
    return parser.parse_args(argv)


if __name__ == "__main__":
    args = options(sys.argv[1:])
    cluster, a = Cluster(), float(args.kick)

    def step(h, q, p):
        p_half = p + a * h * cluster.force(q)
        q_next = q + h * p_half
        return q_next, p_half + (1 - a) * h * cluster.force(q_next)

    def jacobian(h, q, p):
        n = q.size
        eye = np.eye(n)
        q_next = q + h * (p + a * h * cluster.force(q))
        K0, K1 = cluster.stiffness(q), cluster.stiffness(q_next)
        dhalf_dq = a * h * K0
        dq_dq, dq_dp = eye + h * dhalf_dq, h * eye
        dp_dq = dhalf_dq + (1 - a) * h * K1 @ dq_dq
        dp_dp = eye + (1 - a) * h * K1 @ dq_dp
        return np.block([[dq_dq, dq_dp], [dp_dq, dp_dp]])

    vivv_map.serve(step, jacobian=jacobian if args.jacobian else None, arithmetic="numpy", setup=cluster.setup,
                   batch=not args.no_batch)
