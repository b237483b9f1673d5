// What every peer timing program shares: the model written by dump.py, the seeded states the
// programs time over, and the timer. Include it after Pinocchio's own headers (bench_cg.cpp
// must include pinocchio/codegen/cppadcg-algo.hpp before any other Pinocchio header).
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include <pinocchio/multibody.hpp>

namespace peers {

// One joint of the text model: the joint model for its KIND ("RX" ... "PZ", or "RU"/"PU"
// with their unit axis).
inline pinocchio::JointModel joint_of(const std::string& kind, const Eigen::Vector3d& axis) {
  if (kind == "RX") return pinocchio::JointModelRX();
  if (kind == "RY") return pinocchio::JointModelRY();
  if (kind == "RZ") return pinocchio::JointModelRZ();
  if (kind == "PX") return pinocchio::JointModelPX();
  if (kind == "PY") return pinocchio::JointModelPY();
  if (kind == "PZ") return pinocchio::JointModelPZ();
  if (kind == "RU") return pinocchio::JointModelRevoluteUnaligned(axis);
  if (kind == "PU") return pinocchio::JointModelPrismaticUnaligned(axis);
  std::cerr << "unknown joint kind " << kind << "\n";
  std::exit(2);
}

// The model of dump.py's text file at `path`: one line per joint, KIND [axis] parent R p mass
// com I, each joint carrying one body.
inline pinocchio::Model read_model(const char* path) {
  std::ifstream in(path);
  if (!in) { std::cerr << "cannot read " << path << "\n"; std::exit(2); }
  int joints = 0;
  in >> joints;
  pinocchio::Model model;
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
    const auto id = model.addJoint(static_cast<pinocchio::JointIndex>(parent), joint_of(kind, axis),
                                   pinocchio::SE3(rotation, p), "joint" + std::to_string(j + 1));
    model.appendBodyToJoint(id, pinocchio::Inertia(mass, com, inertia), pinocchio::SE3::Identity());
  }
  return model;
}

// The states every program times over, cycled through: STATES of them from std::mt19937(42),
// per state first every entry of q as 3 U(-1, 1), then v_i and a_i as U(-1, 1) in turn. The
// same generator and order in every program, so that their figures are over the same states.
constexpr int STATES = 1024;

struct States {
  std::vector<Eigen::VectorXd> q, v, a;
};

inline States seeded_states(const pinocchio::Model& model) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  States s;
  s.q.resize(STATES);
  s.v.resize(STATES);
  s.a.resize(STATES);
  for (int k = 0; k < STATES; ++k) {
    s.q[k].resize(model.nq);
    s.v[k].resize(model.nv);
    s.a[k].resize(model.nv);
    for (int i = 0; i < model.nq; ++i) s.q[k][i] = 3.0 * uniform(rng);
    for (int i = 0; i < model.nv; ++i) { s.v[k][i] = uniform(rng); s.a[k][i] = uniform(rng); }
  }
  return s;
}

// The mean time of `calls` calls f(0), f(1), ..., in ns per call (f takes the call's index and
// picks its state as index % STATES).
template <class F> double ns_per_call(F& f, long calls) {
  const auto start = std::chrono::steady_clock::now();
  for (long i = 0; i < calls; ++i) f(static_cast<int>(i));
  const auto stop = std::chrono::steady_clock::now();
  return std::chrono::duration<double, std::nano>(stop - start).count() / calls;
}

// The median of `values` (mean of the middle two for an even count).
inline double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace peers
