"""Stormer-Verlet for the chain of tests/chain_formula.hpp, any number of coordinates, in mpmath at
the digits the greeting asks for: the map program of process_map_test.cpp (ProcessMap at 1, 2, 7
and 64 coordinates in four scalars).

    L = sum w_i^2/2 - sum (q_{i+1} - q_i)^2/2 - (q_1^2 + q_n^2)/2 - sum q_i^4/4,   p = w

--h-factor F takes F h where h belongs in the drift (the negative: F = 1.001).
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "python"))
import vivv_map  # noqa: E402

factor = float(sys.argv[2]) if len(sys.argv) > 2 and sys.argv[1] == "--h-factor" else None


def force(q):
    """-dV/dq for the chain with fixed ends and the quartic on-site term."""
    n = len(q)
    f = [-x ** 3 for x in q]
    for i in range(n):
        left = q[i - 1] if i > 0 else 0
        right = q[i + 1] if i + 1 < n else 0
        f[i] += (left - q[i]) + (right - q[i])
    return f


def step(h, q, p):
    drift = h if factor is None else h * vivv_map_number(factor)
    f = force(q)
    half = [p_i + h / 2 * f_i for p_i, f_i in zip(p, f)]
    q_next = [q_i + drift * m_i for q_i, m_i in zip(q, half)]
    f = force(q_next)
    return q_next, [m_i + h / 2 * f_i for m_i, f_i in zip(half, f)]


def vivv_map_number(x):
    import mpmath
    return mpmath.mpf(repr(x))


if __name__ == "__main__":
    sys.exit(vivv_map.serve(step, arithmetic="mpmath"))
