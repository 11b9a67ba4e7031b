// Sparse first and second derivatives of a tape's first output, by edge pushing.
//
// A dense jet over m inputs carries m + m² numbers through every node, so a Lagrangian of n
// coordinates whose tape has O(n) nodes (a chain) costs O(n³) per Hessian. Edge pushing
// (Gower & Mello, "A new framework for the computation of Hessians", Optim. Methods Softw. 27,
// 2012) runs the tape backwards once, carrying the adjoint ā_i = ∂f/∂v_i and the symmetric
// matrix W of second derivatives of f with respect to the live nodes; at node v_i = φ(v_j, v_k)
//   pushing:  W(i, p) w moves to W(j, p) += φ_j w for each predecessor j (2 φ_p w when j = p);
//             W(i, i) w moves to W(j, k) += φ_j φ_k w for each pair of predecessors;
//   creating: W(j, k) += ā_i φ_jk;
//   adjoint:  ā_j += ā_i φ_j,
// and what is left on the inputs is the gradient and the Hessian. Its work is that of the
// nonzero second derivatives it meets: O(n) for a chain, O(n²) for all pairs.
//
// The entries W holds depend on the tape alone, never on the values, so the sweep is run once
// in TapeScalar<T>: SecondDerivativeTape is the straight-line program of f, ∇f and the nonzero
// entries of ∇²f (pattern fixed when it is recorded), evaluated afterwards in T with no
// hashing and no allocation beyond its node values.
#pragma once

#include <cstdint>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/autodiff/tape.hpp"

