// A recording scalar and the expression tape it writes (Taylor mode, issue 3).
//
// TapeScalar<T> is a scalar that, instead of computing, appends the operation
// to the tape of the active TapeRecording: a straight-line program
//   node_i = op_i(node_a, node_b)   (i > a, b)
// over the inputs x_0 … x_{m−1}. Evaluating a Lagrangian with
// S = Jet<TapeScalar<T>, 2n> records L and its first and second derivatives
// (core/autodiff/jet.hpp), so any expression built from them — the Euler–Lagrange
// acceleration — becomes a tape, on which core/autodiff/taylor_expansion.hpp runs the
// Taylor recurrences.
//
// While recording, constants are folded (c ∘ c is computed in T), the
// identities x + 0 = x, x·1 = x, x·0 = 0, x·(−1) = −x, −(−x) = x are applied,
// operations with one constant operand become their own cheaper ops
// (x + c, c − x, c·x, c / x), equal subexpressions share one node, and
// prune() drops every node the outputs do not depend on. sin(x) and cos(x)
// are recorded as one pair (their recurrences need each other).
//
// A tape records one path through the program: L must not branch on the
// values of q or w (TapeScalar has no comparisons, so such an L fails to
// compile).
#pragma once

#include <cassert>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/autodiff/jet.hpp"
#include "core/autodiff/tape_ceiling.hpp"
#include "core/numerics/scalar.hpp"

namespace vivv {

// Operations of the tape. `a`, `b` are node indices, `c` an index into the constants.
enum class TapeOp : unsigned char {
  input,           // x_a
  constant,        // c
  add,             // a + b
  sub,             // a − b
  neg,             // −a
  mul,             // a · b
  square,          // a · a
  div,             // a / b
  add_constant,    // a + c
  constant_minus,  // c − a
  scale,           // c · a
  constant_div,    // c / a
  sin,             // sin a; the next node is its cos partner
  cos,             // cos a; computed with the sin node just before it
  exp,             // e^a
  log,             // ln a
  sqrt,            // √a
  pow,             // a^c (constant exponent)
  atan,            // atan a; b is the node 1 + a·a its recurrences divide by
};

struct TapeNode {
  TapeOp op;
  int a = -1;
  int b = -1;
  int c = -1;
};

// A straight-line program over `inputs` variables with a list of outputs.
template <class T>
struct Tape {
  int inputs = 0;
  std::vector<TapeNode> nodes;  // the first `inputs` nodes are the inputs, in order
  std::vector<T> constants;
  std::vector<int> outputs;  // node indices

  // Number of nodes that are neither inputs nor constants.
  int operations() const {
    int count = 0;
    for (const auto& node : nodes)
      if (node.op != TapeOp::input && node.op != TapeOp::constant) ++count;
    return count;
  }

  // Evaluates the outputs at x in any scalar S (T, a jet over T, a TapeScalar...).
  template <class S>
  std::vector<S> evaluate(const std::vector<S>& x) const;
  // The first output at x (`inputs` values from x[0]), in any scalar S.
  template <class S>
  S evaluate_first(const S* x) const;
  // Every node's value at x, into value[0 … nodes − 1] (grown to the tape if shorter).
  template <class S>
  void run(const S* x, std::vector<S>& value) const;

  // Drops the nodes no output depends on (keeping inputs and sin/cos pairs whole).
  void prune();
};

template <class T>
class TapeScalar;

// The tape TapeScalar operations append to; one active per thread, scoped.
template <class T>
class TapeRecording {
 public:
  // Starts recording a tape with `inputs` variables.
  explicit TapeRecording(int inputs) : previous_(active_) {
    tape_.inputs = inputs;
    for (int i = 0; i < inputs; ++i) tape_.nodes.push_back({TapeOp::input, i, -1, -1});
    active_ = this;
  }
  ~TapeRecording() { active_ = previous_; }
  TapeRecording(const TapeRecording&) = delete;
  TapeRecording& operator=(const TapeRecording&) = delete;

