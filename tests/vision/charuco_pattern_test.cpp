// ChArUco patterns: spec parsing and its errors, object points and layout against OpenCV's
// own board, and corner detection on OpenCV's board image, whole and in part.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/aruco/charuco.hpp>
#include <opencv2/imgproc.hpp>

#include "telear/vision/calibration_images.hpp"
#include "telear/vision/calibration_pattern.hpp"
#include "telear/vision/charuco_board.hpp"
#include "telear/vision/image_file.hpp"
#include "test_util/temp_dir.hpp"

namespace telear::vision {
namespace {

using ::testing::HasSubstr;

CalibrationPattern charuco(const std::string& spec) {
  auto pattern = parse_calibration_pattern(spec);
  EXPECT_TRUE(pattern.ok()) << pattern.error().message;
  return *pattern;
}

TEST(CharucoPattern, ParsesAndRoundTrips) {
  const CalibrationPattern board = charuco("charuco:7x5:0.04:0.03:4x4_50");
  EXPECT_EQ(board.kind, PatternKind::kCharuco);
  EXPECT_EQ(board.squares_x(), 7);
  EXPECT_EQ(board.squares_y(), 5);
  EXPECT_EQ(board.size(), cv::Size(6, 4));  // inner corners
  EXPECT_EQ(board.point_count(), 24);
  EXPECT_EQ(board.spacing, 0.04);
  EXPECT_EQ(board.marker, 0.03);
  EXPECT_EQ(board.dictionary, "4x4_50");
  EXPECT_EQ(board.spec(), "charuco:7x5:0.04:0.03:4x4_50");

  // OpenCV's names are accepted too, and written back in the short form.
  EXPECT_EQ(charuco("charuco:12x9:0.03:0.022:DICT_APRILTAG_36h11").spec(),
            "charuco:12x9:0.03:0.022:apriltag_36h11");
  EXPECT_EQ(charuco("charuco:5x7:0.025:0.018:6X6_250").spec(), "charuco:5x7:0.025:0.018:6x6_250");
  for (const std::string& name : aruco_dictionary_names()) {
    const std::string spec = "charuco:5x5:0.04:0.03:" + name;
    EXPECT_EQ(charuco(spec).spec(), spec);
  }
  EXPECT_EQ(aruco_dictionary_names().front(), "4x4_50");
  EXPECT_EQ(aruco_dictionary_names().back(), "apriltag_36h11");
}

TEST(CharucoPattern, WrongSpecsSayWhatIsWrong) {
  struct Case {
    std::string spec;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"charuco:7x5:0.04:0.03", "not five fields separated by ':'"},
      {"charuco:7x5:0.04:0.03:4x4_50:x", "not five fields"},
      {"charuco:7-5:0.04:0.03:4x4_50", "size '7-5' is not SXxSY"},
      {"charuco:2x5:0.04:0.03:4x4_50", "needs 3 to 201 squares per side"},
      {"charuco:7x2:0.04:0.03:4x4_50", "SXxSY counts squares, not inner corners"},
      {"charuco:7x5:0:0.03:4x4_50", "square size '0' is not a positive number"},
      {"charuco:7x5:0.04:-1:4x4_50", "marker size '-1' is not a positive number"},
      {"charuco:7x5:0.04:0.04:4x4_50",
       "marker size 0.04 m is not smaller than the square size 0.04 m"},
      {"charuco:7x5:0.04:0.05:4x4_50", "not smaller than the square size"},
      {"charuco:7x5:0.04:0.03:4x4_51",
       "unknown dictionary '4x4_51' (one of 4x4_50, 4x4_100, 4x4_250, 4x4_1000, 5x5_50"},
      {"charuco:7x5:0.04:0.03:7x7_50", "apriltag_36h11)"},
      {"charuco:11x10:0.04:0.03:4x4_50",
       "a board of 11x10 squares carries 55 markers but dictionary 4x4_50 has only 50"},
  };
  for (const Case& c : cases) {
    const auto pattern = parse_calibration_pattern(c.spec);
    ASSERT_FALSE(pattern.ok()) << c.spec;
    EXPECT_THAT(pattern.error().message, HasSubstr("pattern '" + c.spec + "': ")) << c.spec;
    EXPECT_THAT(pattern.error().message, HasSubstr(c.message)) << c.spec;
  }
  // The general form lists the ChArUco spec.
  EXPECT_THAT(parse_calibration_pattern("board:9x6:0.025").error().message,
              HasSubstr("charuco:SXxSY:SQUARE_M:MARKER_M:DICT"));
}

// The object points are OpenCV's chessboardCorners, in id order, and the layout is OpenCV's
// marker placement: what interpolateCornersCharuco assumes.
TEST(CharucoPattern, ObjectPointsAndLayoutAreOpenCvsBoard) {
  const CalibrationPattern pattern = charuco("charuco:7x5:0.04:0.03:4x4_50");
  const auto board = cv::aruco::CharucoBoard::create(
      7, 5, 0.04f, 0.03f, cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_50));
  const std::vector<cv::Point3f> points = pattern_object_points(pattern);
  ASSERT_EQ(points.size(), board->chessboardCorners.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    EXPECT_NEAR(cv::norm(points[k] - board->chessboardCorners[k]), 0.0, 1e-7) << k;
  }
  const std::vector<cv::Point3f> some = pattern_object_points(pattern, {7, 0, 23});
  ASSERT_EQ(some.size(), 3u);
  EXPECT_EQ(some[0], points[7]);
  EXPECT_EQ(some[2], points[23]);

