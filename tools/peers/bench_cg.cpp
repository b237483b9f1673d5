// Times Pinocchio's fastest mode and its analytical derivatives on the model written by
// dump.py. Pinocchio's code-generation classes (pinocchio/codegen/cppadcg-algo.hpp: CodeGenRNEA,
// CodeGenCRBA, CodeGenMinv, CodeGenABA, CodeGenRNEADerivatives, CodeGenABADerivatives) tape an
// algorithm with CppAD::AD<CppAD::cg::CG<double>>, write flat C code for it, compile that with
// gcc into a shared library and load it. This program does that for each of the six (timing
// the taping, the C source and gcc), checks each generated function against the plain
// algorithm on 64 states, and times the plain and generated functions over the seeded states of
// peer_model.hpp, the same states as bench.cpp.
//
// Usage: bench_cg MODEL.txt [calls] [--reps R] [--flags "-Ofast"] [--gcc /usr/bin/gcc]
//                 [--keep DIR] [--jacobian]
//   calls       calls per measurement (default 200000)
//   --reps R    repetitions of every measurement, interleaved across functions (default 5)
//   --flags     flags for compiling the generated C code; default -Ofast, which Pinocchio's
//               CodeGenBase::compileLib() uses (the command is `gcc -x c FLAGS -c -fPIC`, then
//               `gcc -O2 -shared -rdynamic` to link)
//   --gcc       the C compiler (run_cg.sh passes a wrapper that runs gcc under nice)
//   --keep DIR  keep the generated C sources and libraries in DIR (default: a scratch directory,
//               removed afterwards)
//   --jacobian  also generate CppAD's (automatic) Jacobian of RNEA and ABA, as CodeGenRNEA and
//               CodeGenABA do by default, and time it; off by default: the forward functions do
//               not need it and ABA's takes minutes to compile
//
// Output on stdout, lines `name value` (ns per call unless the name ends in _s, _kb, _maxdiff
// or _max; each time the median over the repetitions):
//   nv, calls, reps
//   rnea_ns crba_ns aba_ns              plain Pinocchio, as in bench.cpp (same process)
//   minv_ns                             plain computeMinverse
//   rnea_derivs_ns aba_derivs_ns        plain computeRNEADerivatives, computeABADerivatives
//   cg_X_ns                             generated X through Pinocchio's CodeGenX::evalFunction
//                                       (copies in and out of Eigen: what a Pinocchio user calls)
//   cg_X_raw_ns                         the generated function itself on a packed [q v a] or [q]
//                                       input (the floor)
//   cg_X_tape_s cg_X_src_s cg_X_cc_s    seconds to tape and optimise, to write the C source, and
//                                       for gcc (compile and link)
//   cg_X_src_kb                         size of the generated C source
//   cg_X_maxdiff                        largest absolute difference from the plain algorithm over
//                                       64 states (upper triangles for M, M⁻¹, ∂τ/∂q̈, ∂q̈/∂τ,
//                                       which both fill only there)
//   cg_crba_lower_max cg_minv_lower_max largest |entry| of the generated M's and M⁻¹'s strictly
//                                       lower triangle: 0 when only the upper one is filled
//   with --jacobian: cg_rnea_adjac_ns cg_aba_adjac_ns and their _maxdiff
// for X in rnea, crba, minv, aba, rnea_derivs, aba_derivs. Every repetition, the compile command
// and a checksum go to stderr. The generated ABA and CRBA are taped with Convention::WORLD, as
// Pinocchio's code-generation classes do; the plain ones run the default Convention::LOCAL.

// Pinocchio's code-generation header must come before its other headers.
#include <pinocchio/codegen/cppadcg-algo.hpp>

#include <pinocchio/multibody.hpp>
#include <pinocchio/algorithm/aba.hpp>
#include <pinocchio/algorithm/aba-derivatives.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/rnea.hpp>
#include <pinocchio/algorithm/rnea-derivatives.hpp>

#include <algorithm>
#include <functional>
#include <sstream>
#include <unistd.h>

#include "peer_model.hpp"

using namespace pinocchio;
using Clock = std::chrono::steady_clock;

