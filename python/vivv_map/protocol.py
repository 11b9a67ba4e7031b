"""The loop of protocol vivv-map/1 (docs/process-protocol.md in vivv's source tree).

    vivv:    {"protocol": "vivv-map/1", "digits": D, "dimension": n, "system": {...},
              "extensions": ["jacobian", "evaluations", "steps", "trajectory", "pipeline"]}
    program: {"protocol": "vivv-map/1"}   or, sending its own Jacobian or its count of evaluations,
             or taking several steps a request (and answering every state of them), or reading
             requests sent before their answers are read,
             {"protocol": "vivv-map/1", "extensions": ["jacobian", "evaluations", "steps", "trajectory", "pipeline"]}
             (or {"error": "why not"})
    vivv:    {"h": "...", "q": ["...", ...], "p": ["...", ...]}   (+ "t": the first state's time, for an L
                                                                   that depends on time,
                                                                   + "jacobian": true where it reads one,
                                                                   + "steps": k for k steps, when agreed,
                                                                   + "trajectory": true for every state)
    program: {"q": [...], "p": [...]}   (+ "jacobian": [[...], ...] when agreed and asked for,
                                          + "evaluations": k, the step's count, when agreed,
                                          + "steps": m, the steps taken, m < k only where a state
                                            left the finite numbers: the state before it,
                                          + "trajectory": [[q..., p...], ...], the m states reached,
                                            when agreed and asked for)

until vivv closes the program's input. Numbers are decimal strings with at least D significant
digits.
"""
import inspect
import io
import json
import itertools as _itertools
import numbers as _numbers
import os
import sys
import traceback

from .arithmetic import arithmetic_named

PROTOCOL = "vivv-map/1"
JACOBIAN = "jacobian"
EVALUATIONS = "evaluations"
STEPS = "steps"
TRAJECTORY = "trajectory"
PIPELINE = "pipeline"


class Decline(Exception):
    """Raised by setup() when the program cannot step the system vivv greets it with: vivv ends
    the case with this reason."""


def _reply(output, message):
    # ensure_ascii writes a lone surrogate (a file name decoded with surrogateescape) as \udcxx,
    # which no JSON reader takes; such a character is written as its escape's text instead.
    text = json.dumps(message)
    if "\\ud" in text:
        text = json.dumps(_without_surrogates(message))
    output.write(text + "\n")
    output.flush()


def _reply_answer(output, answer):
    """An answer of numbers written as decimal strings ("q", "p", "jacobian": lists of them; "evaluations":
    a count) as one JSON line, joined directly where every string is plain text that needs no escape:
    json.dumps escapes string by string, which at a 228 x 228 Jacobian cost more than the program's
    own step and Jacobian together. Anything else goes through json.dumps as before."""
    parts = []
    for key, value in answer.items():
        if key in (EVALUATIONS, STEPS):
            parts.append(json.dumps(key) + ": " + json.dumps(value))
            continue
        rows = value if key in (JACOBIAN, TRAJECTORY) else [value]
        joined = ['["' + '", "'.join(row) + '"]' if row else "[]" for row in rows]
        text = ", ".join(joined)
        if not text.isascii() or "\\" in text or text.count('"') != 2 * sum(len(row) for row in rows) or \
                not text.isprintable():
            _reply(output, answer)
            return
        parts.append(json.dumps(key) + ": " + ("[" + text + "]" if key in (JACOBIAN, TRAJECTORY) else text))
    output.write("{" + ", ".join(parts) + "}\n")
    output.flush()


