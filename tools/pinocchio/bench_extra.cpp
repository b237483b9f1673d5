// Times the Pinocchio algorithms that rne's kinematics and identification kernels are compared
// with (issues 13, 14), which the shared timing programs do not cover:
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
// Input: the text model of dump.py (one line per joint: KIND [axis] parent R p mass com I).
// States: std::mt19937(42), q = 3 U(-1, 1), v and a = U(-1, 1), 1024 of them cycled through;
// each figure is the median over `reps` repetitions interleaved across the algorithms.
// Output: lines `name value`, ns per call unless the name says otherwise.
#include <pinocchio/multibody.hpp>
#include <pinocchio/algorithm/jacobian.hpp>
#include <pinocchio/algorithm/kinematics.hpp>
#include <pinocchio/algorithm/regressor.hpp>
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <random>
#include <string>
#include <vector>

namespace pin = pinocchio;

static pin::JointModel joint_of(const std::string& kind, const Eigen::Vector3d& axis) {
  if (kind == "RX") return pin::JointModelRX();
  if (kind == "RY") return pin::JointModelRY();
  if (kind == "RZ") return pin::JointModelRZ();
  if (kind == "PX") return pin::JointModelPX();
  if (kind == "PY") return pin::JointModelPY();
  if (kind == "PZ") return pin::JointModelPZ();
  if (kind == "RU") return pin::JointModelRevoluteUnaligned(axis);
  if (kind == "PU") return pin::JointModelPrismaticUnaligned(axis);
  std::cerr << "unknown joint kind " << kind << "\n";
  std::exit(2);
}

static pin::Model read_model(const char* path) {
  std::ifstream in(path);
  if (!in) { std::cerr << "cannot read " << path << "\n"; std::exit(2); }
  int joints = 0;
  in >> joints;
  pin::Model model;
  for (int j = 0; j < joints; ++j) {
    std::string kind;
    Eigen::Vector3d axis = Eigen::Vector3d::Zero(), p, com;
    Eigen::Matrix3d rotation, inertia;
    double parent = 0, mass = 0;
    in >> kind;
    if (kind == "RU" || kind == "PU") in >> axis.x() >> axis.y() >> axis.z();
    in >> parent;
    for (int r = 0; r < 3; ++r) for (int c = 0; c < 3; ++c) in >> rotation(r, c);
    in >> p.x() >> p.y() >> p.z() >> mass >> com.x() >> com.y() >> com.z();
    for (int r = 0; r < 3; ++r) for (int c = 0; c < 3; ++c) in >> inertia(r, c);
    if (!in) { std::cerr << "bad model line " << j + 1 << " in " << path << "\n"; std::exit(2); }
    const auto id = model.addJoint(static_cast<pin::JointIndex>(parent), joint_of(kind, axis),
                                   pin::SE3(rotation, p), "joint" + std::to_string(j + 1));
    model.appendBodyToJoint(id, pin::Inertia(mass, com, inertia), pin::SE3::Identity());
  }
  return model;
}

int main(int argc, char** argv) {
  if (argc < 2) { std::cerr << "usage: bench_extra MODEL.txt [calls] [reps]\n"; return 2; }
  const pin::Model model = read_model(argv[1]);
  pin::Data data(model);
  const long calls = argc > 2 ? std::atol(argv[2]) : 200000;
  const int reps = argc > 3 ? std::atoi(argv[3]) : 5;
  const int states = 1024;
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<Eigen::VectorXd> q(states), v(states), a(states);
  for (int k = 0; k < states; ++k) {
    q[k].resize(model.nq);
    v[k].resize(model.nv);
    a[k].resize(model.nv);
    for (int i = 0; i < model.nq; ++i) q[k][i] = 3.0 * uniform(rng);
    for (int i = 0; i < model.nv; ++i) { v[k][i] = uniform(rng); a[k][i] = uniform(rng); }
  }
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
