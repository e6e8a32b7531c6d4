#pragma once
// A trapezoidal velocity profile of a normalized path parameter s in [0, 1] over a duration T,
// the time scaling that every segment of a joint trajectory shares among its joints.
//
// A segment moves joint j from q0_j to q1_j as q_j(t) = q0_j + D_j s(t), D_j = q1_j - q0_j, so
// every joint starts and stops together and the path is the straight line in joint space.
// With s' = ds/dt, joint j's velocity is D_j s' and its acceleration D_j s''. The joint limits
// |D_j s'| <= v_j and |D_j s''| <= a_j for every j become limits on s:
//
//   s' <= 1 / alpha,  alpha = max_j |D_j| / v_j   (s)     time at full speed, no ramps
//   s'' <= 1 / beta,  beta = max_j |D_j| / a_j    (s^2)
//
// s accelerates at 1 / beta for t_a, cruises at v_p = 1 / (T - t_a), and decelerates at
// 1 / beta for t_a. The shortest duration is alpha + beta / alpha when the cruise speed is
// reached (alpha^2 >= beta) and 2 sqrt(beta) otherwise (a triangle). For any longer T the
// acceleration stays at 1 / beta and the cruise speed drops:
//
//   t_a = 2 beta / (T + sqrt(T^2 - 4 beta))   (the small root, written without cancellation)
//
// which keeps s' <= 1 / alpha, because v_p = t_a / beta decreases as T grows.

namespace telear::core {

struct TrapezoidalProfile {
  double duration = 0.0;      // T, s
  double ramp = 0.0;          // t_a, s; <= T / 2
  double peak_rate = 0.0;     // v_p = ds/dt while cruising, 1/s
  double acceleration = 0.0;  // d2s/dt2 while ramping, 1/s^2

  // The fastest profile within the limits alpha (s) and beta (s^2), stretched to at least
  // `min_duration` seconds. alpha == beta == 0 (no motion) yields duration = min_duration and
  // a profile that stays at s = 0; sample() then reports s = 0 throughout.
  static TrapezoidalProfile Fastest(double alpha, double beta, double min_duration = 0.0);

  // s, ds/dt and d2s/dt2 at local time t, clamped to [0, duration]. s is exactly 0 at t <= 0
  // and exactly 1 at t >= duration (for a moving profile).
  void sample(double t, double& s, double& s_dot, double& s_ddot) const;
};

}  // namespace telear::core