namespace {

double seconds(Clock::time_point from, Clock::time_point to) {
  return std::chrono::duration<double>(to - from).count();
}

// CppADCodeGen's library processor with its source generation exposed, so that the C source
// can be timed apart from gcc: the size of the sources it writes.
struct SourceTimer : CppAD::cg::DynamicModelLibraryProcessor<double> {
  SourceTimer(CppAD::cg::ModelLibraryCSourceGen<double>& library, const std::string& name)
      : CppAD::cg::DynamicModelLibraryProcessor<double>(library, name) {}
  size_t write_sources(CppAD::cg::ModelCSourceGen<double>& model) {
    size_t bytes = 0;
    for (auto& source : this->getSources(model)) bytes += source.second.size();
    for (auto& source : this->getLibrarySources()) bytes += source.second.size();
    return bytes;
  }
};

// A Pinocchio code-generation class with its protected steps reachable: `build` does what
// CodeGenBase::initLib(), compileLib() and loadLib() do, timing each step and with any gcc
// flags; `raw` calls the generated function on a packed input.
template <class Base> struct Generated : Base {
  using Base::Base;
  double tape_s = 0, source_s = 0, compile_s = 0;
  size_t source_bytes = 0;

  void build(const std::string& gcc, const std::vector<std::string>& flags, bool keep,
             bool jacobian) {
    if (!jacobian) this->build_jacobian = false;  // otherwise the class's own default
    const auto taped = Clock::now();
    this->initLib();  // tape with CppAD<CG<double>>, optimise, create the source generators
    const auto written = Clock::now();
    auto* processor = new SourceTimer(*this->libcgen_ptr, this->library_name);
    this->dynamicLibManager_ptr.reset(processor);
    source_bytes = processor->write_sources(*this->cgen_ptr);  // kept for the compile
    const auto compiled = Clock::now();
    CppAD::cg::GccCompiler<double> compiler(gcc);
    compiler.setCompileFlags(flags);  // Pinocchio's compileLib() replaces -O2 by -Ofast
    if (keep) {
      compiler.setSaveToDiskFirst(true);
      compiler.setSourcesFolder("src_" + this->function_name);
    }
    processor->createDynamicLibrary(compiler, false);
    const auto loaded = Clock::now();
    this->loadLib(false);
    tape_s = seconds(taped, written);
    source_s = seconds(written, compiled);
    compile_s = seconds(compiled, loaded);
  }

  void raw(const double* x, double* y) {
    this->generatedFun_ptr->ForwardZero(
        CppAD::cg::ArrayView<const double>(x, static_cast<size_t>(this->getInputDimension())),
        CppAD::cg::ArrayView<double>(y, static_cast<size_t>(this->getOutputDimension())));
  }

  const Eigen::VectorXd& output() const { return this->y; }
};

// The derivative classes keep their result matrices protected.
struct GeneratedRneaDerivatives : Generated<CodeGenRNEADerivatives<double>> {
  using Generated<CodeGenRNEADerivatives<double>>::Generated;
  using CodeGenRNEADerivatives<double>::dtau_dq;
  using CodeGenRNEADerivatives<double>::dtau_dv;
  using CodeGenRNEADerivatives<double>::dtau_da;
};
struct GeneratedAbaDerivatives : Generated<CodeGenABADerivatives<double>> {
  using Generated<CodeGenABADerivatives<double>>::Generated;
  using CodeGenABADerivatives<double>::dddq_dq;
  using CodeGenABADerivatives<double>::dddq_dv;
  using CodeGenABADerivatives<double>::dddq_dtau;
};

template <class A, class B> double max_difference(const A& a, const B& b) {
  return (a - b).cwiseAbs().maxCoeff();
}

template <class A, class B> double max_difference_upper(const A& a, const B& b) {
  double largest = 0;
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index j = i; j < a.cols(); ++j)
      largest = std::max(largest, std::abs(a(i, j) - b(i, j)));
  return largest;
}

template <class M> double max_strictly_lower(const M& m) {
  return m.template triangularView<Eigen::StrictlyLower>().toDenseMatrix().cwiseAbs().maxCoeff();
}

struct Options {
  std::string model;
  long calls = 200000;
  int reps = 5;
  std::string gcc = "/usr/bin/gcc";
  std::vector<std::string> flags{"-Ofast"};
  std::string keep;
  bool jacobian = false;
};

