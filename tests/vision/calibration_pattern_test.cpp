// Pattern specs, object points, and detection accuracy on rendered images with known points.

#include "telear/vision/calibration_pattern.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>

#include "rendered_pattern.hpp"

namespace telear::vision {
namespace {

using ::testing::HasSubstr;

TEST(CalibrationPattern, ParsesSpecs) {
  const auto board = parse_calibration_pattern("chessboard:9x6:0.025");
  ASSERT_TRUE(board.ok()) << board.error().message;
  EXPECT_EQ(board->kind, PatternKind::kChessboard);
  EXPECT_EQ(board->cols, 9);
  EXPECT_EQ(board->rows, 6);
  EXPECT_EQ(board->spacing, 0.025);
  EXPECT_EQ(board->point_count(), 54);
  EXPECT_EQ(board->spec(), "chessboard:9x6:0.025");

  const auto circles = parse_calibration_pattern("circles:4x11:0.02");
  ASSERT_TRUE(circles.ok()) << circles.error().message;
  EXPECT_EQ(circles->kind, PatternKind::kAsymmetricCircles);
  EXPECT_EQ(circles->size(), cv::Size(4, 11));
  EXPECT_EQ(circles->spec(), "circles:4x11:0.02");

  EXPECT_EQ(parse_calibration_pattern("chessboard:9x6:1")->spec(), "chessboard:9x6:1");
}

TEST(CalibrationPattern, WrongSpecsSayWhatIsWrongAndShowTheForm) {
  struct Case {
    std::string spec;
    std::string message;
  };
  const Case cases[] = {
      {"chessboard:9x6", "pattern 'chessboard:9x6': not three fields separated by ':'"},
      {"checkerboard:9x6:0.02", "unknown kind 'checkerboard'"},
      {"chessboard:9*6:0.02", "size '9*6' is not COLSxROWS"},
      {"chessboard:9x:0.02", "size '9x' is not COLSxROWS"},
      {"chessboard:9x6x2:0.02", "size '9x6x2' is not COLSxROWS"},
      {"chessboard:2x6:0.02", "size 2x6 is out of range: a chessboard needs 3 to 200"},
      {"chessboard:9x600:0.02", "size 9x600 is out of range"},
      {"circles:1x11:0.02", "a circle grid needs 2 to 200 circles per row"},
      {"chessboard:9x6:0", "spacing '0' is not a positive number"},
      {"chessboard:9x6:-0.02", "spacing '-0.02' is not a positive number"},
      {"chessboard:9x6:2cm", "spacing '2cm' is not a positive number (the square side"},
      {"chessboard:9x6:inf", "spacing 'inf' is not a positive number"},
  };
  for (const Case& c : cases) {
    const auto r = parse_calibration_pattern(c.spec);
    ASSERT_FALSE(r.ok()) << c.spec;
    EXPECT_THAT(r.error().message, HasSubstr(c.message)) << c.spec;
  }
  EXPECT_THAT(parse_calibration_pattern("chessboard:9*6:0.02").error().message,
              HasSubstr("expected chessboard:COLSxROWS:SQUARE_M, e.g. chessboard:9x6:0.025"));
}

TEST(CalibrationPattern, ObjectPointsFollowOpenCVsLayouts) {
  const auto board = pattern_object_points(*parse_calibration_pattern("chessboard:9x6:0.5"));
  ASSERT_EQ(board.size(), 54u);
  EXPECT_EQ(board[0], cv::Point3f(0, 0, 0));
  EXPECT_EQ(board[1], cv::Point3f(0.5f, 0, 0));
  EXPECT_EQ(board[9], cv::Point3f(0, 0.5f, 0));
  EXPECT_EQ(board[53], cv::Point3f(4.0f, 2.5f, 0));

  const auto grid = pattern_object_points(*parse_calibration_pattern("circles:4x11:0.5"));
  ASSERT_EQ(grid.size(), 44u);
  EXPECT_EQ(grid[0], cv::Point3f(0, 0, 0));
  EXPECT_EQ(grid[1], cv::Point3f(1.0f, 0, 0));      // 2 s along a row
  EXPECT_EQ(grid[4], cv::Point3f(0.5f, 0.5f, 0));   // the next row, shifted by s
  EXPECT_EQ(grid[43], cv::Point3f(3.0f, 5.0f, 0));  // row 10 is not shifted
}

// Detected points vs the truth: the closest true point (OpenCV may number a board from
// either end) and a homography fit in detection order (the order matches the object points).
void expect_accurate(const std::vector<cv::Point2f>& detected, const CalibrationPattern& pattern,
                     const cv::Matx33d& H, double tolerance_px) {
  const std::vector<cv::Point2d> truth = test::true_image_points(pattern, H);
  ASSERT_EQ(detected.size(), truth.size());
  double worst = 0.0;
  for (const cv::Point2f& d : detected) {
    double nearest = 1e9;
    for (const cv::Point2d& t : truth) nearest = std::min(nearest, cv::norm(cv::Point2d(d) - t));
    worst = std::max(worst, nearest);
  }
  EXPECT_LT(worst, tolerance_px);

  std::vector<cv::Point2f> object;
  for (const cv::Point3f& p : pattern_object_points(pattern)) object.emplace_back(p.x, p.y);
  const cv::Mat fit = cv::findHomography(object, detected, 0);
  std::vector<cv::Point2f> mapped;
  cv::perspectiveTransform(object, mapped, fit);
  double residual = 0.0;
  for (std::size_t i = 0; i < mapped.size(); ++i) {
    residual = std::max(residual, static_cast<double>(cv::norm(mapped[i] - detected[i])));
  }
  EXPECT_LT(residual, tolerance_px);
}

TEST(CalibrationPattern, ChessboardCornersAreFoundToATenthOfAPixel) {
  const CalibrationPattern pattern = *parse_calibration_pattern("chessboard:9x6:0.03");
  const cv::Size size(640, 480);
  for (const auto& [width, tilt, roll] :
       {std::tuple{420.0, 0.0, 7.0}, std::tuple{300.0, 35.0, 10.0},
        std::tuple{200.0, -45.0, -20.0}}) {
    // (Not axis-aligned: the renderer quantizes an axis-aligned edge to 1/6 px.)
    const cv::Matx33d H = test::view_homography(pattern, size, width, tilt, roll);
    const cv::Mat image = test::render_pattern(pattern, H, size);
    const auto corners = detect_pattern(image, pattern);
    ASSERT_TRUE(corners.ok()) << width << " " << tilt << ": " << corners.error().message;
    SCOPED_TRACE(::testing::Message() << "width " << width << " tilt " << tilt);
    expect_accurate(*corners, pattern, H, 0.1);
  }
}

TEST(CalibrationPattern, SubpixelWindowFollowsTheCornerSpacing) {
  const CalibrationPattern pattern = *parse_calibration_pattern("chessboard:4x3:1");
  std::vector<cv::Point2f> corners;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) corners.emplace_back(100.0f + 20.0f * c, 50.0f + 30.0f * r);
  }
  EXPECT_EQ(subpixel_half_window(corners, pattern), 6);  // 0.3 x 20 px
  for (cv::Point2f& p : corners) p *= 10.0f;
  EXPECT_EQ(subpixel_half_window(corners, pattern), 15);  // clamped
  for (cv::Point2f& p : corners) p *= 0.01f;
  EXPECT_EQ(subpixel_half_window(corners, pattern), 2);  // clamped
}

