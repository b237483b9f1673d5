// Times plain Pinocchio on the model written by dump.py: RNEA, CRBA, ABA, nonLinearEffects and
// the generalized gravity, header-only (-O3 -march=native), over the seeded states of
// peer_model.hpp.
//
// Usage: bench MODEL.txt [calls]      (calls default 200000)
// Output: lines `name value` on stdout: nv, then rnea_ns, crba_ns, aba_ns, nle_ns and gravity_ns,
// each the mean ns per call over `calls` calls after a warm-up of calls / 4 RNEA calls; a
// checksum on stderr keeps the results alive.
#include <pinocchio/multibody.hpp>
#include <pinocchio/algorithm/aba.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/rnea.hpp>

#include <algorithm>

#include "peer_model.hpp"

using namespace pinocchio;

int main(int argc, char** argv) {
  if (argc < 2) { std::cerr << "usage: bench MODEL.txt [calls]\n"; return 2; }
  const Model model = peers::read_model(argv[1]);
  Data data(model);
  const long calls = argc > 2 ? std::atol(argv[2]) : 200000;
  const peers::States s = peers::seeded_states(model);
  const int K = peers::STATES;
  double sink = 0;
  auto id = [&](int i) { rnea(model, data, s.q[i % K], s.v[i % K], s.a[i % K]); sink += data.tau[0]; };
  auto mass = [&](int i) { crba(model, data, s.q[i % K]); sink += data.M(0, 0); };
  auto fd = [&](int i) { aba(model, data, s.q[i % K], s.v[i % K], s.a[i % K]); sink += data.ddq[0]; };
  auto bias = [&](int i) { nonLinearEffects(model, data, s.q[i % K], s.v[i % K]); sink += data.nle[0]; };
  auto gravity = [&](int i) { computeGeneralizedGravity(model, data, s.q[i % K]); sink += data.g[0]; };
  peers::ns_per_call(id, calls / 4);  // warm-up
  std::cout << "nv " << model.nv << "\n";
  std::cout << "rnea_ns " << peers::ns_per_call(id, calls) << "\n";
  std::cout << "crba_ns " << peers::ns_per_call(mass, calls) << "\n";
  std::cout << "aba_ns " << peers::ns_per_call(fd, calls) << "\n";
  std::cout << "nle_ns " << peers::ns_per_call(bias, calls) << "\n";
  std::cout << "gravity_ns " << peers::ns_per_call(gravity, calls) << "\n";
  std::cerr << "(checksum " << sink << ")\n";
}
