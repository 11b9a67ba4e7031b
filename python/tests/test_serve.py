"""serve() against greetings and requests written here: the digits it writes in each arithmetic,
a declined greeting, the Jacobian extension taken up only when offered, an error answer."""
import io
import itertools
import json
import os
import sys

import pytest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from vivv_map import Decline, serve  # noqa: E402
from vivv_map.protocol import PROTOCOL  # noqa: E402


def talk(step, lines, **options):
    """serve()'s answers, one dict per line, to a greeting and requests."""
    output = io.StringIO()
    serve(step, input=io.StringIO("".join(json.dumps(line) + "\n" for line in lines)), output=output, **options)
    return [json.loads(line) for line in output.getvalue().splitlines()]


def greeting(digits, extensions=()):
    return {"protocol": PROTOCOL, "digits": digits, "dimension": 1, "system": {"name": "harmonic_oscillator",
                                                                               "params": {"omega": "1"}},
            **({"extensions": list(extensions)} if extensions else {})}


def euler(h, q, p):
    return [q[0] + h * p[0]], [p[0] - h * q[0]]


def significant(text):
    mantissa = text.lstrip("-").split("e")[0].replace(".", "").lstrip("0")
    return len(mantissa)


@pytest.mark.parametrize("arithmetic, digits", [("mpmath", 40), ("decimal", 40), ("float", 17), ("numpy", 17)])
def test_each_arithmetic_writes_the_digits_asked_for(arithmetic, digits):
    if arithmetic == "numpy":
        pytest.importorskip("numpy")
    if arithmetic == "mpmath":
        pytest.importorskip("mpmath")
    answers = talk(euler, [greeting(digits), {"h": "0.1", "q": ["1"], "p": ["0.5"]}], arithmetic=arithmetic)
    assert answers[0] == {"protocol": PROTOCOL}
    q, p = answers[1]["q"][0], answers[1]["p"][0]
    assert significant(q) == digits and significant(p) == digits, (q, p)
    assert float(q) == pytest.approx(1.05) and float(p) == pytest.approx(0.4)


def test_a_double_program_declines_more_digits_naming_the_case_field():
    answers = talk(euler, [greeting(44)], arithmetic="float")
    assert "error" in answers[0] and '"precision": "double"' in answers[0]["error"]


def test_another_protocol_is_declined():
    answers = talk(euler, [{"protocol": "vivv-map/2", "digits": 17, "dimension": 1, "system": {}}], arithmetic="float")
    assert answers == [{"error": f"this program speaks {PROTOCOL}, not 'vivv-map/2'"}]


def test_setup_declines_a_system_it_cannot_step():
    def setup(system, dimension, number):
        raise Decline(f"not {system['name']}")
    answers = talk(euler, [greeting(17)], arithmetic="float", setup=setup)
    assert answers == [{"error": "not harmonic_oscillator"}]


def test_the_jacobian_is_sent_only_when_offered():
    jacobian = lambda h, q, p: [[1, h], [-h, 1]]  # noqa: E731
    request = {"h": "0.5", "q": ["1"], "p": ["0"], "jacobian": True}
    offered = talk(euler, [greeting(17, ["jacobian"]), request, {**request, "jacobian": False}],
                   jacobian=jacobian, arithmetic="float")
    assert offered[0] == {"protocol": PROTOCOL, "extensions": ["jacobian"]}
    assert [[float(x) for x in row] for row in offered[1]["jacobian"]] == [[1, 0.5], [-0.5, 1]]
    assert all(significant(x) == 17 for row in offered[1]["jacobian"] for x in row)
    assert "jacobian" not in offered[2]  # sent only where vivv asks for it
    plain = talk(euler, [greeting(17), request], jacobian=jacobian, arithmetic="float")
    assert plain[0] == {"protocol": PROTOCOL} and "jacobian" not in plain[1]
    unasked = talk(euler, [greeting(17, ["jacobian"]), request], arithmetic="float")
    assert unasked[0] == {"protocol": PROTOCOL}