  // The variable x_i.
  TapeScalar<T> input(int i) const;

  // Ends the recording: the tape with `outputs`, pruned to what they need.
  Tape<T> finish(const std::vector<TapeScalar<T>>& outputs);

  static TapeRecording& active() {
    if (!active_) throw std::logic_error("TapeScalar used outside a TapeRecording");
    return *active_;
  }

  // Index of node op(a, b, c), shared with an equal node recorded before.
  int record(TapeOp op, int a, int b = -1, int c = -1) {
    if (op == TapeOp::add || op == TapeOp::mul) {
      if (a > b) std::swap(a, b);  // commutative: one node for a ∘ b and b ∘ a
    }
    auto key = std::make_tuple(static_cast<int>(op), a, b, c);
    auto found = memo_.find(key);
    if (found != memo_.end()) return found->second;
    int index = static_cast<int>(tape_.nodes.size());
    if (tape_detail::node_ceiling && tape_.nodes.size() + 2 > tape_detail::node_ceiling)
      throw TapeCeilingReached(tape_detail::node_ceiling);
    if (op == TapeOp::sin || op == TapeOp::cos) {
      // One pair (sin a, cos a) at (index, index + 1), whichever was asked first.
      tape_.nodes.push_back({TapeOp::sin, a, -1, -1});
      tape_.nodes.push_back({TapeOp::cos, a, -1, -1});
      memo_[std::make_tuple(static_cast<int>(TapeOp::sin), a, -1, -1)] = index;
      memo_[std::make_tuple(static_cast<int>(TapeOp::cos), a, -1, -1)] = index + 1;
      return op == TapeOp::sin ? index : index + 1;
    }
    tape_.nodes.push_back({op, a, b, c});
    memo_[key] = index;
    return index;
  }

  // Index of constant c in the pool (equal constants share one entry).
  int constant(const T& value) {
    for (std::size_t i = 0; i < tape_.constants.size(); ++i)
      if (tape_.constants[i] == value) return static_cast<int>(i);
    tape_.constants.push_back(value);
    return static_cast<int>(tape_.constants.size()) - 1;
  }

  const Tape<T>& tape() const { return tape_; }

 private:
  Tape<T> tape_;
  std::map<std::tuple<int, int, int, int>, int> memo_;
  TapeRecording* previous_;
  static thread_local TapeRecording* active_;
};

template <class T>
thread_local TapeRecording<T>* TapeRecording<T>::active_ = nullptr;

// A value on the active tape: node `node`, or the constant `value` when node < 0.
template <class T>
class TapeScalar {
 public:
  TapeScalar() : value_(0) {}
  TapeScalar(const T& constant) : value_(constant) {}  // NOLINT: constants promote
  template <class I, std::enable_if_t<std::is_integral_v<I>, int> = 0>
  TapeScalar(I constant) : value_(constant) {}  // NOLINT

  static TapeScalar node(int index) {
    TapeScalar x;
    x.node_ = index;
    return x;
  }

  bool is_constant() const { return node_ < 0; }
  bool is_constant(int c) const { return node_ < 0 && value_ == c; }
  const T& value() const { return value_; }
  int index() const { return node_; }

  // The node holding this value (a constant gets a node of its own).
  int materialize() const {
    auto& recording = TapeRecording<T>::active();
    return is_constant() ? recording.record(TapeOp::constant, -1, -1, recording.constant(value_))
                         : node_;
  }

  TapeScalar& operator+=(const TapeScalar& b) { return *this = *this + b; }
  TapeScalar& operator-=(const TapeScalar& b) { return *this = *this - b; }
  TapeScalar& operator*=(const TapeScalar& b) { return *this = *this * b; }
  TapeScalar& operator/=(const TapeScalar& b) { return *this = *this / b; }