bool parse(int argc, char** argv, Options& o) {
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--reps" && has_value) o.reps = std::atoi(argv[++i]);
    else if (arg == "--gcc" && has_value) o.gcc = argv[++i];
    else if (arg == "--keep" && has_value) o.keep = argv[++i];
    else if (arg == "--jacobian") o.jacobian = true;
    else if (arg == "--flags" && has_value) {
      o.flags.clear();
      std::istringstream words(argv[++i]);
      for (std::string w; words >> w;) o.flags.push_back(w);
    } else positional.push_back(arg);
  }
  if (positional.empty() || o.reps < 1) return false;
  o.model = positional[0];
  if (positional.size() > 1) o.calls = std::atol(positional[1].c_str());
  return o.calls > 0;
}

// One timed function: its output line's name and its time per repetition.
struct Timed {
  std::string name;
  std::function<double(long)> time;  // mean ns per call over that many calls
  std::vector<double> ns;
};

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (!parse(argc, argv, o)) {
    std::cerr << "usage: bench_cg MODEL.txt [calls] [--reps R] [--flags \"-Ofast\"] "
                 "[--gcc /usr/bin/gcc] [--keep DIR] [--jacobian]\n";
    return 2;
  }
  Model model = peers::read_model(o.model.c_str());
  model.name = "m";
  Data data(model);
  const int nq = model.nq, nv = model.nv, K = peers::STATES;
  const peers::States s = peers::seeded_states(model);

  // Packed inputs of the generated functions: [q v a] and [q] per state.
  const int wide = nq + 2 * nv;
  std::vector<double> packed_qva(static_cast<size_t>(K) * wide), packed_q(static_cast<size_t>(K) * nq);
  for (int k = 0; k < K; ++k) {
    double* x = &packed_qva[static_cast<size_t>(k) * wide];
    for (int i = 0; i < nq; ++i) x[i] = packed_q[static_cast<size_t>(k) * nq + i] = s.q[k][i];
    for (int i = 0; i < nv; ++i) { x[nq + i] = s.v[k][i]; x[nq + nv + i] = s.a[k][i]; }
  }
  auto qva = [&](int i) { return &packed_qva[static_cast<size_t>(i % K) * wide]; };
  auto q_only = [&](int i) { return &packed_q[static_cast<size_t>(i % K) * nq]; };

  // Generate, compile and load, in a directory of their own.
  char scratch_template[] = "/tmp/bench_cg.XXXXXX";
  const bool keep = !o.keep.empty();
  std::string work = o.keep;
  if (keep) {
    const std::string mkdir = "mkdir -p '" + o.keep + "'";
    if (std::system(mkdir.c_str()) != 0) { std::cerr << "cannot create " << o.keep << "\n"; return 2; }
  } else {
    const char* made = mkdtemp(scratch_template);
    if (!made) { std::cerr << "cannot create a scratch directory\n"; return 2; }
    work = made;
  }
  char cwd[4096];
  if (!getcwd(cwd, sizeof cwd) || chdir(work.c_str()) != 0) {
    std::cerr << "cannot enter " << work << "\n";
    return 2;
  }
  std::cerr << "generated code compiled with: " << o.gcc << " -x c";
  for (const auto& f : o.flags) std::cerr << " " << f;
  std::cerr << " -c -fPIC; linked with: " << o.gcc << " -O2 -shared -rdynamic\n";

  Generated<CodeGenRNEA<double>> g_rnea(model);
  Generated<CodeGenCRBA<double>> g_crba(model);
  Generated<CodeGenMinv<double>> g_minv(model);
  Generated<CodeGenABA<double>> g_aba(model);
  GeneratedRneaDerivatives g_rnea_derivs(model);
  GeneratedAbaDerivatives g_aba_derivs(model);
  std::ostringstream build_lines;
  auto build = [&](auto& generated, const std::string& name) {
    generated.build(o.gcc, o.flags, keep, o.jacobian);
    build_lines << "cg_" << name << "_tape_s " << generated.tape_s << "\n"
                << "cg_" << name << "_src_s " << generated.source_s << "\n"
                << "cg_" << name << "_cc_s " << generated.compile_s << "\n"
                << "cg_" << name << "_src_kb " << generated.source_bytes / 1024.0 << "\n";
    std::cerr << "built " << name << " (tape " << generated.tape_s << " s, C source "
              << generated.source_s << " s, gcc " << generated.compile_s << " s, "
              << generated.source_bytes / 1024 << " KiB)\n";
  };
  build(g_rnea, "rnea");
  build(g_crba, "crba");
  build(g_minv, "minv");
  build(g_aba, "aba");
  build(g_rnea_derivs, "rnea_derivs");
  build(g_aba_derivs, "aba_derivs");
  if (chdir(cwd) != 0) std::cerr << "cannot return to " << cwd << "\n";
  if (!keep) {
    const std::string remove = "rm -rf '" + work + "'";
    if (std::system(remove.c_str()) != 0) std::cerr << "cannot remove " << work << "\n";
  }

  // The generated functions against the plain algorithms.
  double d_rnea = 0, d_crba = 0, d_minv = 0, d_aba = 0, d_rnea_derivs = 0, d_aba_derivs = 0;
  double d_rnea_jacobian = 0, d_aba_jacobian = 0;
  Eigen::MatrixXd dq(nv, nv), dv(nv, nv), da(nv, nv);
  for (int k = 0; k < 64; ++k) {
    const auto &q = s.q[k], &v = s.v[k], &a = s.a[k];
    rnea(model, data, q, v, a);
    g_rnea.evalFunction(q, v, a);
    d_rnea = std::max(d_rnea, max_difference(g_rnea.output(), data.tau));
    data.M.setZero();
    crba(model, data, q);
    g_crba.evalFunction(q);
    d_crba = std::max(d_crba, max_difference_upper(g_crba.M, data.M));
    data.Minv.setZero();
    computeMinverse(model, data, q);
    g_minv.evalFunction(q);
    d_minv = std::max(d_minv, max_difference_upper(g_minv.Minv, data.Minv));
    aba(model, data, q, v, a);
    g_aba.evalFunction(q, v, a);
    d_aba = std::max(d_aba, max_difference(g_aba.output(), data.ddq));

    dq.setZero(); dv.setZero(); da.setZero();
    computeRNEADerivatives(model, data, q, v, a, dq, dv, da);
    g_rnea_derivs.evalFunction(q, v, a);
    d_rnea_derivs = std::max({d_rnea_derivs, max_difference(g_rnea_derivs.dtau_dq, dq),
                              max_difference(g_rnea_derivs.dtau_dv, dv),
                              max_difference_upper(g_rnea_derivs.dtau_da, da)});
    if (o.jacobian) {
      g_rnea.evalJacobian(q, v, a);
      d_rnea_jacobian = std::max({d_rnea_jacobian, max_difference(g_rnea.dtau_dq, dq),
                                  max_difference(g_rnea.dtau_dv, dv),
                                  max_difference_upper(g_rnea.dtau_da, da)});
    }
    dq.setZero(); dv.setZero(); da.setZero();
    computeABADerivatives(model, data, q, v, a, dq, dv, da);
    g_aba_derivs.evalFunction(q, v, a);
    d_aba_derivs = std::max({d_aba_derivs, max_difference(g_aba_derivs.dddq_dq, dq),
                             max_difference(g_aba_derivs.dddq_dv, dv),
                             max_difference_upper(g_aba_derivs.dddq_dtau, da)});
    if (o.jacobian) {
      g_aba.evalJacobian(q, v, a);
      d_aba_jacobian = std::max({d_aba_jacobian, max_difference(g_aba.da_dq, dq),
                                 max_difference(g_aba.da_dv, dv),
                                 max_difference_upper(g_aba.da_dtau, da)});
    }
  }
  // Whether the generated M and M⁻¹ fill their lower triangle (it is not among the outputs).
  g_crba.M.setZero();
  g_crba.evalFunction(s.q[0]);
  const double crba_lower = max_strictly_lower(g_crba.M);
  g_minv.Minv.setZero();
  g_minv.evalFunction(s.q[0]);
  const double minv_lower = max_strictly_lower(g_minv.Minv);

  // Timing: each entry times its own lambda, so the timed loop makes no indirect call.
  double sink = 0;
  std::vector<double> out(3 * static_cast<size_t>(nv) * nv + 16);
  double* y = out.data();