TEST(CalibrationPattern, AsymmetricCircleCentresAreFound) {
  const CalibrationPattern pattern = *parse_calibration_pattern("circles:4x11:0.02");
  const cv::Size size(640, 480);
  // Affine views (no perspective), where a circle's centroid is exactly its centre's image.
  const double a = 0.3;
  const cv::Matx33d H(1600.0 * std::cos(a), -1600.0 * std::sin(a), 260.0, 1400.0 * std::sin(a),
                      1400.0 * std::cos(a), 70.0, 0.0, 0.0, 1.0);
  const cv::Mat image = test::render_pattern(pattern, H, size);
  const auto centres = detect_pattern(image, pattern);
  ASSERT_TRUE(centres.ok()) << centres.error().message;
  expect_accurate(*centres, pattern, H, 0.1);
}

TEST(CalibrationPattern, NothingIsFoundWhereThereIsNoPattern) {
  const CalibrationPattern board = *parse_calibration_pattern("chessboard:9x6:0.03");
  cv::Mat blank(480, 640, CV_8UC3, cv::Scalar(90, 120, 150));
  const auto none = detect_pattern(blank, board);
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.error().message,
            "no pattern found (the whole chessboard:9x6:0.03 must be visible; COLSxROWS counts "
            "inner corners)");
  // A smaller board is not this pattern.
  const CalibrationPattern other = *parse_calibration_pattern("chessboard:7x5:0.03");
  const cv::Mat image = test::render_pattern(
      other, test::view_homography(other, {640, 480}, 300.0, 20.0), {640, 480});
  EXPECT_FALSE(detect_pattern(image, board).ok());
  const CalibrationPattern circles = *parse_calibration_pattern("circles:4x11:0.02");
  EXPECT_FALSE(detect_pattern(blank, circles).ok());
}

TEST(CalibrationPattern, ABoardLargerThanThePatternIsRecognised) {
  // On real images findChessboardCorners finds an 8x6 pattern on part of a 9x6 board (21 of
  // OpenCV's 26 stereo images); larger_chessboard() tells the board's real size.
  const CalibrationPattern board = *parse_calibration_pattern("chessboard:9x6:0.03");
  const cv::Mat image = test::render_pattern(
      board, test::view_homography(board, {640, 480}, 380.0, 0.0, 6.0), {640, 480});
  EXPECT_FALSE(larger_chessboard(image, board).has_value());
  for (const char* spec : {"chessboard:8x6:0.03", "chessboard:7x5:0.03"}) {
    const auto size = larger_chessboard(image, *parse_calibration_pattern(spec));
    ASSERT_TRUE(size.has_value()) << spec;
    EXPECT_EQ(*size, cv::Size(9, 6)) << spec;
  }
  const auto transposed =
      larger_chessboard(image, *parse_calibration_pattern("chessboard:5x7:0.03"));
  ASSERT_TRUE(transposed.has_value());
  EXPECT_EQ(*transposed, cv::Size(6, 9));  // in the pattern's orientation
}

}  // namespace
}  // namespace telear::vision