def test_each_answer_counts_its_evaluations_when_offered():
    made = [0]
    def counting(h, q, p):
        made[0] += 3  # three force evaluations a step
        return euler(h, q, p)
    request = {"h": "0.5", "q": ["1"], "p": ["0"]}
    answers = talk(counting, [greeting(17, ["jacobian", "evaluations"]), request, request],
                   arithmetic="float", evaluations=lambda: made[0])
    assert answers[0] == {"protocol": PROTOCOL, "extensions": ["evaluations"]}
    assert [answer["evaluations"] for answer in answers[1:]] == [3, 3]
    plain = talk(counting, [greeting(17), request], arithmetic="float", evaluations=lambda: made[0])
    assert plain[0] == {"protocol": PROTOCOL} and "evaluations" not in plain[1]  # not offered: not sent


@pytest.mark.parametrize("arithmetic, digits", [("mpmath", 40), ("float", 17), ("numpy", 17)])
def test_k_steps_in_one_request_are_the_k_single_steps(arithmetic, digits):
    pytest.importorskip(arithmetic if arithmetic != "float" else "json")
    made = [0]
    def counting(h, q, p):
        made[0] += 2
        return euler(h, q, p)
    start = {"h": "0.125", "q": ["1"], "p": ["0.5"]}
    batched = talk(counting, [greeting(digits, ["evaluations", "steps"]), {**start, "steps": 5}],
                   arithmetic=arithmetic, evaluations=lambda: made[0])
    assert batched[0] == {"protocol": PROTOCOL, "extensions": ["evaluations", "steps"]}
    assert batched[1]["steps"] == 5 and batched[1]["evaluations"] == 10
    single, state = [], start
    for _ in range(5):  # the same five steps, each crossing as text
        single = talk(euler, [greeting(digits), state], arithmetic=arithmetic)
        state = {"h": "0.125", "q": single[1]["q"], "p": single[1]["p"]}
    assert (batched[1]["q"], batched[1]["p"]) == (single[1]["q"], single[1]["p"])  # 17 digits carry a double
    q, p = 1.0, 0.5
    for _ in range(5):  # h = 1/8: every value is a short binary fraction, exact in each arithmetic
        q, p = q + p / 8, p - q / 8
    assert float(batched[1]["q"][0]) == q and float(batched[1]["p"][0]) == p


def test_steps_are_taken_up_only_when_offered_and_batch_declines_them():
    request = {"h": "0.5", "q": ["1"], "p": ["0"], "steps": 3}
    assert talk(euler, [greeting(17), request], arithmetic="float")[1].keys() == {"q", "p"}  # one step
    declined = talk(euler, [greeting(17, ["steps"]), request], arithmetic="float", batch=False)
    assert declined[0] == {"protocol": PROTOCOL} and declined[1].keys() == {"q", "p"}
    one = talk(euler, [greeting(17), {"h": "0.5", "q": ["1"], "p": ["0"]}], arithmetic="float")[1]
    assert (declined[1]["q"], declined[1]["p"]) == (one["q"], one["p"])


def test_a_state_that_leaves_the_finite_numbers_ends_the_steps_before_it():
    def explode(h, q, p):  # finite twice, then infinite
        return [q[0] * 1e200], [p[0]]
    answers = talk(explode, [greeting(17, ["steps"]), {"h": "0.5", "q": ["1"], "p": ["2"], "steps": 4}],
                   arithmetic="float")
    assert answers[1]["steps"] == 1 and float(answers[1]["q"][0]) == 1e200 and float(answers[1]["p"][0]) == 2
    for count in (0, -1, 1.5, True, "2"):
        bad = talk(euler, [greeting(17, ["steps"]), {"h": "0.5", "q": ["1"], "p": ["0"], "steps": count}],
                   arithmetic="float")
        assert "steps" in bad[1]["error"], bad[1]


