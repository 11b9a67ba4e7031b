"""The arithmetics a map program can compute in: how a decimal string becomes a number, how a
number is written back with D significant digits, and the precision each can carry."""
import decimal
import math
import sys

DOUBLE_DIGITS = 17  # the significant digits that carry a double exactly (what vivv asks of one)


def _library(name, package):
    """The module `name`, or None with why not: the message a greeting is declined with."""
    try:
        return __import__(name), None
    except ImportError:
        return None, f"this program computes with {name}, which {sys.executable} cannot import (Debian: {package})"


def _finite(x):
    try:
        return math.isfinite(float(x))
    except (ArithmeticError, ValueError, TypeError):
        return False


class Arithmetic:
    """name; start(digits) sets the working precision (None, or why it cannot be carried);
    number(text) reads a decimal string; text(x) writes x with the digits asked for;
    vector(values) what step() receives (a list, or a NumPy array)."""

    name = "abstract"

    def start(self, digits):
        self.digits = digits
        return None

    def vector(self, values):
        return list(values)

    def numbers(self, texts):
        """The decimal strings `texts` read as numbers, in order."""
        return [self.number(t) for t in texts]

    def texts(self, values):
        """Each of `values` written as text(x) does; raises what text() raises."""
        return [self.text(x) for x in values]

    def finite(self, values):
        """Whether every one of `values` is a finite number a double can hold (a larger one counts as not:
        vivv then steps the run one request a step, and judges each state itself)."""
        return all(map(_finite, values))


class MpmathArithmetic(Arithmetic):
    name = "mpmath"

    def start(self, digits):
        self.mpmath, reason = _library("mpmath", "python3-mpmath")
        if reason:
            return reason
        self.mpmath.mp.dps = digits
        return super().start(digits)

    def number(self, text):
        return self.mpmath.mpf(text)

    def text(self, x):
        return self.mpmath.nstr(self.mpmath.mpf(x), self.digits, strip_zeros=False, min_fixed=1, max_fixed=0)


class DecimalArithmetic(Arithmetic):
    name = "decimal"

    def start(self, digits):
        decimal.getcontext().prec = digits
        return super().start(digits)

    def number(self, text):
        return +decimal.Decimal(text)  # rounded to the context's precision

    def text(self, x):
        return format(+decimal.Decimal(x), "." + str(self.digits - 1) + "e")


class FloatArithmetic(Arithmetic):
    """Python floats (IEEE double): a program that computes in double and can carry 17 digits at
    most. Its case declares "precision": "double", so that vivv greets every instance with 17."""

    name = "float"

    def start(self, digits):
        if digits > DOUBLE_DIGITS:
            return (f"this program computes in double precision ({self.name}: {DOUBLE_DIGITS} significant "
                    f"digits at most) and the greeting asked for {digits}; give its case "
                    "\"precision\": \"double\" beside \"command\" (vivv then greets every instance with 17 "
                    "digits and differentiates the map at widths a double resolves)")
        return super().start(digits)

    def number(self, text):
        return float(text)

    def text(self, x):
        return "%.*e" % (self.digits - 1, float(x))

    # The same as number() and text() element by element, at C speed: at n = 114 (a 38-atom cluster)
    # the loop of Python calls had been most of a request's cost on the program's side and 15 times
    # the program's own Jacobian (bench/process_program.py).
    def numbers(self, texts):
        return list(map(float, texts))

    def texts(self, values):
        return list(map(("%." + str(self.digits - 1) + "e").__mod__, map(float, values)))


class NumpyArithmetic(FloatArithmetic):
    """Float arithmetic with q and p given to step() as NumPy float64 arrays."""

    name = "numpy"

    def start(self, digits):
        self.numpy, reason = _library("numpy", "python3-numpy")
        if reason:
            return reason
        return super().start(digits)

    def vector(self, values):
        return self.numpy.array(values if isinstance(values, list) else list(values), dtype=self.numpy.float64)


ARITHMETICS = {a.name: a for a in (MpmathArithmetic, DecimalArithmetic, FloatArithmetic, NumpyArithmetic)}


def arithmetic_named(name):
    if name not in ARITHMETICS:
        raise ValueError(f"unknown arithmetic {name!r}: one of {', '.join(sorted(ARITHMETICS))}")
    return ARITHMETICS[name]()