def _without_surrogates(value):
    if isinstance(value, str):
        try:  # bytes decoded with surrogateescape: their own escapes, \xe9
            return value.encode("utf-8", "surrogateescape").decode("utf-8", "backslashreplace")
        except UnicodeEncodeError:  # any other lone surrogate: \ud800
            return value.encode("utf-8", "backslashreplace").decode("utf-8")
    if isinstance(value, dict):
        return {_without_surrogates(k): _without_surrogates(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_without_surrogates(v) for v in value]
    return value


def _protocol_channel():
    """The process's standard output kept for the protocol alone: file descriptor 1 becomes a copy
    of standard error, so that whatever the user's code prints — print(), a library's C code —
    reaches vivv's record of the program's standard error instead of breaking the protocol."""
    sys.stdout.flush()
    channel = os.dup(1)
    os.dup2(2, 1)
    return io.TextIOWrapper(os.fdopen(channel, "wb", buffering=0), encoding="utf-8", newline="\n",
                            write_through=True)


class BadAnswer(Exception):
    """A value the user's step() or jacobian() returned that is not what the protocol carries."""


def _where(function):
    """"name (defined at file:line)" for the user's function."""
    name = getattr(function, "__qualname__", None) or getattr(function, "__name__", None) or repr(function)
    try:
        return f"{name} (defined at {inspect.getsourcefile(function)}:{inspect.getsourcelines(function)[1]})"
    except (TypeError, OSError):
        return name


def _shown(value):
    text = repr(value)
    return text if len(text) <= 200 else text[:200] + "…"


def _real_array(values, shape):
    """A NumPy array of real numbers (integer or floating dtype) of `shape` as nested lists of Python
    numbers, or None for anything else (which takes the checked way, element by element). Its dtype
    vouches for every element: at n = 114 the checks of a Jacobian's 52 000 entries one by one took
    20 times the program's own step and Jacobian."""
    dtype = getattr(values, "dtype", None)
    if dtype is None or getattr(dtype, "kind", None) not in ("f", "i", "u") or getattr(values, "shape", None) != shape:
        return None
    return values.tolist()


def _real_numbers(values, size, what, function, returned):
    """`values` as a list of `size` real numbers, or BadAnswer naming the function and the value."""
    fast = _real_array(values, (size,))
    if fast is not None:
        return fast
    expected = f"expected {what}"
    if isinstance(values, (str, bytes)) or values is None or not hasattr(values, "__iter__"):
        raise BadAnswer(f"{_where(function)} returned {_shown(returned)}; {expected}")
    sized = hasattr(values, "__len__")
    values = list(values) if sized else list(_itertools.islice(values, size + 1))  # an endless one is not read forever
    if len(values) != size:
        count = f"more than {size}" if not sized and len(values) > size else str(len(values))
        raise BadAnswer(f"{_where(function)} returned {_shown(returned)}: {count} numbers where "
                        f"{size} belong; {expected}")
    for x in values:
        kind = type(x).__name__
        if isinstance(x, (bool, str, bytes)) or x is None or kind in ("bool_", "bool"):  # NumPy's bool too
            raise BadAnswer(f"{_where(function)} returned {_shown(returned)}: {_shown(x)} is not a number; {expected}")
        if isinstance(x, _numbers.Complex) and not isinstance(x, _numbers.Real) or "complex" in kind:
            raise BadAnswer(f"{_where(function)} returned {_shown(returned)}: {_shown(x)} is complex; {expected} "
                            "(real: a complex value's imaginary part would be lost)")
        if not isinstance(x, _numbers.Real) and not hasattr(x, "__float__"):
            raise BadAnswer(f"{_where(function)} returned {_shown(returned)}: {_shown(x)} ({kind}) is not a "
                            f"number; {expected}")
    return values


def _state(result, dimension, function):
    what = f"(q, p), each {dimension} real numbers"
    if isinstance(result, (str, bytes)) or not hasattr(result, "__len__") or len(result) != 2:
        raise BadAnswer(f"{_where(function)} returned {_shown(result)}; expected {what}")
    q, p = result
    return (_real_numbers(q, dimension, what, function, result), _real_numbers(p, dimension, what, function, result))


def _matrix(result, size, function):
    what = f"a {size} x {size} matrix d(q', p')/d(q, p): {size} rows of {size} real numbers"
    fast = _real_array(result, (size, size))
    if fast is not None:
        return fast
    if isinstance(result, (str, bytes)) or result is None or not hasattr(result, "__iter__"):
        raise BadAnswer(f"{_where(function)} returned {_shown(result)}; expected {what}")
    rows = list(result)
    if len(rows) != size:
        raise BadAnswer(f"{_where(function)} returned {_shown(result)}: {len(rows)} rows; expected {what}")
    return [_real_numbers(row, size, what, function, result) for row in rows]


def _written(values, numbers, function, returned):
    """`values` as the arithmetic's decimal strings, or BadAnswer naming the function and the value
    that has none (an int beyond a double's range, an object whose conversion raises)."""
    try:  # all at once; the value at fault is found one by one below
        return numbers.texts(values)
    except (ArithmeticError, ValueError, TypeError):
        pass
    text = []
    for x in values:
        try:
            text.append(numbers.text(x))
        except (ArithmeticError, ValueError, TypeError) as error:
            raise BadAnswer(f"{_where(function)} returned {_shown(returned)}: {_shown(x)} cannot be written as a "
                            f"number ({type(error).__name__}: {error})") from None
    return text


def serve(step, jacobian=None, *, arithmetic="mpmath", setup=None, evaluations=None, batch=True, input=None,
          output=None):
    """Answer vivv's requests with step(h, q, p) -> (q', p') until vivv closes the input.

    A step (and a jacobian) with a parameter named t is called step(h, q, p, t=t) with the time of
    the state it steps from, for a case whose Lagrangian depends on time (vivv's requests carry
    "t"); the k steps of one request are at t, t + h, …, t + (k − 1)h. Without such a parameter it is
    called as before, and a request's "t" is not read.

    arithmetic: "mpmath" (mp.dps = D), "decimal" (the context's precision = D), "float" or
    "numpy" (IEEE double; the case declares "precision": "double"; q and p are NumPy arrays
    with "numpy"). jacobian(h, q, p), if given, returns the 2n x 2n matrix d(q', p')/d(q, p)
    (row i: the derivatives of the i-th component of (q', p') with respect to (q, p)), sent with
    each answer to a request marked "jacobian": true when vivv offers the extension. setup(system, dimension, number), if given, is
    called once with the greeting's system (a dict: "name", "params" — a decimal string per name, a
    list of them, in the case's order, for a family such as masses m — or a formula's fields), the
    dimension n and number(text) converting a decimal string to the arithmetic's numbers; it
    raises Decline(reason) for a system the program cannot step. evaluations(), if given, returns
    how many evaluations (of the forces, or of L) the program has made so far, a whole number: each
    answer then says how many its step made (extension "evaluations"), and the report's
    work-precision diagram draws the program by that count instead of leaving it out. An exception
    in step() or jacobian() is sent to vivv as an error answer with its traceback's last line.
    batch (default True) takes up the extension "steps": vivv may then ask for k steps in one request
    (a run whose states in between no claim reads), and step() is called k times here, only the
    last state crossing the pipe; a state that leaves the finite numbers ends the k early (vivv then
    steps that run one request a step). With it the extension "trajectory" is taken up too: a request
    that asks for it is answered with every state of its k steps (the claims that read them all:
    energy-behaviour, discrete-noether, symplecticity). batch=False declines both: every step crosses.
    """
    step_takes_time, jacobian_takes_time = _takes_time(step), jacobian is not None and _takes_time(jacobian)
    input = sys.stdin if input is None else input
    output = _protocol_channel() if output is None else output
    numbers = arithmetic_named(arithmetic)
    greeting = json.loads(input.readline() or "null")
    if not isinstance(greeting, dict) or greeting.get("protocol") != PROTOCOL:
        protocol = greeting.get("protocol") if isinstance(greeting, dict) else greeting
        _reply(output, {"error": f"this program speaks {PROTOCOL}, not {protocol!r}"})
        return 1
    digits, dimension = int(greeting["digits"]), int(greeting["dimension"])
    reason = numbers.start(digits)
    if reason is None and setup is not None:
        try:
            setup(greeting.get("system", {}), dimension, numbers.number)
        except Decline as decline:
            reason = str(decline)
    if reason is not None:
        _reply(output, {"error": reason})
        return 1
    offered = greeting.get("extensions", [])
    send_jacobian = jacobian is not None and JACOBIAN in offered
    send_evaluations = evaluations is not None and EVALUATIONS in offered
    take_steps = batch and STEPS in offered
    take_trajectory = take_steps and TRAJECTORY in offered
    # This loop reads a request a line at a time and answers each before it reads the next, so
    # vivv may send the next ones before the first is answered (extension "pipeline").
    take_pipeline = PIPELINE in offered
    taken = [name for name, taken in ((JACOBIAN, send_jacobian), (EVALUATIONS, send_evaluations),
                                      (STEPS, take_steps), (TRAJECTORY, take_trajectory),
                                      (PIPELINE, take_pipeline)) if taken]
    _reply(output, {"protocol": PROTOCOL, **({"extensions": taken} if taken else {})})
    for line in input:
        request = json.loads(line)
        h = numbers.number(request["h"])
        q = numbers.vector(numbers.numbers(request["q"]))
        p = numbers.vector(numbers.numbers(request["p"]))
        t = numbers.number(request["t"]) if "t" in request else None
        count = request.get(STEPS, 1) if take_steps else 1
        if isinstance(count, bool) or not isinstance(count, int) or count < 1:
            _reply(output, {"error": f"a request's \"steps\" is {count!r}: expected a whole number, 1 or more"})
            return 1
        every = take_trajectory and request.get(TRAJECTORY) is True  # answer every state of the count
        try:
            before = _count(evaluations) if send_evaluations else 0
            x, taken_steps, states = (q, p), 0, []
            while True:  # count steps from (q, p); the states between them stay here
                result = step(h, *x, t=t + taken_steps * h) if step_takes_time and t is not None else step(h, *x)
                q_next, p_next = _state(result, dimension, step)
                if count > 1 and not (numbers.finite(q_next) and numbers.finite(p_next)):
                    q_next, p_next, result = list(x[0]), list(x[1]), x  # the state before it; vivv steps one by one
                    break
                taken_steps += 1
                if every:
                    states.append(_written(q_next, numbers, step, result) + _written(p_next, numbers, step, result))
                if taken_steps == count:
                    break
                x = (numbers.vector(q_next), numbers.vector(p_next))
            answer = {"q": _written(q_next, numbers, step, result), "p": _written(p_next, numbers, step, result)}
            if STEPS in request and take_steps:
                answer[STEPS] = taken_steps
            if every:
                answer[TRAJECTORY] = states
            if send_evaluations:
                made = _count(evaluations) - before
                if made < 0:
                    raise BadAnswer(f"evaluations() fell from {before} to {before + made} across one step(): "
                                    "it must count up (the evaluations made so far)")
                answer[EVALUATIONS] = made
            if send_jacobian and request.get(JACOBIAN) is True:  # vivv asks where it reads one
                matrix = jacobian(h, q, p, t=t) if jacobian_takes_time and t is not None else jacobian(h, q, p)
                answer[JACOBIAN] = [_written(row, numbers, jacobian, matrix)
                                    for row in _matrix(matrix, 2 * dimension, jacobian)]
        except BadAnswer as bad:  # what the user's function returned, named with the function
            _reply(output, {"error": str(bad)})
            return 1
        except (Exception, SystemExit) as error:  # the user's code (sys.exit() in step() too): named, with its line
            _reply(output, {"error": _described(error)})
            return 1
        _reply_answer(output, answer)
    return 0


def _takes_time(function):
    """Whether `function` has a parameter named t that a keyword can fill (step(h, q, p, t))."""
    try:
        parameter = inspect.signature(function).parameters.get("t")
    except (TypeError, ValueError):  # a builtin without a signature: it takes no time
        return False
    return parameter is not None and parameter.kind in (inspect.Parameter.POSITIONAL_OR_KEYWORD,
                                                        inspect.Parameter.KEYWORD_ONLY)


def _count(evaluations):
    """evaluations()'s value, a whole number (a bool or a float is refused, as vivv would)."""
    value = evaluations()
    if isinstance(value, bool) or not isinstance(value, _numbers.Integral) or value < 0:
        raise BadAnswer(f"evaluations() returned {value!r}: it must return the evaluations made so far, "
                        "a whole number, 0 or more")
    return int(value)


def _described(error):
    """The exception and the line of the user's code it came from (the innermost frame outside
    vivv_map), so that an error is never blamed on this package's own lines."""
    frames = traceback.extract_tb(error.__traceback__)
    package = os.path.dirname(os.path.abspath(__file__))
    user = [f for f in frames if not os.path.abspath(f.filename).startswith(package + os.sep)]
    where = (user or frames)[-1]
    return f"{type(error).__name__}: {error} (at {where.filename}:{where.lineno})"
