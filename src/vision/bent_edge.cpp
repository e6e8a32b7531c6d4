#include "bent_edge.hpp"

#include <cmath>

namespace telear::vision {

// The total-least-squares line a x + b y + c = 0 ((a, b) a unit normal) through `points`.
cv::Vec3d fit_edge_line(const std::vector<cv::Point2d>& points) {
  cv::Point2d mean(0.0, 0.0);
  for (const cv::Point2d& q : points) mean += q / static_cast<double>(points.size());
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (const cv::Point2d& q : points) {
    const cv::Point2d d = q - mean;
    sxx += d.x * d.x;
    sxy += d.x * d.y;
    syy += d.y * d.y;
  }
  // The normal is the eigenvector of the scatter's smaller eigenvalue: the direction at
  // angle theta + 90 deg, theta the principal axis' angle.
  const double theta = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  const cv::Point2d normal(-std::sin(theta), std::cos(theta));
  return {normal.x, normal.y, -normal.dot(mean)};
}

namespace {

// An edge's points against the straight line through them: the distance d from it, along the
// normal that points `towards`, and t along it from `near`.
struct EdgeFrame {
  cv::Point2d normal, along, on_line;  // on_line: `near` moved onto the line
  double offset = 0.0;                 // normal . q + offset = d
};

EdgeFrame edge_frame(const std::vector<cv::Point2d>& points, const cv::Point2d& near,
                     const cv::Point2d& towards) {
  const cv::Vec3d line = fit_edge_line(points);
  EdgeFrame f;
  const double sign = line[0] * towards.x + line[1] * towards.y < 0.0 ? -1.0 : 1.0;
  f.normal = sign * cv::Point2d(line[0], line[1]);
  f.offset = sign * line[2];
  f.along = cv::Point2d(-f.normal.y, f.normal.x);
  f.on_line = near - (f.normal.dot(near) + f.offset) * f.normal;
  return f;
}

}  // namespace

std::optional<double> edge_bend(const std::vector<cv::Point2d>& points, const cv::Point2d& near,
                                const cv::Point2d& towards) {
  if (points.size() < 6) return std::nullopt;
  const EdgeFrame f = edge_frame(points, near, towards);
  cv::Matx33d normal_matrix = cv::Matx33d::zeros();
  cv::Vec3d rhs(0.0, 0.0, 0.0);
  for (const cv::Point2d& q : points) {
    const double t = (q - near).dot(f.along);
    const cv::Vec3d basis(1.0, t, t * t);
    normal_matrix += basis * basis.t();
    rhs += (f.normal.dot(q) + f.offset) * basis;
  }
  cv::Vec3d abc;
  if (!cv::solve(normal_matrix, rhs, abc, cv::DECOMP_CHOLESKY)) return std::nullopt;
  return abc[2];
}

// d - bend t^2 = a + b t fitted; the tangent at t = 0 passes through on_line + a normal in
// direction along + b normal.
cv::Vec3d edge_tangent(const std::vector<cv::Point2d>& points, const cv::Point2d& near,
                       const cv::Point2d& towards, double bend) {
  const EdgeFrame f = edge_frame(points, near, towards);
  cv::Matx22d normal_matrix = cv::Matx22d::zeros();
  cv::Vec2d rhs(0.0, 0.0);
  for (const cv::Point2d& q : points) {
    const double t = (q - near).dot(f.along);
    const cv::Vec2d basis(1.0, t);
    normal_matrix += basis * basis.t();
    rhs += (f.normal.dot(q) + f.offset - bend * t * t) * basis;
  }
  cv::Vec2d ab;
  if (!cv::solve(normal_matrix, rhs, ab, cv::DECOMP_CHOLESKY)) return fit_edge_line(points);
  const cv::Point2d point = f.on_line + ab[0] * f.normal;
  cv::Point2d tangent_normal = f.normal - ab[1] * f.along;
  tangent_normal /= cv::norm(tangent_normal);
  return {tangent_normal.x, tangent_normal.y, -tangent_normal.dot(point)};
}

}  // namespace telear::vision