  const CharucoLayout layout = charuco_layout(pattern);
  ASSERT_EQ(layout.markers.size(), board->ids.size());
  EXPECT_EQ(layout.markers.size(), 17u);
  EXPECT_TRUE(layout.black_square(0, 0));  // the top-left square is black
  EXPECT_FALSE(layout.black_square(1, 0));
  for (std::size_t k = 0; k < layout.markers.size(); ++k) {
    EXPECT_EQ(layout.markers[k].id, board->ids[k]);
    EXPECT_NEAR(layout.markers[k].top_left.x, board->objPoints[k][0].x, 1e-6);
    EXPECT_NEAR(layout.markers[k].top_left.y, board->objPoints[k][0].y, 1e-6);
  }

  // The layout's reflectance is OpenCV's printed board (draw() rounds the marker cells to
  // whole pixels, so compare at the centre of every marker cell and near the corner of
  // every square, inside its white margin where it has a marker).
  const int per_square = 120;
  const cv::Mat drawn = draw_charuco_board(pattern, per_square, 0);
  ASSERT_EQ(drawn.size(), cv::Size(7 * per_square, 5 * per_square));
  const double pixels_per_m = per_square / 0.04;
  const auto drawn_white = [&](double x, double y) {
    return drawn.at<std::uint8_t>(static_cast<int>(y * pixels_per_m),
                                  static_cast<int>(x * pixels_per_m)) > 127;
  };
  int samples = 0;
  for (const CharucoMarker& marker : layout.markers) {
    const int n = marker.cells.rows;
    ASSERT_EQ(n, 6);  // 4 x 4 bits and the border
    for (int row = 0; row < n; ++row) {
      for (int col = 0; col < n; ++col) {
        const double x = marker.top_left.x + (col + 0.5) * marker.side / n;
        const double y = marker.top_left.y + (row + 0.5) * marker.side / n;
        EXPECT_EQ(layout.reflectance(x, y) > 0.5, drawn_white(x, y)) << marker.id;
        ++samples;
      }
    }
  }
  for (int j = 0; j < 5; ++j) {
    for (int i = 0; i < 7; ++i) {
      const double x = (i + 0.05) * 0.04, y = (j + 0.05) * 0.04;
      EXPECT_EQ(layout.reflectance(x, y) > 0.5, drawn_white(x, y)) << i << " " << j;
      EXPECT_EQ(layout.black_square(i, j), !drawn_white(x, y)) << i << " " << j;
    }
  }
  EXPECT_EQ(samples, 17 * 36);
}

