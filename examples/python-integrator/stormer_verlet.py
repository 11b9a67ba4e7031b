"""Stormer-Verlet (leapfrog) as a one-step map on (q, p), for vivv's process protocol.

    p_half = p + kick·h·F(q);  q' = q + h·p_half;  p' = p_half + (1 - kick)·h·F(q')

kick = 1/2 is Stormer-Verlet: order 2 and symplectic. `--kick 0.6` is the bug this example's
negative case plants: still a composition of symplectic kicks and drifts, but order 1.

    python3 stormer_verlet.py [--kick K] [--arithmetic mpmath|numpy] [--scale-momentum S] [--shift C]
                              [--jacobian [--wrong-jacobian-after K]] [--count-evaluations]

--arithmetic numpy computes in double with NumPy arrays (its cases declare "precision":
"double"). --scale-momentum S multiplies p' by 1 + S on every step: a map that is not
symplectic by exactly S (det J = 1 + S), the negative control of symplecticity's detection
limit in double. --shift C adds C·h^3 to q' on every step: still symplectic and of order 2, with
a larger error constant (the regression a baseline guard must catch). --jacobian sends the map's
own Jacobian, derived by hand (vivv's symplecticity then needs no differences of the program);
--wrong-jacobian-after K plants a bug in it from the K-th on (dp'/dq off by 1 %).
--count-evaluations tells vivv how many times each step evaluated F (extension "evaluations": 2
a step), so that the report's work-precision diagram draws this program by its work.
"""
import argparse
import os
import sys

try:
    import vivv_map
except ImportError:  # run from vivv's source tree: the package beside the examples
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
    import vivv_map

from systems import Force


def verlet(h, q, p, force, kick):
    f = force(q)
    p = [pi + kick * h * fi for pi, fi in zip(p, f)]
    q = [qi + h * pi for qi, pi in zip(q, p)]
    f = force(q)
    p = [pi + (1 - kick) * h * fi for pi, fi in zip(p, f)]
    return q, p


def verlet_jacobian(h, q, p, force, kick, scale=1):
    """d(q', p')/d(q, p) of verlet() (rows: q'_i then p'_i; columns: q_j then p_j), scaled as step()
    scales p'. With K = dF/dq: p_half = p + a·h·F(q), q' = q + h·p_half, p' = p_half + b·h·F(q')."""
    n, a, b = len(q), kick, 1 - kick
    q_next = verlet(h, q, p, force, kick)[0]
    K0, K1 = force.stiffness(q), force.stiffness(q_next)
    eye = lambda i, j: 1 if i == j else 0  # noqa: E731
    dhalf_dq = [[a * h * K0[i][j] for j in range(n)] for i in range(n)]  # dp_half/dq
    dq_dq = [[eye(i, j) + h * dhalf_dq[i][j] for j in range(n)] for i in range(n)]
    dq_dp = [[h * eye(i, j) for j in range(n)] for i in range(n)]
    dp_dq = [[dhalf_dq[i][j] + b * h * sum(K1[i][m] * dq_dq[m][j] for m in range(n)) for j in range(n)]
             for i in range(n)]
    dp_dp = [[eye(i, j) + b * h * sum(K1[i][m] * dq_dp[m][j] for m in range(n)) for j in range(n)]
             for i in range(n)]
    return [dq_dq[i] + dq_dp[i] for i in range(n)] + [[x * scale for x in dp_dq[i] + dp_dp[i]] for i in range(n)]


def options(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--kick", default="1/2", help="the first kick's fraction of h (1/2 is Verlet)")
    parser.add_argument("--arithmetic", default="mpmath", choices=["mpmath", "numpy"])
    parser.add_argument("--scale-momentum", default="0", help="multiply p' by 1 + S on every step")
    parser.add_argument("--shift", default="0", help="add C·h^3 to q' on every step")
    parser.add_argument("--jacobian", action="store_true",
                        help="send the map's own Jacobian (extension jacobian), derived by hand")
    parser.add_argument("--wrong-jacobian-after", type=int, default=None, metavar="K",
                        help="from the K-th Jacobian on, send dp'/dq 1 %% too large (a planted bug)")
    parser.add_argument("--count-evaluations", action="store_true",
                        help="report each step's evaluations of F (extension evaluations)")
    return parser.parse_args(argv)


def fraction(text, number):
    """'0.6' or '3/5' in the arithmetic of `number` (never through a float for mpmath)."""
    numerator, _, denominator = text.partition("/")
    return number(numerator) / number(denominator) if denominator else number(numerator)


if __name__ == "__main__":
    args = options(sys.argv[1:])
    force = Force()
    constants = {}

    def setup(system, dimension, number):
        force.setup(system, dimension, number)
        constants["kick"] = fraction(args.kick, number)
        constants["scale"] = 1 + number(args.scale_momentum)
        constants["shift"] = number(args.shift)

    def step(h, q, p):
        q, p = verlet(h, q, p, force, constants["kick"])
        return [qi + constants["shift"] * h ** 3 for qi in q], [pi * constants["scale"] for pi in p]

    sent = [0]

    def jacobian(h, q, p):
        J = verlet_jacobian(h, q, p, force, constants["kick"], constants["scale"])
        sent[0] += 1
        if args.wrong_jacobian_after is not None and sent[0] > args.wrong_jacobian_after:
            n = len(q)
            J[n][0] = J[n][0] * constants["wrong"]
        return J

    constants["wrong"] = 1.01
    vivv_map.serve(step, jacobian=jacobian if args.jacobian else None, arithmetic=args.arithmetic, setup=setup,
                   evaluations=(lambda: force.evaluations) if args.count_evaluations else None)