 private:
  int node_ = -1;
  T value_;
};

namespace tape_detail {

template <class T>
TapeScalar<T> make(TapeOp op, int a, int b = -1, int c = -1) {
  return TapeScalar<T>::node(TapeRecording<T>::active().record(op, a, b, c));
}
template <class T>
TapeScalar<T> with_constant(TapeOp op, const TapeScalar<T>& x, const T& c) {
  auto& recording = TapeRecording<T>::active();
  return TapeScalar<T>::node(recording.record(op, x.index(), -1, recording.constant(c)));
}
template <class T>
const TapeNode& node_of(const TapeScalar<T>& x) {
  return TapeRecording<T>::active().tape().nodes[x.index()];
}
// c·x, folding c·(d·x) = (cd)·x and c·(−x) = (−c)·x.
template <class T>
TapeScalar<T> scaled(const TapeScalar<T>& x, const T& c) {
  const TapeNode node = node_of(x);
  if (node.op == TapeOp::scale) {
    const T product = c * TapeRecording<T>::active().tape().constants[node.c];
    return with_constant(TapeOp::scale, TapeScalar<T>::node(node.a), product);
  }
  if (node.op == TapeOp::neg) return with_constant(TapeOp::scale, TapeScalar<T>::node(node.a), T(-c));
  return with_constant(TapeOp::scale, x, c);
}

// x^c for a constant exponent c in T, in any scalar S the tape is evaluated in.
template <class S, class T>
S power(S x, const T& c) {
  using std::pow;
  return pow(std::move(x), c);
}

}  // namespace tape_detail

// −x, folding −c, −(−x) = x and −(c·x) = (−c)·x.
template <class T>
TapeScalar<T> operator-(const TapeScalar<T>& x) {
  if (x.is_constant()) return TapeScalar<T>(T(-x.value()));
  const TapeNode node = tape_detail::node_of(x);
  if (node.op == TapeOp::neg) return TapeScalar<T>::node(node.a);
  if (node.op == TapeOp::scale) return tape_detail::scaled(x, T(-1));
  return tape_detail::make<T>(TapeOp::neg, x.index());
}

// a + b with x + 0 = x, x + x = 2·x.
template <class T>
TapeScalar<T> operator+(const TapeScalar<T>& a, const TapeScalar<T>& b) {
  if (a.is_constant() && b.is_constant()) return TapeScalar<T>(T(a.value() + b.value()));
  if (a.is_constant(0)) return b;
  if (b.is_constant(0)) return a;
  if (a.is_constant()) return tape_detail::with_constant(TapeOp::add_constant, b, a.value());
  if (b.is_constant()) return tape_detail::with_constant(TapeOp::add_constant, a, b.value());
  if (a.index() == b.index()) return tape_detail::scaled(a, T(2));
  return tape_detail::make<T>(TapeOp::add, a.index(), b.index());
}

// a − b with x − 0 = x, 0 − x = −x.
template <class T>
TapeScalar<T> operator-(const TapeScalar<T>& a, const TapeScalar<T>& b) {
  if (a.is_constant() && b.is_constant()) return TapeScalar<T>(T(a.value() - b.value()));
  if (b.is_constant(0)) return a;
  if (a.is_constant(0)) return -b;
  if (b.is_constant()) return tape_detail::with_constant(TapeOp::add_constant, a, T(-b.value()));
  if (a.is_constant()) return tape_detail::with_constant(TapeOp::constant_minus, b, a.value());
  if (a.index() == b.index()) return TapeScalar<T>(0);
  return tape_detail::make<T>(TapeOp::sub, a.index(), b.index());
}

// a · b with x·0 = 0, x·1 = x, x·(−1) = −x, c·(d·x) = (cd)·x, x·x a square.
template <class T>
TapeScalar<T> operator*(const TapeScalar<T>& a, const TapeScalar<T>& b) {
  if (a.is_constant() && b.is_constant()) return TapeScalar<T>(T(a.value() * b.value()));
  if (a.is_constant(0) || b.is_constant(0)) return TapeScalar<T>(0);
  if (a.is_constant(1)) return b;
  if (b.is_constant(1)) return a;
  if (a.is_constant(-1)) return -b;
  if (b.is_constant(-1)) return -a;
  if (a.is_constant()) return tape_detail::scaled(b, a.value());
  if (b.is_constant()) return tape_detail::scaled(a, b.value());
  if (a.index() == b.index()) return tape_detail::make<T>(TapeOp::square, a.index());
  return tape_detail::make<T>(TapeOp::mul, a.index(), b.index());
}

// a / b with 0/x = 0, x/1 = x, x/c = (1/c)·x.
template <class T>
TapeScalar<T> operator/(const TapeScalar<T>& a, const TapeScalar<T>& b) {
  if (a.is_constant() && b.is_constant()) return TapeScalar<T>(T(a.value() / b.value()));
  if (a.is_constant(0)) return TapeScalar<T>(0);
  if (b.is_constant(1)) return a;
  if (b.is_constant()) return a * TapeScalar<T>(T(1 / b.value()));
  if (a.is_constant()) return tape_detail::with_constant(TapeOp::constant_div, b, a.value());
  if (a.index() == b.index()) return TapeScalar<T>(1);
  return tape_detail::make<T>(TapeOp::div, a.index(), b.index());
}

// Mixed operations with anything that converts to T (T, int, ...).
#define VIVV_TAPE_MIXED(op)                                                                 \
  template <class T, class U, std::enable_if_t<std::is_convertible_v<U, T>, int> = 0>       \
  TapeScalar<T> operator op(const TapeScalar<T>& a, const U& b) {                           \
    return a op TapeScalar<T>(T(b));                                                        \
  }                                                                                         \
  template <class T, class U, std::enable_if_t<std::is_convertible_v<U, T>, int> = 0>       \
  TapeScalar<T> operator op(const U& a, const TapeScalar<T>& b) {                           \
    return TapeScalar<T>(T(a)) op b;                                                        \
  }
VIVV_TAPE_MIXED(+)
VIVV_TAPE_MIXED(-)
VIVV_TAPE_MIXED(*)
VIVV_TAPE_MIXED(/)
#undef VIVV_TAPE_MIXED

// Elementary functions: folded on constants, recorded otherwise.
#define VIVV_TAPE_FUNCTION(name)                                         \
  template <class T>                                                     \
  TapeScalar<T> name(const TapeScalar<T>& x) {                           \
    using std::name;                                                     \
    if (x.is_constant()) return TapeScalar<T>(T(name(x.value())));       \
    return tape_detail::make<T>(TapeOp::name, x.index());                \
  }
VIVV_TAPE_FUNCTION(sin)
VIVV_TAPE_FUNCTION(cos)
VIVV_TAPE_FUNCTION(exp)
VIVV_TAPE_FUNCTION(log)
VIVV_TAPE_FUNCTION(sqrt)
#undef VIVV_TAPE_FUNCTION

// atan x, recorded with the node 1 + x² that its derivative 1/(1 + x²) needs.
template <class T>
TapeScalar<T> atan(const TapeScalar<T>& x) {
  using std::atan;
  if (x.is_constant()) return TapeScalar<T>(T(atan(x.value())));
  const TapeScalar<T> denominator = 1 + x * x;
  return tape_detail::make<T>(TapeOp::atan, x.index(), denominator.index());
}

// x^p: a constant exponent is one node (x^0 = 1, x^1 = x); otherwise e^{p ln x}.
template <class T>
TapeScalar<T> pow(const TapeScalar<T>& x, const TapeScalar<T>& p) {
  using std::pow;
  if (x.is_constant() && p.is_constant()) return TapeScalar<T>(T(pow(x.value(), p.value())));
  if (p.is_constant(0)) return TapeScalar<T>(1);
  if (p.is_constant(1)) return x;
  if (p.is_constant()) return tape_detail::with_constant(TapeOp::pow, x, p.value());
  return exp(p * log(x));
}
template <class T, class U, std::enable_if_t<std::is_convertible_v<U, T>, int> = 0>
TapeScalar<T> pow(const TapeScalar<T>& x, const U& p) {
  return pow(x, TapeScalar<T>(T(p)));
}

template <class T>
TapeScalar<T> TapeRecording<T>::input(int i) const {
  return TapeScalar<T>::node(i);
}

template <class T>
Tape<T> TapeRecording<T>::finish(const std::vector<TapeScalar<T>>& outputs) {
  tape_.outputs.clear();
  for (const auto& y : outputs) tape_.outputs.push_back(y.materialize());
  Tape<T> result = tape_;
  result.prune();
  return result;
}

template <class T>
void Tape<T>::prune() {
  const int count = static_cast<int>(nodes.size());
  std::vector<char> live(count, 0);
  for (int i = 0; i < inputs; ++i) live[i] = 1;
  for (int y : outputs) live[y] = 1;
  for (int i = count - 1; i >= inputs; --i) {
    const TapeNode& node = nodes[i];
    if (node.op == TapeOp::cos && live[i]) live[i - 1] = 1;  // the pair is computed at the sin
    if (node.op == TapeOp::sin && live[i]) live[i + 1] = 1;
    if (!live[i]) continue;
    if (node.a >= 0 && node.op != TapeOp::input) live[node.a] = 1;
    if (node.b >= 0) live[node.b] = 1;
  }
  std::vector<int> renumber(count, -1);
  std::vector<TapeNode> kept;
  for (int i = 0; i < count; ++i) {
    if (!live[i]) continue;
    TapeNode node = nodes[i];
    if (node.op != TapeOp::input) {
      if (node.a >= 0) node.a = renumber[node.a];
      if (node.b >= 0) node.b = renumber[node.b];
    }
    renumber[i] = static_cast<int>(kept.size());
    kept.push_back(node);
  }
  for (int& y : outputs) y = renumber[y];
  nodes = std::move(kept);
}

template <class T>
template <class S>
void Tape<T>::run(const S* x, std::vector<S>& value) const {
  using std::atan;
  using std::cos;
  using std::exp;
  using std::log;
  using std::sin;
  using std::sqrt;
  if (value.size() < nodes.size()) value.resize(nodes.size());
  // The operand of node i's function: for a jet, a copy of value[a] into slot i, moved out.
  const auto argument = [&value](std::size_t i, int a) -> S {
    if constexpr (is_jet<S>::value) {
      value[i] = value[a];
      return std::move(value[i]);
    } else {
      return value[a];
    }
  };
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const TapeNode& node = nodes[i];
    // Constants enter as T: a constant operand of a jet has no derivatives to carry.
    switch (node.op) {
      case TapeOp::input: value[i] = x[node.a]; break;
      case TapeOp::constant: value[i] = S(constants[node.c]); break;
      // Jets combine in place into their slot (a copy into storage the slot already has, then a
      // compound operation): for MPFR a jet temporary is 1 + N + N² allocations per node, what
      // made a formula system's DEL step cost 1.5 times its compiled twin's.
      case TapeOp::add:
        if constexpr (is_jet<S>::value)
          value[i] = value[node.a], value[i] += value[node.b];
        else
          value[i] = value[node.a] + value[node.b];
        break;
      case TapeOp::sub:
        if constexpr (is_jet<S>::value)
          value[i] = value[node.a], value[i] -= value[node.b];
        else
          value[i] = value[node.a] - value[node.b];
        break;
      case TapeOp::neg:
        if constexpr (is_jet<S>::value)
          value[i] = value[node.a], value[i] *= decltype(S::value)(-1);
        else
          value[i] = -value[node.a];
        break;
      case TapeOp::mul:
        if constexpr (is_jet<S>::value)
          value[i] = value[node.a], value[i] *= value[node.b];
        else
          value[i] = value[node.a] * value[node.b];
        break;
      case TapeOp::square:
        if constexpr (is_jet<S>::value)
          value[i] = value[node.a], value[i] *= value[node.a];
        else
          value[i] = value[node.a] * value[node.a];
        break;
      case TapeOp::div:
        if constexpr (is_jet<S>::value)
          value[i] = value[node.a], value[i] /= value[node.b];
        else
          value[i] = value[node.a] / value[node.b];
        break;
      case TapeOp::add_constant:
        if constexpr (is_jet<S>::value)
          value[i] = value[node.a], value[i].value += constants[node.c];
        else
          value[i] = value[node.a] + constants[node.c];
        break;
      case TapeOp::constant_minus:
        if constexpr (is_jet<S>::value)
          value[i] = value[node.a], value[i] *= decltype(S::value)(-1),
          value[i].value += constants[node.c];
        else
          value[i] = constants[node.c] - value[node.a];
        break;
      case TapeOp::scale:
        if constexpr (is_jet<S>::value)
          value[i] = value[node.a], value[i] *= decltype(S::value)(constants[node.c]);
        else
          value[i] = constants[node.c] * value[node.a];
        break;
      case TapeOp::constant_div: value[i] = constants[node.c] / value[node.a]; break;
      // A jet's elementary functions take their argument by value: a copy moved in comes back
      // transformed in the slot's storage.
      case TapeOp::sin:
        if constexpr (is_jet<S>::value) {
          // The pair at once, from one sine and one cosine of the value (node i + 1 is the cos
          // partner, prune() keeps it): the same chain rules as the jet's sin and cos, which
          // compute both each. Computed apart, a pendulum's DEL step made four MPFR sines and
          // cosines per L where its compiled twin makes two.
          assert(i + 1 < nodes.size() && nodes[i + 1].op == TapeOp::cos &&
                 nodes[i + 1].a == node.a);
          using V = std::decay_t<decltype(S::value)>;
          const V s = sin(value[node.a].value), c = cos(value[node.a].value);
          value[i] = value[node.a], value[i].apply_chain(s, c, -s);
          value[i + 1] = value[node.a], value[i + 1].apply_chain(c, -s, -c);
          ++i;
        } else {
          value[i] = sin(argument(i, node.a));
        }
        break;
      case TapeOp::cos:  // for a jet, computed with its sin partner above
        value[i] = cos(argument(i, node.a));
        break;
      case TapeOp::exp:
        value[i] = exp(argument(i, node.a));
        break;
      case TapeOp::log:
        value[i] = log(argument(i, node.a));
        break;
      case TapeOp::sqrt:
        value[i] = sqrt(argument(i, node.a));
        break;
      case TapeOp::pow:
        value[i] = tape_detail::power(argument(i, node.a), constants[node.c]);
        break;
      case TapeOp::atan:
        value[i] = atan(argument(i, node.a));
        break;
    }
  }
}

