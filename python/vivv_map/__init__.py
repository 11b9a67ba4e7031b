"""Serve a one-step map to vivv over protocol vivv-map/1, and run vivv from a test suite.

    from vivv_map import serve

    def step(h, q, p):          # one step of your integrator on (q, p)
        ...
        return q_next, p_next

    serve(step)                 # mpmath at the digits vivv asks for
    serve(step, arithmetic="numpy")   # a double-precision program (its case: "precision": "double")

serve() reads vivv's greeting, sets the working precision, converts every number of each
request to the arithmetic's numbers, calls step(h, q, p) and writes each component back with
the significant digits vivv asked for, trailing zeros included. Given jacobian(h, q, p) — the
2n x 2n matrix d(q', p')/d(q, p), row i the derivatives of the i-th component of (q', p') —
it also sends that matrix with each answer (extension "jacobian"), and vivv's symplecticity
check uses it instead of differentiating the program.

vivv_map.testing runs vivv on a case and returns its verdicts, for a pytest suite that guards
an integrator (and its error constants, with a baseline report).
"""
from .protocol import PROTOCOL, Decline, serve

__all__ = ["PROTOCOL", "Decline", "serve"]
__version__ = "0.1.0"