def test_a_count_that_is_not_a_whole_number_or_falls_is_an_error_answer():
    request = {"h": "0.5", "q": ["1"], "p": ["0"]}
    for count, words in [(lambda: 1.5, "returned 1.5"), (lambda: True, "returned True"),
                         (lambda: "2", "returned '2'"), (lambda: -1, "returned -1")]:
        answers = talk(euler, [greeting(17, ["evaluations"]), request], arithmetic="float", evaluations=count)
        assert words in answers[1]["error"], answers[1]
    falling = iter([5, 4])
    answers = talk(euler, [greeting(17, ["evaluations"]), request], arithmetic="float",
                   evaluations=lambda: next(falling))
    assert "fell from 5 to 4" in answers[1]["error"], answers[1]


def test_an_exception_in_step_is_an_error_answer():
    def broken(h, q, p):
        raise ZeroDivisionError("h too small")
    answers = talk(broken, [greeting(17), {"h": "0.1", "q": ["1"], "p": ["0"]}], arithmetic="float")
    assert answers[1]["error"].startswith("ZeroDivisionError: h too small (at ")


def test_a_missing_library_declines_naming_the_interpreter(monkeypatch):
    monkeypatch.setitem(sys.modules, "numpy", None)  # import numpy now raises ImportError
    answers = talk(euler, [greeting(17)], arithmetic="numpy")
    assert answers[0]["error"].startswith("this program computes with numpy, which " + sys.executable)


REQUEST = {"h": "0.1", "q": ["1"], "p": ["0"]}


def returns(value):
    def my_step(h, q, p):
        return value
    return my_step


@pytest.mark.parametrize("value, says", [
    (None, "returned None; expected (q, p), each 1 real numbers"),
    (1.5, "returned 1.5; expected (q, p)"),
    ("abc", "returned 'abc'; expected (q, p)"),
    (([1.0, 2.0], [0.0]), "2 numbers where 1 belong"),
    (([None], [0.0]), "None is not a number"),
    (([1 + 2j], [0.0]), "(1+2j) is complex"),
    ((itertools.repeat(1.0), [0.0]), "more than 1 numbers where 1 belong"),  # an endless iterable, not read forever
    (([10 ** 400], [0.0]), "cannot be written as a number (OverflowError"),  # an int beyond a double's range
])
def test_a_bad_return_value_names_the_users_function_and_the_value(value, says):
    answer = talk(returns(value), [greeting(17), REQUEST], arithmetic="float")[1]["error"]
    assert "returns.<locals>.my_step (defined at " + __file__ in answer
    assert says in answer
    assert "vivv_map" not in answer.split("(defined at")[1].split(")")[0]


def test_a_numpy_complex_result_is_refused_not_truncated():
    numpy = pytest.importorskip("numpy")
    step = returns((numpy.array([1 + 1e-3j]), numpy.array([0.0])))
    answer = talk(step, [greeting(17), REQUEST], arithmetic="numpy")[1]["error"]
    assert "is complex" in answer and "imaginary part would be lost" in answer


@pytest.mark.parametrize("matrix, says", [(None, "returned None"), ([1.0, 0.0, 0.0, 1.0], "4 rows"),
                                          ([[1.0, 0.0], [0.0]], "1 numbers where 2 belong")])
def test_a_bad_jacobian_names_the_users_function(matrix, says):
    def my_jacobian(h, q, p):
        return matrix
    request = dict(REQUEST, jacobian=True)
    answers = talk(euler, [greeting(17, ["jacobian"]), request], arithmetic="float", jacobian=my_jacobian)
    assert "my_jacobian (defined at " in answers[1]["error"] and says in answers[1]["error"]


def test_sys_exit_in_the_users_step_is_an_error_answer_placed_at_its_line():
    def my_step(h, q, p):
        sys.exit(3)
    answer = talk(my_step, [greeting(17), REQUEST], arithmetic="float")[1]["error"]
    assert answer.startswith("SystemExit: 3") and f"(at {__file__}:" in answer


def test_an_error_in_the_users_code_is_placed_there_not_in_vivv_map():
    def my_step(h, q, p):
        return [q[0] / 0], [p[0]]
    answer = talk(my_step, [greeting(17), REQUEST], arithmetic="float")[1]["error"]
    assert answer.startswith("ZeroDivisionError") and f"(at {__file__}:" in answer


