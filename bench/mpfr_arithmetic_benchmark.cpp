// Google Benchmark: the arithmetic floor of the Taylor recurrences in MPFR (issue 3).
//
// The recurrences of core/autodiff/taylor_expansion.hpp are inner products
//   r = Σ_{j=1..k} a_j b_{k−j},
// so the cost of one multiply-add at the working precision bounds the Taylor
// flow from below. Measured per term of a length-48 inner product (order 48 is
// the Taylor order at tolerance 1e-40) at 254, 256 and 257 bits (4, 4 and 5
// limbs of 64 bits):
//   mpfr_mul_add:  mpfr_mul into a scratch, then mpfr_add (two roundings per term);
//   mpfr_fma:      mpfr_fma (one rounding per term);
//   taylor_dot:    taylor_detail::set_dot, the inner product the recurrences use;
//   mpn_mul_n:     the exact limb product alone (GMP), the part no method avoids.
#include <benchmark/benchmark.h>
#include <gmp.h>
#include <mpfr.h>

#include <vector>

#include "core/autodiff/taylor_expansion.hpp"

namespace {

constexpr int terms = 48;

// Operands like Taylor coefficients: a_j ≈ ±0.7^j, mantissas of all bits.
void fill_operands(std::vector<mpfr_t>& values, int bits, unsigned seed) {
  gmp_randstate_t random;
  gmp_randinit_default(random);
  gmp_randseed_ui(random, seed);
  for (std::size_t j = 0; j < values.size(); ++j) {
    mpfr_init2(values[j], bits);
    mpfr_urandomb(values[j], random);
    mpfr_mul_d(values[j], values[j], j % 3 == 0 ? -1.0 : 1.0, MPFR_RNDN);
    mpfr_mul_2si(values[j], values[j], -static_cast<long>(j) / 2, MPFR_RNDN);
  }
  gmp_randclear(random);
}

void clear_operands(std::vector<mpfr_t>& values) {
  for (auto& value : values) mpfr_clear(value);
}

// The counter every benchmark here reports: nanoseconds per term of the inner product.
void report_ns_per_term(benchmark::State& state) {
  state.counters["ns_per_term"] = benchmark::Counter(
      double(terms) * double(state.iterations()),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert, benchmark::Counter::kIs1000);
}

// r = Σ_j a_j b_{k−j} by mpfr_mul then mpfr_add per term.
void mpfr_mul_add(benchmark::State& state) {
  const int bits = static_cast<int>(state.range(0));
  std::vector<mpfr_t> a(terms), b(terms);
  fill_operands(a, bits, 1);
  fill_operands(b, bits, 2);
  mpfr_t sum, product;
  mpfr_init2(sum, bits);
  mpfr_init2(product, bits);
  for (auto _ : state) {
    mpfr_set_zero(sum, 1);
    for (int j = 0; j < terms; ++j) {
      mpfr_mul(product, a[j], b[terms - 1 - j], MPFR_RNDN);
      mpfr_add(sum, sum, product, MPFR_RNDN);
    }
    benchmark::DoNotOptimize(sum);
  }
  report_ns_per_term(state);
  mpfr_clear(sum);
  mpfr_clear(product);
  clear_operands(a);
  clear_operands(b);
}

// r = Σ_j a_j b_{k−j} by mpfr_fma per term.
void mpfr_fma_terms(benchmark::State& state) {
  const int bits = static_cast<int>(state.range(0));
  std::vector<mpfr_t> a(terms), b(terms);
  fill_operands(a, bits, 1);
  fill_operands(b, bits, 2);
  mpfr_t sum;
  mpfr_init2(sum, bits);
  for (auto _ : state) {
    mpfr_set_zero(sum, 1);
    for (int j = 0; j < terms; ++j) mpfr_fma(sum, a[j], b[terms - 1 - j], sum, MPFR_RNDN);
    benchmark::DoNotOptimize(sum);
  }
  report_ns_per_term(state);
  mpfr_clear(sum);
  clear_operands(a);
  clear_operands(b);
}

// r = Σ_j a_j b_{k−j} by taylor_detail::set_dot on Boost's MPFR numbers of `bits` bits.
void taylor_dot(benchmark::State& state) {
  const int bits = static_cast<int>(state.range(0));
  std::vector<mpfr_t> raw_a(terms), raw_b(terms);
  fill_operands(raw_a, bits, 1);
  fill_operands(raw_b, bits, 2);
  std::vector<vivv::mpfr_real> a(terms), b(terms);
  for (int j = 0; j < terms; ++j) {
    mpfr_set_prec(a[j].backend().data(), bits);
    mpfr_set_prec(b[j].backend().data(), bits);
    mpfr_set(a[j].backend().data(), raw_a[j], MPFR_RNDN);
    mpfr_set(b[j].backend().data(), raw_b[j], MPFR_RNDN);
  }
  vivv::mpfr_real sum, scratch;
  mpfr_set_prec(sum.backend().data(), bits);
  mpfr_set_prec(scratch.backend().data(), bits);
  for (auto _ : state) {
    vivv::taylor_detail::set_dot(sum, a.data(), b.data(), 0, terms - 1, terms - 1, scratch);
    benchmark::DoNotOptimize(sum);
  }
  report_ns_per_term(state);
  clear_operands(raw_a);
  clear_operands(raw_b);
}

// The exact limb products alone: mpn_mul_n on the significands.
void mpn_mul_n_terms(benchmark::State& state) {
  const int bits = static_cast<int>(state.range(0));
  const int limbs = (bits + GMP_NUMB_BITS - 1) / GMP_NUMB_BITS;
  std::vector<mpfr_t> a(terms), b(terms);
  fill_operands(a, bits, 1);
  fill_operands(b, bits, 2);
  std::vector<mp_limb_t> product(2 * limbs);
  for (auto _ : state) {
    for (int j = 0; j < terms; ++j) {
      mpn_mul_n(product.data(), static_cast<mp_limb_t*>(mpfr_custom_get_significand(a[j])),
                static_cast<mp_limb_t*>(mpfr_custom_get_significand(b[terms - 1 - j])), limbs);
      benchmark::DoNotOptimize(product.data());
      benchmark::ClobberMemory();
    }
  }
  report_ns_per_term(state);
  clear_operands(a);
  clear_operands(b);
}

BENCHMARK(mpfr_mul_add)->Arg(254)->Arg(256)->Arg(257);
BENCHMARK(mpfr_fma_terms)->Arg(254)->Arg(256)->Arg(257);
BENCHMARK(taylor_dot)->Arg(254)->Arg(256)->Arg(257);
BENCHMARK(mpn_mul_n_terms)->Arg(254)->Arg(256)->Arg(257);

}  // namespace

BENCHMARK_MAIN();
