#include "telear/core/plan_hash.hpp"

#include <bit>
#include <cmath>
#include <cstdint>

#include "telear/core/joint_limits.hpp"
#include "telear/core/number_format.hpp"
#include "telear/core/sha256.hpp"

namespace telear::core {
namespace {

// Explicit little-endian bytes, whatever the host's order.
class CanonicalWriter {
 public:
  void u8(std::uint8_t v) { bytes_.push_back(static_cast<char>(v)); }
  void u32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i) u8(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void u64(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) u8(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
  void size(std::size_t n) { u32(static_cast<std::uint32_t>(n)); }
  void text(std::string_view s) {
    size(s.size());
    bytes_.append(s);
  }
  void joints(const Eigen::VectorXd& q) {
    for (Eigen::Index j = 0; j < q.size(); ++j) f64(q[j]);
  }
  std::string take() { return std::move(bytes_); }
  void reserve(std::size_t n) { bytes_.reserve(n); }

 private:
  std::string bytes_;
};

}  // namespace

Result<std::string> canonical_plan_bytes(const Trajectory& trajectory) {
  const double duration = trajectory.duration();
  if (!std::isfinite(duration) || duration < 0.0) {  // never from a validated plan; not hashed
    return Error{"the trajectory's duration is not a finite number of seconds: " +
                 format_number(duration)};
  }
  // floor(100 duration) + 1 samples on the grid, one more for the end when off the grid.
  const double grid = std::floor(duration * kPlanHashRateHz);
  if (grid + 2.0 > kMaxPlanHashSamples) {
    return Error{"the " + format_seconds(duration) + " trajectory is too long to hash: at " +
                 format_number(kPlanHashRateHz) + " Hz it needs " +
                 format_number(grid + 2.0, "%.0f") + " samples, more than the maximum of " +
                 std::to_string(kMaxPlanHashSamples)};
  }
  const auto last_index = static_cast<std::uint32_t>(grid);
  const bool end_sample = static_cast<double>(last_index) / kPlanHashRateHz < duration;
  const std::uint32_t samples = last_index + 1 + (end_sample ? 1 : 0);

  CanonicalWriter out;
  const int dof = trajectory.dof();
  out.reserve(256 + static_cast<std::size_t>(samples) * static_cast<std::size_t>(dof) * 8 +
              trajectory.waypoints().size() * static_cast<std::size_t>(dof + 3) * 8);
  out.text(kTrajectoryAlgorithm);
  out.u32(static_cast<std::uint32_t>(dof));
  for (int j = 0; j < dof; ++j) {
    out.f64(trajectory.velocity_limits()[j]);
    out.f64(trajectory.acceleration_limits()[j]);
  }
  out.f64(trajectory.options().velocity_scale);
  out.f64(trajectory.options().acceleration_scale);
  out.size(trajectory.waypoints().size());
  for (const JointWaypoint& w : trajectory.waypoints()) {
    out.joints(w.q);
    // The flags: what the operator asked (via, cartesian) and which points the expansion of
    // a Cartesian segment inserted.
    out.u8(
        static_cast<std::uint8_t>((w.via ? 1 : 0) | (w.cartesian ? 2 : 0) | (w.expanded ? 4 : 0)));
    out.f64(w.min_duration);
    out.u8(w.gripper ? 1 : 0);
    out.f64(w.gripper.value_or(0.0));
  }
  out.f64(duration);
  out.u32(samples);
  Eigen::VectorXd q(dof);
  for (std::uint32_t i = 0; i <= last_index; ++i) {
    trajectory.sample(static_cast<double>(i) / kPlanHashRateHz, q);
    out.joints(q);
  }
  if (end_sample) {
    trajectory.sample(duration, q);
    out.joints(q);
  }
  const std::vector<GripperEvent> events = trajectory.gripper_events();
  out.size(events.size());
  for (const GripperEvent& e : events) {
    out.f64(e.time);
    out.f64(e.opening);
  }
  return out.take();
}

Result<std::string> plan_hash(const Trajectory& trajectory) {
  auto bytes = canonical_plan_bytes(trajectory);
  if (!bytes) return bytes.error();
  return sha256_hex(*bytes);
}

}  // namespace telear::core