#define TIMED(NAME, BODY) \
  Timed{NAME, [&](long calls) { auto f = [&](int i) { BODY; }; return peers::ns_per_call(f, calls); }, {}}
  std::vector<Timed> timed = {
      TIMED("rnea_ns", rnea(model, data, s.q[i % K], s.v[i % K], s.a[i % K]); sink += data.tau[0]),
      TIMED("crba_ns", crba(model, data, s.q[i % K]); sink += data.M(0, 0)),
      TIMED("aba_ns", aba(model, data, s.q[i % K], s.v[i % K], s.a[i % K]); sink += data.ddq[0]),
      TIMED("minv_ns", computeMinverse(model, data, s.q[i % K]); sink += data.Minv(0, 0)),
      TIMED("rnea_derivs_ns", computeRNEADerivatives(model, data, s.q[i % K], s.v[i % K], s.a[i % K]);
            sink += data.dtau_dq(0, 0)),
      TIMED("aba_derivs_ns", computeABADerivatives(model, data, s.q[i % K], s.v[i % K], s.a[i % K]);
            sink += data.ddq_dq(0, 0)),
      TIMED("cg_rnea_ns", g_rnea.evalFunction(s.q[i % K], s.v[i % K], s.a[i % K]);
            sink += g_rnea.output()[0]),
      TIMED("cg_crba_ns", g_crba.evalFunction(s.q[i % K]); sink += g_crba.M(0, 0)),
      TIMED("cg_minv_ns", g_minv.evalFunction(s.q[i % K]); sink += g_minv.Minv(0, 0)),
      TIMED("cg_aba_ns", g_aba.evalFunction(s.q[i % K], s.v[i % K], s.a[i % K]);
            sink += g_aba.output()[0]),
      TIMED("cg_rnea_derivs_ns", g_rnea_derivs.evalFunction(s.q[i % K], s.v[i % K], s.a[i % K]);
            sink += g_rnea_derivs.dtau_dq(0, 0)),
      TIMED("cg_aba_derivs_ns", g_aba_derivs.evalFunction(s.q[i % K], s.v[i % K], s.a[i % K]);
            sink += g_aba_derivs.dddq_dq(0, 0)),
      TIMED("cg_rnea_raw_ns", g_rnea.raw(qva(i), y); sink += y[0]),
      TIMED("cg_crba_raw_ns", g_crba.raw(q_only(i), y); sink += y[0]),
      TIMED("cg_minv_raw_ns", g_minv.raw(q_only(i), y); sink += y[0]),
      TIMED("cg_aba_raw_ns", g_aba.raw(qva(i), y); sink += y[0]),
      TIMED("cg_rnea_derivs_raw_ns", g_rnea_derivs.raw(qva(i), y); sink += y[0]),
      TIMED("cg_aba_derivs_raw_ns", g_aba_derivs.raw(qva(i), y); sink += y[0]),
  };
  if (o.jacobian) {
    timed.push_back(TIMED("cg_rnea_adjac_ns", g_rnea.evalJacobian(s.q[i % K], s.v[i % K], s.a[i % K]);
                          sink += g_rnea.dtau_dq(0, 0)));
    timed.push_back(TIMED("cg_aba_adjac_ns", g_aba.evalJacobian(s.q[i % K], s.v[i % K], s.a[i % K]);
                          sink += g_aba.da_dq(0, 0)));
  }
