#include "synthetic_marker.hpp"

#include <opencv2/aruco.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace telear::test {

cv::Mat synthetic_marker_image(int width, int height,
                               const std::array<Eigen::Vector2d, 4>& corners_px,
                               const SyntheticMarkerOptions& options) {
  constexpr int kCell = 64;  // source pixels per cell
  cv::Mat bits;
  cv::aruco::drawMarker(cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_50), options.id,
                        6 * kCell, bits, 1);
  cv::Mat source;
  cv::copyMakeBorder(bits, source, kCell, kCell, kCell, kCell, cv::BORDER_CONSTANT, 255);
  // Source pixel i covers [i - 0.5, i + 0.5): the black square spans kCell - 0.5 .. 7 kCell - 0.5.
  const float lo = kCell - 0.5f, hi = 7 * kCell - 0.5f;
  const std::vector<cv::Point2f> from = {{lo, lo}, {hi, lo}, {hi, hi}, {lo, hi}};
  const int S = options.supersample;
  std::vector<cv::Point2f> to;
  for (const Eigen::Vector2d& c : corners_px) {
    to.emplace_back(static_cast<float>(S * (c.x() + 0.5) - 0.5),
                    static_cast<float>(S * (c.y() + 0.5) - 0.5));
  }
  const cv::Mat H = cv::getPerspectiveTransform(from, to);
  cv::Mat high(S * height, S * width, CV_8UC1, cv::Scalar(options.background));
  cv::warpPerspective(source, high, H, high.size(), cv::INTER_LINEAR, cv::BORDER_TRANSPARENT);
  cv::Mat image;
  cv::resize(high, image, cv::Size(width, height), 0, 0, cv::INTER_AREA);
  if (options.noise_sigma > 0.0) {
    cv::Mat noise(image.size(), CV_32F);
    cv::RNG rng(options.seed);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, options.noise_sigma);
    cv::Mat value;
    image.convertTo(value, CV_32F);
    value += noise;
    value.convertTo(image, CV_8U);  // rounds and saturates
  }
  return image;
}

}  // namespace telear::test