template <class T>
template <class S>
std::vector<S> Tape<T>::evaluate(const std::vector<S>& x) const {
  if (static_cast<int>(x.size()) != inputs)
    throw std::invalid_argument("Tape::evaluate: expected " + std::to_string(inputs) + " inputs");
  std::vector<S> value;
  run(x.data(), value);
  std::vector<S> y;
  for (int index : outputs) y.push_back(value[index]);
  return y;
}

namespace tape_detail {

// The node values of evaluate_first in jets, kept between calls (one buffer per thread and jet
// type; a run only does arithmetic, so no evaluation nests inside another): the slots' storage
// is reused, where a fresh vector allocated every node's jet on every call. An MPFR buffer is
// dropped when the working precision changes, so no slot carries another precision.
template <class S>
std::vector<S>& jet_scratch() {
  thread_local std::vector<S> scratch;
  if constexpr (is_mpfr_v<leaf_scalar_t<S>>) {
    thread_local unsigned digits = 0;
    const unsigned now = mpfr_real::default_precision();
    if (digits != now) scratch.clear(), digits = now;
  }
  return scratch;
}

}  // namespace tape_detail

template <class T>
template <class S>
S Tape<T>::evaluate_first(const S* x) const {
  if constexpr (is_jet<S>::value) {
    std::vector<S>& value = tape_detail::jet_scratch<S>();
    run(x, value);
    return value[outputs.front()];
  } else {
    std::vector<S> value;
    run(x, value);
    return value[outputs.front()];
  }
}

}  // namespace vivv
