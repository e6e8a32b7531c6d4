#include "telear/geometry/allowed_collisions.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

#include "telear/core/number_format.hpp"
#include "telear/core/random_configuration.hpp"
#include "telear/core/yaml_reader.hpp"
#include "telear/geometry/collision_checker.hpp"

namespace telear::geometry {
namespace {

std::pair<std::string, std::string> ordered(const std::string& a, const std::string& b) {
  return a < b ? std::make_pair(a, b) : std::make_pair(b, a);
}

bool before(const AllowedPair& p, const std::pair<std::string, std::string>& key) {
  return std::tie(p.a, p.b) < std::tie(key.first, key.second);
}

}  // namespace

const char* to_string(AllowedReason reason) {
  switch (reason) {
    case AllowedReason::kAdjacent:
      return "adjacent";
    case AllowedReason::kAlways:
      return "always";
    case AllowedReason::kNever:
      return "never";
    case AllowedReason::kConstant:
      return "constant";
    case AllowedReason::kUser:
      return "user";
  }
  return "?";
}

std::optional<AllowedReason> allowed_reason_from_string(const std::string& text) {
  for (AllowedReason r : {AllowedReason::kAdjacent, AllowedReason::kAlways, AllowedReason::kNever,
                          AllowedReason::kConstant, AllowedReason::kUser}) {
    if (text == to_string(r)) return r;
  }
  return std::nullopt;
}

void AllowedCollisionMatrix::allow(const std::string& a, const std::string& b,
                                   AllowedReason reason) {
  const auto key = ordered(a, b);
  auto it = std::lower_bound(pairs_.begin(), pairs_.end(), key, before);
  if (it != pairs_.end() && it->a == key.first && it->b == key.second) return;
  pairs_.insert(it, AllowedPair{key.first, key.second, reason});
}

bool AllowedCollisionMatrix::allowed(const std::string& a, const std::string& b) const {
  const auto key = ordered(a, b);
  auto it = std::lower_bound(pairs_.begin(), pairs_.end(), key, before);
  return it != pairs_.end() && it->a == key.first && it->b == key.second;
}

std::string AllowedCollisionMatrix::to_yaml() const {
  std::ostringstream out;
  for (const AllowedPair& p : pairs_) {
    out << "- [" << p.a << ", " << p.b << ", " << to_string(p.reason) << "]\n";
  }
  return out.str();
}

Result<AllowedCollisionMatrix> AllowedCollisionMatrix::from_yaml(const std::string& text,
                                                                 const std::string& source) {
  auto loaded = core::load_yaml(text, source + ": ");
  if (!loaded) return loaded.error();
  const YAML::Node root = *loaded;
  AllowedCollisionMatrix m;
  if (!root || root.IsNull()) return m;
  if (!root.IsSequence()) return Error{source + ": must be a list of [body, body, reason]"};
  for (std::size_t i = 0; i < root.size(); ++i) {
    const YAML::Node e = root[i];
    const std::string where = source + "[" + std::to_string(i) + "]";
    if (!e.IsSequence() || e.size() < 2 || e.size() > 3 || !e[0].IsScalar() || !e[1].IsScalar()) {
      return Error{where + ": must be [body, body] or [body, body, reason]"};
    }
    AllowedReason reason = AllowedReason::kUser;
    if (e.size() == 3) {
      const std::string r = e[2].IsScalar() ? e[2].Scalar() : "?";
      const std::optional<AllowedReason> parsed = allowed_reason_from_string(r);
      if (!parsed) {
        return Error{where + ": unknown reason '" + r +
                     "' (adjacent, always, never, constant or user)"};
      }
      reason = *parsed;
    }
    m.allow(e[0].Scalar(), e[1].Scalar(), reason);
  }
  return m;
}

Status AllowedCollisionOptions::validate() const {
  if (samples < 1) return Error{"samples must be at least 1, got " + std::to_string(samples)};
  if (!(gripper_fraction >= 0.0 && gripper_fraction <= 1.0)) {
    return Error{"gripper_fraction must lie in [0, 1]"};
  }
  if (!(constant_tolerance_m >= 0.0 && std::isfinite(constant_tolerance_m))) {
    return Error{"constant_tolerance_m must be finite and at least 0, got " +
                 core::format_number(constant_tolerance_m)};
  }
  return Status::Ok();
}

AllowedCollisionMatrix adjacent_collisions(const RobotCollisionModel& robot) {
  AllowedCollisionMatrix m;
  for (std::size_t a = 0; a < robot.bodies.size(); ++a) {
    for (std::size_t b = a + 1; b < robot.bodies.size(); ++b) {
      if (std::abs(robot.bodies[a].frame - robot.bodies[b].frame) <= 1) {
        m.allow(robot.bodies[a].name, robot.bodies[b].name, AllowedReason::kAdjacent);
      }
    }
  }
  return m;
}

Result<AllowedCollisionMatrix> compute_allowed_collisions(const RobotCollisionModel& robot,
                                                          const AllowedCollisionOptions& options) {
  if (Status s = options.validate(); !s) return Error{"allowed collisions: " + s.error().message};
  AllowedCollisionMatrix adjacent = adjacent_collisions(robot);
  // A checker with no workspace and only the adjacent pairs allowed: its pairs are the
  // candidates.
  Result<CollisionChecker> checker = CollisionChecker::create(robot, core::Workspace{}, adjacent);
  if (!checker) return checker.error();
  const std::vector<CollisionPair> pairs = checker->pairs();
  const auto rigid = [&](int body) {
    return robot.bodies[static_cast<std::size_t>(body)].motion == CollisionBody::Motion::kRigid;
  };
  std::vector<int> hits(pairs.size(), 0);
  // Constant-distance candidates: rigid pairs (a finger also moves with the opening, which the
  // samples hold fixed) not yet seen in contact or with a distance range above the tolerance.
  // A pair drops out at its first sample outside the range, so only the constant pairs are
  // measured at every sample.
  std::vector<char> constant(pairs.size(), 0);
  std::vector<double> d_min(pairs.size(), std::numeric_limits<double>::infinity());
  std::vector<double> d_max(pairs.size(), -std::numeric_limits<double>::infinity());
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    constant[p] = options.allow_constant && rigid(pairs[p].body) && rigid(pairs[p].other_body);
  }
  std::mt19937_64 rng(options.seed);
  for (int i = 0; i < options.samples; ++i) {
    checker->set_configuration(core::random_configuration(*robot.model, rng),
                               options.gripper_fraction);
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      if (checker->in_contact(pairs[p])) {
        ++hits[p];
        constant[p] = 0;
        continue;
      }
      if (!constant[p]) continue;
      const double d = checker->distance(pairs[p]).distance_m;
      d_min[p] = std::min(d_min[p], d);
      d_max[p] = std::max(d_max[p], d);
      if (!(d > 0.0) || d_max[p] - d_min[p] > options.constant_tolerance_m) constant[p] = 0;
    }
  }
  AllowedCollisionMatrix m = adjacent;
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const std::string& a = robot.bodies[static_cast<std::size_t>(pairs[p].body)].name;
    const std::string& b = robot.bodies[static_cast<std::size_t>(pairs[p].other_body)].name;
    if (hits[p] == options.samples) m.allow(a, b, AllowedReason::kAlways);
    if (constant[p]) m.allow(a, b, AllowedReason::kConstant);
    if (hits[p] == 0 && options.allow_never) m.allow(a, b, AllowedReason::kNever);
  }
  return m;
}

}  // namespace telear::geometry