def test_an_error_text_with_a_lone_surrogate_is_still_json_vivv_reads():
    name = b"caf\xe9.dat".decode("utf-8", "surrogateescape")

    def my_step(h, q, p):
        raise FileNotFoundError(name)
    line = io.StringIO()
    serve(my_step, input=io.StringIO(json.dumps(greeting(17)) + "\n" + json.dumps(REQUEST) + "\n"), output=line,
          arithmetic="float")
    answer = line.getvalue().splitlines()[1]
    text = json.loads(answer)["error"]
    assert not any(0xD800 <= ord(c) <= 0xDFFF for c in text)  # a strict JSON reader takes the line
    assert "caf\\xe9.dat" in text


def test_what_the_users_code_prints_goes_to_standard_error():
    import subprocess
    program = (
        "import sys\n"
        f"sys.path.insert(0, {os.path.join(os.path.dirname(os.path.abspath(__file__)), '..')!r})\n"
        "from vivv_map import serve\n"
        "def setup(system, n, number):\n    print('setting up', n)\n"
        "def step(h, q, p):\n    print('debug', q)\n    return [q[0] + h * p[0]], [p[0] - h * q[0]]\n"
        "serve(step, arithmetic='float', setup=setup)\n")
    lines = json.dumps(greeting(17)) + "\n" + json.dumps(REQUEST) + "\n"
    done = subprocess.run([sys.executable, "-c", program], input=lines, capture_output=True, text=True, timeout=60)
    answers = [json.loads(line) for line in done.stdout.splitlines()]
    assert answers[0] == {"protocol": PROTOCOL} and set(answers[1]) == {"q", "p"}
    assert "setting up 1" in done.stderr and "debug [1.0]" in done.stderr


def test_numpy_arrays_are_read_whole_and_still_checked_by_their_dtype():
    # A real array of the right shape is taken by its dtype (no element-by-element checks: a 228 x 228
    # Jacobian's took 20 times the program's step); anything else still takes the checked way.
    numpy = pytest.importorskip("numpy")
    request = dict(REQUEST, jacobian=True)
    good = talk(returns((numpy.array([1.5]), numpy.array([-0.25]))), [greeting(17, ["jacobian"]), request],
                arithmetic="numpy", jacobian=lambda h, q, p: numpy.array([[1.0, 0.5], [-0.5, 1.0]]))[1]
    assert [float(x) for x in good["q"] + good["p"]] == [1.5, -0.25]
    assert [[float(x) for x in row] for row in good["jacobian"]] == [[1, 0.5], [-0.5, 1]]
    assert all(significant(x) == 17 for row in good["jacobian"] for x in row)
    for value, says in [((numpy.array([1.0, 2.0]), numpy.array([0.0])), "2 numbers where 1 belong"),
                        ((numpy.array([True]), numpy.array([0.0])), "is not a number"),
                        ((numpy.array(["1.0"]), numpy.array([0.0])), "is not a number"),
                        ((numpy.array([1.0], dtype=object), numpy.array([None], dtype=object)), "None is not a number")]:
        answer = talk(returns(value), [greeting(17), REQUEST], arithmetic="numpy")[1]
        assert says in answer.get("error", ""), (value, answer)
    wrong_shape = talk(euler, [greeting(17, ["jacobian"]), request], arithmetic="numpy",
                       jacobian=lambda h, q, p: numpy.eye(3))[1]
    assert "3 rows" in wrong_shape.get("error", ""), wrong_shape


@pytest.mark.parametrize("arithmetic, digits", [("mpmath", 40), ("float", 17), ("numpy", 17)])
def test_trajectory_answers_every_state_of_the_steps(arithmetic, digits):
    pytest.importorskip(arithmetic if arithmetic != "float" else "json")
    start = {"h": "0.125", "q": ["1"], "p": ["0.5"]}
    answers = talk(euler, [greeting(digits, ["steps", "trajectory"]), {**start, "steps": 4, "trajectory": True},
                           {**start, "steps": 4}], arithmetic=arithmetic)
    assert answers[0] == {"protocol": PROTOCOL, "extensions": ["steps", "trajectory"]}
    states, state = answers[1]["trajectory"], start
    assert len(states) == 4 and answers[1]["steps"] == 4
    for row in states:  # each the single step from the one before, as text
        single = talk(euler, [greeting(digits), state], arithmetic=arithmetic)[1]
        assert row == single["q"] + single["p"]
        state = {"h": "0.125", "q": single["q"], "p": single["p"]}
    assert states[-1] == answers[1]["q"] + answers[1]["p"]
    assert "trajectory" not in answers[2]  # only where the request asks for it