// A board image where square side = `per_square` pixels; the corner (r, c) is then at
// ((c + 1) per_square - 0.5 + margin, (r + 1) per_square - 0.5 + margin) (pixel centres).
cv::Mat board_image(const CalibrationPattern& pattern, int per_square, int margin) {
  cv::Mat image = draw_charuco_board(pattern, per_square, margin);
  cv::GaussianBlur(image, image, cv::Size(3, 3), 0.7);
  return image;
}

TEST(CharucoPattern, FindsTheWholeBoardAndPartsOfIt) {
  const CalibrationPattern pattern = charuco("charuco:7x5:0.04:0.03:4x4_50");
  const int per_square = 50, margin = 30;
  const cv::Mat image = board_image(pattern, per_square, margin);
  const auto expected = [&](int id) {
    const int r = id / pattern.cols, c = id % pattern.cols;
    return cv::Point2f(static_cast<float>((c + 1) * per_square + margin) - 0.5f,
                       static_cast<float>((r + 1) * per_square + margin) - 0.5f);
  };

  const auto whole = detect_pattern(image, pattern);
  ASSERT_TRUE(whole.ok()) << whole.error().message;
  ASSERT_EQ(whole->size(), 24u);
  for (int id = 0; id < 24; ++id) {
    EXPECT_LT(cv::norm((*whole)[static_cast<std::size_t>(id)] - expected(id)), 0.05) << id;
  }

  // The right 40 % cut off: the corners of the left part, by id, where they are.
  const cv::Mat left_part = image(cv::Rect(0, 0, image.cols * 6 / 10, image.rows)).clone();
  const auto part = detect_pattern_points(left_part, pattern);
  ASSERT_TRUE(part.ok()) << part.error().message;
  EXPECT_GE(part->ids.size(), 8u);
  EXPECT_LT(part->ids.size(), 24u);
  for (std::size_t k = 0; k < part->ids.size(); ++k) {
    EXPECT_LT(part->ids[static_cast<std::size_t>(k)] % pattern.cols, 4);
    EXPECT_LT(cv::norm(part->image_points[k] - expected(part->ids[k])), 0.05) << part->ids[k];
  }
  // detect_pattern wants the whole board and says how much it saw.
  const auto not_whole = detect_pattern(left_part, pattern);
  ASSERT_FALSE(not_whole.ok());
  EXPECT_THAT(not_whole.error().message,
              HasSubstr("of the board's 24 ChArUco corners found (the whole "
                        "charuco:7x5:0.04:0.03:4x4_50 must be visible here)"));
}

TEST(CharucoPattern, TooFewCornersOrNoneSayWhy) {
  const CalibrationPattern pattern = charuco("charuco:7x5:0.04:0.03:4x4_50");
  const int per_square = 50, margin = 30;
  const cv::Mat image = board_image(pattern, per_square, margin);
  // The top-left 2.6 x 2.6 squares: markers 0, 3 and 4 next to corners 0, 1, 6, 7.
  const int side = margin + 13 * per_square / 5;
  const auto few = detect_pattern_points(image(cv::Rect(0, 0, side, side)).clone(), pattern);
  ASSERT_FALSE(few.ok());
  EXPECT_THAT(few.error().message, HasSubstr("ChArUco corner"));
  EXPECT_THAT(few.error().message, HasSubstr("found, fewer than the 6 a view needs"));

  const cv::Mat blank(200, 200, CV_8UC1, cv::Scalar(200));
  const auto none = detect_pattern_points(blank, pattern);
  ASSERT_FALSE(none.ok());
  EXPECT_THAT(none.error().message,
              HasSubstr("no ChArUco marker found (dictionary 4x4_50; check that the board was "
                        "printed for charuco:7x5:0.04:0.03:4x4_50)"));

  // Another dictionary's board shows no marker of this one.
  const CalibrationPattern other = charuco("charuco:7x5:0.04:0.03:6x6_50");
  EXPECT_FALSE(detect_pattern_points(board_image(other, per_square, margin), pattern).ok());
}

