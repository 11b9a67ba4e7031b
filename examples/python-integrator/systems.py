"""The forces F(q) = -grad V(q), and their derivatives K(q) = dF/dq, of the catalogue systems of the form L = |w|^2/2 - V(q) (unit mass,
so p = w), in the arithmetic the program computes in — for the example integrators' setup():

    force = systems.Force()
    serve(step, setup=force.setup)          # then force(q) inside step

Any other system is declined with the list of the known ones.
"""
import math

from vivv_map import Decline


def _functions(number):
    """sin, cos and sqrt for the arithmetic whose numbers `number` makes."""
    sample = number("1")
    if type(sample).__module__.startswith("mpmath"):
        import mpmath
        return mpmath.sin, mpmath.cos, mpmath.sqrt
    if type(sample).__name__ == "Decimal":
        raise Decline("the example systems need sin, which Python's decimal module does not have")
    return math.sin, math.cos, math.sqrt


class Force:
    """F(q) of the system vivv greets the program with; set by setup(system, dimension, number)."""

    def __init__(self):
        self.force = None
        self.evaluations = 0  # calls of F so far (reported with --count-evaluations)

    def setup(self, system, dimension, number):
        name = system.get("name")
        k = {key: number(value) for key, value in system.get("params", {}).items()}
        sin, cos, sqrt = _functions(number)
        # K(q) = dF/dq, the force's derivative (for a program that sends its own Jacobian).
        r = lambda q: sqrt(q[0] ** 2 + q[1] ** 2)  # noqa: E731
        stiffnesses = {
            ("harmonic_oscillator", 1): lambda q: [[-k["omega"] ** 2]],
            ("pendulum", 1): lambda q: [[-k["k"] * cos(q[0])]],
            ("kepler", 2): lambda q: [[-k["mu"] * ((1 if i == j else 0) / r(q) ** 3 - 3 * q[i] * q[j] / r(q) ** 5)
                                       for j in range(2)] for i in range(2)],
            ("henon_heiles", 2): lambda q: [[-1 - 2 * k["lambda"] * q[1], -2 * k["lambda"] * q[0]],
                                            [-2 * k["lambda"] * q[0], -1 + 2 * k["lambda"] * q[1]]],
        }
        forces = {
            ("harmonic_oscillator", 1): lambda q: [-k["omega"] ** 2 * q[0]],
            ("pendulum", 1): lambda q: [-k["k"] * sin(q[0])],
            ("kepler", 2): lambda q: [-k["mu"] * x / sqrt(q[0] ** 2 + q[1] ** 2) ** 3 for x in q],
            ("henon_heiles", 2): lambda q: [-q[0] - 2 * k["lambda"] * q[0] * q[1],
                                            -q[1] - k["lambda"] * (q[0] ** 2 - q[1] ** 2)],
        }
        if (name, dimension) not in forces:
            known = ", ".join(sorted(system for system, _ in forces))
            raise Decline(f"this integrator steps L = |w|^2/2 - V(q) for {known}; "
                          f"not '{name}' in {dimension} dimensions")
        self.force = forces[(name, dimension)]
        self.stiffness = stiffnesses[(name, dimension)]

    def __call__(self, q):
        self.evaluations += 1
        return self.force(q)