namespace vivv {

// f, ∇f and the lower triangle of ∇²f of a tape's first output at one point, in S.
template <class S>
struct EdgePushed {
  S value;
  std::vector<S> gradient;                   // ∂f/∂x_k for every input k
  std::vector<std::pair<int, int>> pattern;  // (row, column) of each entry, row >= column
  std::vector<S> hessian;                    // ∂²f/∂x_row ∂x_column at pattern's entries
};

namespace edge_pushing_detail {

// A node's local derivatives: its distinct predecessors j, φ_j and φ_jk (where nonzero).
template <class S>
struct LocalDerivatives {
  int count = 0;
  int predecessor[2] = {-1, -1};
  S first[2];
  S second[2][2];  // symmetric; read where has_second is set
  bool has_second[2][2] = {{false, false}, {false, false}};
};

// φ_j and φ_jk of node i, whose value is value[i], from its operands' values.
template <class S, class T>
LocalDerivatives<S> local_derivatives(const Tape<T>& tape, int i, const std::vector<S>& value) {
  using std::cos;
  using std::pow;
  using std::sin;
  const TapeNode& node = tape.nodes[i];
  LocalDerivatives<S> d;
  const auto unary = [&](S first, const S* second) {
    d.count = 1, d.predecessor[0] = node.a, d.first[0] = std::move(first);
    if (second) d.second[0][0] = *second, d.has_second[0][0] = true;
  };
  const auto binary = [&](S first_a, S first_b) {
    d.count = 2, d.predecessor[0] = node.a, d.predecessor[1] = node.b;
    d.first[0] = std::move(first_a), d.first[1] = std::move(first_b);
  };
  const S& u = value[node.a < 0 ? 0 : node.a];
  switch (node.op) {
    case TapeOp::input:
    case TapeOp::constant:
      return d;
    case TapeOp::add: binary(S(1), S(1)); break;
    case TapeOp::sub: binary(S(1), S(-1)); break;
    case TapeOp::neg: unary(S(-1), nullptr); break;
    case TapeOp::mul:
      binary(value[node.b], u);
      d.second[0][1] = S(1), d.has_second[0][1] = true;
      break;
    case TapeOp::square: {
      const S two(2);
      unary(2 * u, &two);
      break;
    }
    case TapeOp::div: {  // u / w: (1/w, −u/w²), φ_uw = −1/w², φ_ww = 2u/w³
      const S& w = value[node.b];
      const S inverse = 1 / w;
      binary(inverse, -value[i] * inverse);
      d.second[0][1] = -inverse * inverse, d.has_second[0][1] = true;
      d.second[1][1] = 2 * value[i] * inverse * inverse, d.has_second[1][1] = true;
      break;
    }
    case TapeOp::add_constant: unary(S(1), nullptr); break;
    case TapeOp::constant_minus: unary(S(-1), nullptr); break;
    case TapeOp::scale: unary(S(tape.constants[node.c]), nullptr); break;
    case TapeOp::constant_div: {  // c / u: −c/u², 2c/u³
      const S inverse = 1 / u;
      const S second = 2 * value[i] * inverse * inverse;
      unary(-value[i] * inverse, &second);
      break;
    }
    case TapeOp::sin: {
      const S second = -value[i];
      unary(cos(u), &second);
      break;
    }
    case TapeOp::cos: {
      const S second = -value[i];
      unary(-sin(u), &second);
      break;
    }
    case TapeOp::exp: unary(value[i], &value[i]); break;
    case TapeOp::log: {
      const S inverse = 1 / u;
      const S second = -inverse * inverse;
      unary(inverse, &second);
      break;
    }
    case TapeOp::sqrt: {  // 1/(2√u), −1/(4 u √u)
      const S first = 1 / (2 * value[i]);
      const S second = -first / (2 * u);
      unary(first, &second);
      break;
    }
    case TapeOp::pow: {  // c u^(c−1), c (c − 1) u^(c−2)
      const T& c = tape.constants[node.c];
      const S second = S(c * (c - 1)) * tape_detail::power(u, T(c - 2));
      unary(S(c) * tape_detail::power(u, T(c - 1)), &second);
      break;
    }
    case TapeOp::atan: {  // 1/(1 + u²), −2u/(1 + u²)²; node.b is 1 + u², not an operand
      const S first = 1 / value[node.b];
      const S second = -2 * u * first * first;
      unary(first, &second);
      break;
    }
  }
  // Constants have no derivatives, and an operand met twice (a ∘ a) is one predecessor:
  // φ_a = φ_1 + φ_2, φ_aa = φ_11 + 2 φ_12 + φ_22.
  if (d.count == 2 && d.predecessor[0] == d.predecessor[1]) {
    d.first[0] = d.first[0] + d.first[1];
    S second(0);
    bool any = false;
    for (int a = 0; a < 2; ++a)
      for (int b = a; b < 2; ++b)
        if (d.has_second[a][b]) second = second + (a == b ? S(1) : S(2)) * d.second[a][b], any = true;
    d.count = 1;
    d.second[0][0] = second, d.has_second[0][0] = any;
    d.has_second[0][1] = d.has_second[1][1] = false;
  }
  LocalDerivatives<S> kept;
  for (int a = 0; a < d.count; ++a) {
    if (tape.nodes[d.predecessor[a]].op == TapeOp::constant) continue;
    const int k = kept.count++;
    kept.predecessor[k] = d.predecessor[a], kept.first[k] = d.first[a];
    for (int b = a, l = k; b < d.count; ++b) {
      if (tape.nodes[d.predecessor[b]].op == TapeOp::constant) continue;
      if (d.has_second[a][b]) kept.second[k][l] = d.second[a][b], kept.has_second[k][l] = true;
      ++l;
    }
  }
  return kept;
}

// The symmetric matrix W over nodes: entry (r, p) with r >= p kept in row r, which the sweep
// reads when it reaches node r and never writes again.
template <class S>
class NodeHessian {
 public:
  explicit NodeHessian(int nodes) : rows_(nodes), nodes_(static_cast<std::uint64_t>(nodes)) {}

  // W(a, b) += w.
  void add(int a, int b, S w) {
    if (a < b) std::swap(a, b);
    const std::uint64_t key = static_cast<std::uint64_t>(a) * nodes_ + static_cast<std::uint64_t>(b);
    const auto [slot, inserted] = slot_of_.try_emplace(key, static_cast<int>(weight_.size()));
    if (inserted) {
      rows_[a].push_back({b, slot->second});
      weight_.push_back(std::move(w));
    } else {
      weight_[slot->second] = weight_[slot->second] + w;
    }
  }
  // The entries (p, slot) of row r, p <= r.
  const std::vector<std::pair<int, int>>& row(int r) const { return rows_[r]; }
  const S& weight(int slot) const { return weight_[slot]; }