#undef TIMED
  for (auto& t : timed) t.time(o.calls / 8);  // warm-up
  for (int r = 0; r < o.reps; ++r)
    for (auto& t : timed) t.ns.push_back(t.time(o.calls));

  std::cout << "nv " << nv << "\ncalls " << o.calls << "\nreps " << o.reps << "\n";
  for (const auto& t : timed) {
    std::cout << t.name << " " << peers::median(t.ns) << "\n";
    std::cerr << t.name << " reps:";
    for (double ns : t.ns) std::cerr << " " << ns;
    std::cerr << "\n";
  }
  std::cout << build_lines.str();
  std::cout << "cg_rnea_maxdiff " << d_rnea << "\ncg_crba_maxdiff " << d_crba
            << "\ncg_minv_maxdiff " << d_minv << "\ncg_aba_maxdiff " << d_aba
            << "\ncg_rnea_derivs_maxdiff " << d_rnea_derivs << "\ncg_aba_derivs_maxdiff "
            << d_aba_derivs << "\ncg_crba_lower_max " << crba_lower << "\ncg_minv_lower_max "
            << minv_lower << "\n";
  if (o.jacobian)
    std::cout << "cg_rnea_adjac_maxdiff " << d_rnea_jacobian << "\ncg_aba_adjac_maxdiff "
              << d_aba_jacobian << "\n";
  std::cerr << "(checksum " << sink << ")\n";
}
