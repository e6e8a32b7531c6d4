#pragma once
// `telear bench render`: the seed paper's Tables 1 and 2 re-run headless (EGL) on the same
// cases, printed beside the seed's figures (REFERENCES.md):
//   graphics only : no drawing; a cube and the arm; the arm with 8 segments; with 50
//                   segments, solid and wire-frame;
//   on video      : the same arm over a 640x480 video frame, uploaded as a texture every
//                   frame, and the composed frame read back to memory;
//   mono / stereo : one view, or two views (6 cm apart) side by side, each with its own
//                   video frame in the video cases.
// Every frame moves the arm (all joints), so every part's matrix is uploaded, and ends with
// glFinish (graphics only) or the read-back (video), so a frame is complete when timed.
//
// --mesh-arm NAME (ur6 or arm7) adds one case beyond the seed's: a URDF arm of dense meshes
// (scripts/generate_arms.py --detail 64: >= 100k triangles) in the full stereo AR frame
// (two video uploads, two arm renders, the read-back), generated at the start of the run into
// a temporary directory (removed at the end) and reported with its ratio to the PUMA's
// "video, arm, 8 seg" stereo case; both run whatever --only says (--only mesh: just these).
//
// RenderBenchScene is the workload shared by this command and bench/render_bench.cpp
// (Google Benchmark).

#include <cstddef>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/geometry/robot_geometry.hpp"

namespace telear::cli {

struct RenderBenchCase {
  std::string name;
  bool draw_arm = true;
  bool draw_cube = false;
  int segments = 8;
  bool wireframe = false;
  bool video = false;   // 640x480 frame upload + background + read-back
  bool stereo = false;  // two views side by side
  // The seed's figure for this row (REFERENCES.md), as text; empty when it has none.
  std::string seed;
  // A robot file (e.g. a generated arm7.yaml) whose URDF meshes are drawn instead of the
  // PUMA 560's primitive body (segments is then unused); empty: the PUMA.
  std::string robot_file;
  // The visual meshes' level of detail (geometry::GeometryOptions::visual_tolerance_m; 0: as
  // loaded).
  double visual_tolerance_m = 0.0;
};

// The rows of the table, in order.
std::vector<RenderBenchCase> render_bench_cases();

class RenderBenchScene {
 public:
  // A current GL context is required. width x height is one eye's view (and video frame).
  static Result<std::unique_ptr<RenderBenchScene>> create(const RenderBenchCase& c, int width,
                                                          int height);
  ~RenderBenchScene();
  // Renders one complete frame (see the header comment).
  void frame();
  // Triangles and vertices of the arm drawn per view.
  std::size_t triangle_count() const;
  std::size_t vertex_count() const;
  // The last frame's read-back (video cases), or a read-back made now (other cases).
  std::vector<unsigned char> last_image();

 private:
  RenderBenchScene();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct RenderBenchOptions {
  double seconds = 1.0;  // timed per case (after a short warm-up)
  int width = 640;
  int height = 480;
  std::string only;  // run only the cases whose name contains this text
  bool json = false;
  std::string mesh_arm;  // "ur6" or "arm7": add the mesh-arm case; empty: none
  int mesh_detail = 64;  // generate_arms.py --detail (segments around a surface of revolution)
  // The mesh arm's level of detail (metres); the arm is also drawn as loaded, for comparison.
  double mesh_tolerance_m = geometry::GeometryOptions{}.visual_tolerance_m;
};

// The generator of the mesh arms (the source tree's scripts/generate_arms.py, run with
// /usr/bin/python3); not installed with telear.
std::string generate_arms_script();

// The cases added by --mesh-arm NAME, drawing `robot_file` at a level of detail (tolerance in
// metres; 0: as loaded), and the PUMA case they are compared with.
RenderBenchCase mesh_arm_case(const std::string& name, const std::string& robot_file,
                              double visual_tolerance_m);
std::string mesh_arm_baseline_case();

int run_bench_render(const RenderBenchOptions& options, std::ostream& out, std::ostream& err);

}  // namespace telear::cli