// The board with everything left of x0 and right of x1 (pixels) painted white.
cv::Mat board_part(const cv::Mat& board, int x0, int x1) {
  cv::Mat part = board.clone();
  part(cv::Rect(0, 0, x0, part.rows)).setTo(255);
  part(cv::Rect(x1, 0, part.cols - x1, part.rows)).setTo(255);
  return part;
}

// A stereo pair keeps the corners both images show, by id, with their object points; a pair
// that shares fewer than 6 is skipped, saying how many each image had.
TEST(CharucoPattern, StereoPairsKeepTheCornersBothImagesShow) {
  const CalibrationPattern pattern = charuco("charuco:7x5:0.04:0.03:4x4_50");
  const int per_square = 50, margin = 30;
  const cv::Mat board = board_image(pattern, per_square, margin);
  const auto x = [&](int squares) { return margin + squares * per_square; };
  test_files::TempDir tmp("charuco_pairs");
  const std::string dir = tmp.string();
  // Pair 0: left shows squares 0..4 (corner columns 0..3), right squares 2..6 (columns 2..5):
  // columns 2 and 3 in common. Pair 1: left squares 0..3 (columns 0..2): column 2 alone.
  const std::vector<std::string> left = {dir + "/left0.png", dir + "/left1.png"};
  const std::vector<std::string> right = {dir + "/right0.png", dir + "/right1.png"};
  ASSERT_TRUE(write_png_file(left[0], board_part(board, 0, x(5))));
  ASSERT_TRUE(write_png_file(right[0], board_part(board, x(2), board.cols)));
  ASSERT_TRUE(write_png_file(left[1], board_part(board, 0, x(4))));
  ASSERT_TRUE(write_png_file(right[1], board_part(board, x(2), board.cols)));

  const auto pairs = detect_in_image_pairs(left, right, pattern);
  ASSERT_TRUE(pairs.ok()) << pairs.error().message;
  ASSERT_EQ(pairs->views.size(), 1u);
  const StereoPatternView& view = pairs->views[0];
  ASSERT_EQ(view.object_points.size(), 8u);
  ASSERT_EQ(view.left_points.size(), 8u);
  ASSERT_EQ(view.right_points.size(), 8u);
  const std::vector<cv::Point3f> all = pattern_object_points(pattern);
  for (std::size_t k = 0; k < view.object_points.size(); ++k) {
    // Columns 2 and 3 (x = 3 s, 4 s); the same corner in both images (the same pixels here).
    const float column = view.object_points[k].x / 0.04f - 1.0f;
    EXPECT_TRUE(std::abs(column - 2.0f) < 1e-4f || std::abs(column - 3.0f) < 1e-4f) << column;
    EXPECT_LT(cv::norm(view.left_points[k] - view.right_points[k]), 0.05) << k;
    const float u = margin + (column + 1.0f) * per_square - 0.5f;
    EXPECT_NEAR(view.left_points[k].x, u, 0.05) << k;
  }
  ASSERT_EQ(pairs->rejected.size(), 1u);
  EXPECT_EQ(pairs->rejected[0].name, left[1]);
  EXPECT_EQ(pairs->rejected[0].reason,
            "the images share only 4 ChArUco corners (left 12, right 16), fewer than the 6 a "
            "pair needs");

  // Each image alone is a view with the corners it shows.
  const auto mono = detect_in_images(left, pattern);
  ASSERT_TRUE(mono.ok()) << mono.error().message;
  ASSERT_EQ(mono->views.size(), 2u);
  EXPECT_EQ(mono->views[0].object_points.size(), 16u);
  EXPECT_EQ(mono->views[1].object_points.size(), 12u);
  EXPECT_EQ(mono->views[1].object_points[0], all[0]);
}

}  // namespace
}  // namespace telear::vision