 private:
  std::vector<std::vector<std::pair<int, int>>> rows_;
  std::unordered_map<std::uint64_t, int> slot_of_;
  std::vector<S> weight_;
  std::uint64_t nodes_;
};

}  // namespace edge_pushing_detail

// f = the tape's first output, with ∇f and the nonzero entries of ∇²f, at x (tape.inputs
// values), by one forward run and one edge-pushing sweep, in any scalar S.
template <class S, class T>
EdgePushed<S> edge_push(const Tape<T>& tape, const S* x) {
  using namespace edge_pushing_detail;
  std::vector<S> value;
  tape.run(x, value);
  const int count = static_cast<int>(tape.nodes.size());
  const int output = tape.outputs.front();
  std::vector<S> adjoint(count, S(0));
  std::vector<char> reached(count, 0);  // ā_i is (structurally) nonzero
  adjoint[output] = S(1), reached[output] = 1;
  NodeHessian<S> W(count);
  for (int i = count - 1; i >= tape.inputs; --i) {
    if (!reached[i] && W.row(i).empty()) continue;
    const LocalDerivatives<S> d = local_derivatives(tape, i, value);
    for (const auto& [p, slot] : W.row(i)) {
      const S w = W.weight(slot);  // a copy: adding to W may move its weights
      if (p == i) {
        for (int a = 0; a < d.count; ++a)
          for (int b = a; b < d.count; ++b) W.add(d.predecessor[a], d.predecessor[b], d.first[a] * d.first[b] * w);
      } else {
        for (int a = 0; a < d.count; ++a)
          W.add(d.predecessor[a], p, d.predecessor[a] == p ? S(2 * d.first[a] * w) : S(d.first[a] * w));
      }
    }
    if (!reached[i]) continue;
    for (int a = 0; a < d.count; ++a)
      for (int b = a; b < d.count; ++b)
        if (d.has_second[a][b]) W.add(d.predecessor[a], d.predecessor[b], adjoint[i] * d.second[a][b]);
    for (int a = 0; a < d.count; ++a) {
      adjoint[d.predecessor[a]] = adjoint[d.predecessor[a]] + adjoint[i] * d.first[a];
      reached[d.predecessor[a]] = 1;
    }
  }
  EdgePushed<S> result;
  result.value = value[output];
  result.gradient.assign(adjoint.begin(), adjoint.begin() + tape.inputs);
  for (int r = 0; r < tape.inputs; ++r)
    for (const auto& [p, slot] : W.row(r)) {
      result.pattern.push_back({r, p});
      result.hessian.push_back(W.weight(slot));
    }
  return result;
}

// f, ∇f and ∇²f's nonzero entries of a tape, recorded once as a straight-line program of their
// own (outputs: f, then the gradient, then the entries in `pattern`'s order).
template <class T>
struct SecondDerivativeTape {
  Tape<T> program;
  int inputs = 0;
  std::vector<std::pair<int, int>> pattern;  // row >= column
  // f and ∇f alone, pruned of what only the Hessian needs.
  Tape<T> gradient_program;

  // Records edge_push(tape) in TapeScalar<T>.
  explicit SecondDerivativeTape(const Tape<T>& tape) : inputs(tape.inputs) {
    TapeRecording<T> recording(tape.inputs);
    std::vector<TapeScalar<T>> x;
    for (int k = 0; k < tape.inputs; ++k) x.push_back(recording.input(k));
    const EdgePushed<TapeScalar<T>> pushed = edge_push(tape, x.data());
    std::vector<TapeScalar<T>> outputs{pushed.value};
    outputs.insert(outputs.end(), pushed.gradient.begin(), pushed.gradient.end());
    outputs.insert(outputs.end(), pushed.hessian.begin(), pushed.hessian.end());
    program = recording.finish(outputs);
    pattern = pushed.pattern;
    gradient_program = program;
    gradient_program.outputs.resize(1 + static_cast<std::size_t>(inputs));
    gradient_program.prune();
  }

  // f, ∇f and the entries at `pattern`, at x, in T (the result's own pattern left empty).
  EdgePushed<T> evaluate(const T* x) const { return run(program, x, pattern.size()); }
  // f and ∇f alone at x (pattern and hessian left empty).
  EdgePushed<T> evaluate_gradient(const T* x) const { return run(gradient_program, x, 0); }

 private:
  // `tape` at x: its value, its `inputs` gradient entries and the `entries` Hessian entries after.
  EdgePushed<T> run(const Tape<T>& tape, const T* x, std::size_t entries) const {
    std::vector<T>& value = tape_detail::jet_scratch<T>();
    tape.run(x, value);
    EdgePushed<T> result;
    result.value = value[tape.outputs[0]];
    result.gradient.reserve(inputs);
    for (int k = 0; k < inputs; ++k) result.gradient.push_back(value[tape.outputs[1 + k]]);
    result.hessian.reserve(entries);
    for (std::size_t e = 0; e < entries; ++e) result.hessian.push_back(value[tape.outputs[1 + inputs + e]]);
    return result;
  }
};

}  // namespace vivv