def test_trajectory_is_taken_up_only_with_steps_and_ends_where_the_steps_end():
    request = {"h": "0.5", "q": ["1"], "p": ["2"], "steps": 4, "trajectory": True}
    assert talk(euler, [greeting(17, ["trajectory"]), request], arithmetic="float")[0] == {"protocol": PROTOCOL}
    assert talk(euler, [greeting(17, ["steps", "trajectory"]), request], arithmetic="float",
                batch=False)[0] == {"protocol": PROTOCOL}

    def explode(h, q, p):  # finite twice, then infinite
        return [q[0] * 1e200], [p[0]]
    answers = talk(explode, [greeting(17, ["steps", "trajectory"]), request], arithmetic="float")
    assert answers[1]["steps"] == 1 and len(answers[1]["trajectory"]) == 1
    assert answers[1]["trajectory"][0] == answers[1]["q"] + answers[1]["p"]


def test_pipeline_is_taken_up_and_requests_sent_ahead_are_answered_in_order():
    """Through real pipes: 8 requests written before any answer is read, answered in their order
    with what each alone gets."""
    import subprocess
    assert talk(euler, [greeting(17, ["pipeline"])], arithmetic="float")[0] == {
        "protocol": PROTOCOL, "extensions": ["pipeline"]}
    program = ("import sys; sys.path.insert(0, %r)\n"
               "from vivv_map import serve\n"
               "serve(lambda h, q, p: ([q[0] + h * p[0]], [p[0] - h * q[0]]), arithmetic='float')\n"
               % os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    requests = [{"h": "0.125", "q": [repr(0.1 * k)], "p": ["0.5"]} for k in range(1, 9)]
    child = subprocess.Popen([sys.executable, "-c", program], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    child.stdin.write(json.dumps(greeting(17, ["pipeline"])) + "\n")
    child.stdin.flush()
    assert json.loads(child.stdout.readline())["extensions"] == ["pipeline"]
    child.stdin.write("".join(json.dumps(request) + "\n" for request in requests))
    child.stdin.flush()
    answers = [json.loads(child.stdout.readline()) for _ in requests]
    child.stdin.close()
    assert child.wait(timeout=10) == 0
    for request, answer in zip(requests, answers):
        assert answer == talk(euler, [greeting(17), request], arithmetic="float")[1]


def test_a_step_with_a_parameter_t_is_given_the_time_of_each_state():
    """A request's "t" (a Lagrangian that depends on time) reaches a step(h, q, p, t): at t for one
    step, at t, t + h, … for the k steps of one request; a step without t is called as before, and
    a step with t=0 keeps its default where a request carries no time."""
    times = []

    def timed(h, q, p, t=0):
        times.append(t)
        return [q[0] + h * p[0]], [p[0] + h * t]

    answers = talk(timed, [greeting(17, ["steps"]), {"h": "0.25", "t": "2", "q": ["1"], "p": ["0"]},
                           {"h": "0.25", "t": "3", "q": ["1"], "p": ["0"], "steps": 3},
                           {"h": "0.25", "q": ["1"], "p": ["0"]}], arithmetic="float")
    assert times == [2.0, 3.0, 3.25, 3.5, 0]
    assert float(answers[1]["p"][0]) == 0.5
    assert float(answers[2]["p"][0]) == pytest.approx(0.25 * (3 + 3.25 + 3.5))
    untimed = talk(euler, [greeting(17), {"h": "0.1", "t": "5", "q": ["1"], "p": ["0.5"]}], arithmetic="float")
    assert float(untimed[1]["q"][0]) == pytest.approx(1.05)
