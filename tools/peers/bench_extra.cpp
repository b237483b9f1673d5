// Times the Pinocchio algorithms that rne's kinematics and identification kernels are compared
// with, which bench.cpp and bench_cg.cpp do not cover:
//   jacobians_ns      computeJointJacobians (every joint's Jacobian, in data.J)
//   jacobians_all_ns  the same, then getJointJacobian(LOCAL_WORLD_ALIGNED) of every joint: the
//                     6 x nv Jacobian of each moving body's frame origin in world axes, what
//                     rne's frame_jacobians returns for frames at the moving links
//   jdqd_ns           computeJointJacobiansTimeVariation, then dJ(LOCAL_WORLD_ALIGNED) * v of
//                     every joint: J-dot times q-dot of each moving body
//   jdqd_fk_ns        the same quantity from forwardKinematics(q, v, 0) and
//                     getClassicalAcceleration(LOCAL_WORLD_ALIGNED) of every joint
//   regressor_ns      computeJointTorqueRegressor
//   jdqd_maxdiff      max abs difference of the two J-dot q-dot ways over the states: not 0,
//                     the time-variation product is not the classical acceleration of the
//                     origin; jdqd_fk_ns is (what rne's frame_jacobian_dot_qd returns)
// Input: the text model of dump.py; states: those of peer_model.hpp, cycled through. Each figure
// is the median over `reps` repetitions interleaved across the algorithms.
//
// Usage: bench_extra MODEL.txt [calls] [reps]      (calls default 200000, reps 5)
// Output: lines `name value`, ns per call unless the name says otherwise.
#include <pinocchio/multibody.hpp>
#include <pinocchio/algorithm/jacobian.hpp>
#include <pinocchio/algorithm/kinematics.hpp>
#include <pinocchio/algorithm/regressor.hpp>
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "peer_model.hpp"

namespace pin = pinocchio;

int main(int argc, char** argv) {
  if (argc < 2) { std::cerr << "usage: bench_extra MODEL.txt [calls] [reps]\n"; return 2; }
  const pin::Model model = peers::read_model(argv[1]);
  pin::Data data(model);
  const long calls = argc > 2 ? std::atol(argv[2]) : 200000;
  const int reps = argc > 3 ? std::atoi(argv[3]) : 5;
  const int states = peers::STATES;
  const peers::States seeded = peers::seeded_states(model);
  const std::vector<Eigen::VectorXd>& q = seeded.q;
  const std::vector<Eigen::VectorXd>& v = seeded.v;
  const std::vector<Eigen::VectorXd>& a = seeded.a;
  const auto bodies = static_cast<pin::JointIndex>(model.njoints);
  std::vector<pin::Data::Matrix6x> jacobians(bodies, pin::Data::Matrix6x::Zero(6, model.nv));
  pin::Data::Matrix6x dj = pin::Data::Matrix6x::Zero(6, model.nv);
  std::vector<pin::Motion::Vector6> jdqd(bodies), jdqd_fk(bodies);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.nv);
  double sink = 0;

  auto joint_jacobians = [&](int k) {
    pin::computeJointJacobians(model, data, q[k]);
    sink += data.J(0, 0);
  };
  auto all_jacobians = [&](int k) {
    pin::computeJointJacobians(model, data, q[k]);
    for (pin::JointIndex j = 1; j < bodies; ++j)
      pin::getJointJacobian(model, data, j, pin::LOCAL_WORLD_ALIGNED, jacobians[j]);
    sink += jacobians[bodies - 1](0, 0);
  };
  auto time_variation = [&](int k) {
    pin::computeJointJacobiansTimeVariation(model, data, q[k], v[k]);
    for (pin::JointIndex j = 1; j < bodies; ++j) {
      pin::getJointJacobianTimeVariation(model, data, j, pin::LOCAL_WORLD_ALIGNED, dj);
      jdqd[j].noalias() = dj * v[k];
    }
    sink += jdqd[bodies - 1][0];
  };
  auto classical = [&](int k) {
    pin::forwardKinematics(model, data, q[k], v[k], zero);
    for (pin::JointIndex j = 1; j < bodies; ++j)
      jdqd_fk[j] = pin::getClassicalAcceleration(model, data, j, pin::LOCAL_WORLD_ALIGNED).toVector();
    sink += jdqd_fk[bodies - 1][0];
  };
  auto regressor = [&](int k) {
    pin::computeJointTorqueRegressor(model, data, q[k], v[k], a[k]);
    sink += data.jointTorqueRegressor(0, 0);
  };

  double maxdiff = 0;
  for (int k = 0; k < states; ++k) {
    time_variation(k);
    classical(k);
    for (pin::JointIndex j = 1; j < bodies; ++j)
      maxdiff = std::max(maxdiff, (jdqd[j] - jdqd_fk[j]).cwiseAbs().maxCoeff());
  }

  struct Subject { const char* name; std::function<void(int)> call; std::vector<double> ns; };
  std::vector<Subject> subjects = {
      {"jacobians_ns", joint_jacobians, {}}, {"jacobians_all_ns", all_jacobians, {}},
      {"jdqd_ns", time_variation, {}},       {"jdqd_fk_ns", classical, {}},
      {"regressor_ns", regressor, {}}};
  for (auto& s : subjects)  // warm-up
    for (long i = 0; i < calls / 10; ++i) s.call(static_cast<int>(i % states));
  for (int r = 0; r < reps; ++r) {
    for (auto& s : subjects) {
      const auto start = std::chrono::steady_clock::now();
      for (long i = 0; i < calls; ++i) s.call(static_cast<int>(i % states));
      const auto stop = std::chrono::steady_clock::now();
      s.ns.push_back(std::chrono::duration<double, std::nano>(stop - start).count() / calls);
      std::cerr << s.name << " rep " << r << " " << s.ns.back() << "\n";
    }
  }
  std::cout << "nv " << model.nv << "\n" << "calls " << calls << "\n" << "reps " << reps << "\n";
  for (auto& s : subjects) {
    std::sort(s.ns.begin(), s.ns.end());
    std::cout << s.name << " " << s.ns[s.ns.size() / 2] << "\n";
  }
  std::cout << "jdqd_maxdiff " << maxdiff << "\n";
  std::cerr << "(checksum " << sink << ")\n";
}
