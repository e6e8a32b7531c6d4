#include "telear/render/ar_view.hpp"

#include <epoxy/gl.h>

#include <algorithm>

namespace telear::render {

namespace {

bool frame_fits(const core::Image* frame, const core::YCbCrImage* planes,
                const vision::CameraModel& camera) {
  if (frame != nullptr) {
    return frame->width == camera.width && frame->height == camera.height && frame->channels == 3;
  }
  return planes != nullptr && planes->width == camera.width && planes->height == camera.height &&
         planes->chroma_width > 0 && planes->chroma_height > 0 &&
         planes->y.size() == static_cast<std::size_t>(planes->width) * planes->height &&
         planes->cb.size() ==
             static_cast<std::size_t>(planes->chroma_width) * planes->chroma_height &&
         planes->cr.size() == planes->cb.size();
}

}  // namespace

ArView::ArView(const core::RobotModel& model, const core::ArmBody& body)
    : model_(&model),
      body_(body),
      ghost_pose_(std::make_unique<core::ArmBodyPose>(model, body_)),
      reported_pose_(std::make_unique<core::ArmBodyPose>(model, body_)),
      predicted_pose_(std::make_unique<core::ArmBodyPose>(model, body_)),
      capture_pose_(std::make_unique<core::ArmBodyPose>(model, body_)) {}

Result<ArView> ArView::create(const core::RobotModel& model, const core::ArmBody& body,
                              const vision::StereoCameraModel& cameras,
                              const std::vector<SceneObject>& objects,
                              const ArViewOptions& options) {
  ArView view(model, body);
  view.cameras_ = cameras;
  view.options_ = options;
  auto ghost = ArmRenderer::create(view.body_);
  if (!ghost) return ghost.error();
  auto reported = ArmRenderer::create(view.body_);
  if (!reported) return reported.error();
  auto predicted = ArmRenderer::create(view.body_);
  if (!predicted) return predicted.error();
  auto capture = ArmRenderer::create(view.body_);
  if (!capture) return capture.error();
  view.ghost_ = std::move(ghost.value());
  view.reported_ = std::move(reported.value());
  view.predicted_ = std::move(predicted.value());
  view.capture_ = std::move(capture.value());
  if (!objects.empty()) {
    auto scene = create_scene_renderer(objects);
    if (!scene) return scene.error();
    view.objects_ = std::move(scene.value());
  }
  const vision::CameraModel* eyes[2] = {&cameras.left, &cameras.right};
  for (int i = 0; i < 2; ++i) {
    OverlayOptions overlay_options;
    overlay_options.mode = options.overlay_mode;
    overlay_options.clear_colour = options.vr_background;
    auto overlay = Overlay::create(*eyes[i], overlay_options);
    if (!overlay) return overlay.error();
    auto target = OffscreenTarget::create(eyes[i]->width, eyes[i]->height);
    if (!target) return target.error();
    view.overlays_[i] = std::move(overlay.value());
    view.eyes_[i] = std::move(target.value());
  }
  auto composer = StereoComposer::create();
  if (!composer) return composer.error();
  view.composer_ = std::move(composer.value());
  if (options.layout != StereoLayout::kSeparate) {
    const ComposedSize size =
        composed_size(options.layout, cameras.left.width, cameras.left.height);
    auto composed = OffscreenTarget::create(size.width, size.height);
    if (!composed) return composed.error();
    view.composed_ = std::move(composed.value());
  }
  return view;
}

const OffscreenTarget& ArView::composed() const {
  return options_.layout == StereoLayout::kSeparate ? eyes_[0] : composed_;
}

void ArView::render(const ArViewInput& input) {
  ghost_pose_->set_configuration(input.ghost_q);
  ghost_pose_->set_gripper_opening(body_.gripper_opening_m(input.ghost_gripper));
  ghost_.update(*ghost_pose_);
  const bool draw_reported = input.reported_q.size() == model_->dof();
  if (draw_reported) {
    reported_pose_->set_configuration(input.reported_q);
    reported_pose_->set_gripper_opening(body_.gripper_opening_m(input.reported_gripper));
    reported_.update(*reported_pose_);
  }
  if (draws_predicted(input)) {
    predicted_pose_->set_configuration(input.predicted_q);
    predicted_pose_->set_gripper_opening(body_.gripper_opening_m(input.predicted_gripper));
    predicted_.update(*predicted_pose_);
  }
  if (draws_capture_arm(input)) {
    capture_pose_->set_configuration(input.capture_q);
    capture_pose_->set_gripper_opening(body_.gripper_opening_m(input.capture_gripper));
    capture_.update(*capture_pose_);
  }
  const bool video_ok = input.mode == ViewMode::kAr &&
                        frame_fits(input.left, input.left_planes, cameras_.left) &&
                        frame_fits(input.right, input.right_planes, cameras_.right);
  if (input.mode == ViewMode::kVr) {
    status_ = ViewStatus::kVirtual;
  } else {
    status_ = (video_ok && !input.stale) ? ViewStatus::kLive : ViewStatus::kStale;
  }
  for (int i = 0; i < 2; ++i) draw_eye(i, input, video_ok);
  if (options_.layout != StereoLayout::kSeparate) {
    composer_.compose(options_.layout, eyes_[0].colour_texture(), eyes_[1].colour_texture(),
                      composed_);
  }
}

void ArView::draw_eye(int index, const ArViewInput& input, bool video_ok) {
  Overlay& overlay = overlays_[index];
  if (video_ok) {
    const core::Image* frame = index == 0 ? input.left : input.right;
    if (frame != nullptr) {
      overlay.upload_frame(frame->pixels.data(), ChannelOrder::kRgb);
    } else {
      overlay.upload_planes(*(index == 0 ? input.left_planes : input.right_planes));
    }
  } else {
    overlay.clear_frame();
  }
  const bool virtual_scene = !video_ok;
  const bool draw_reported = input.reported_q.size() == model_->dof();
  DrawOptions ghost;
  ghost.style = options_.ghost_style;
  ghost.alpha = options_.ghost_alpha;
  ghost.colour = options_.ghost_colour;
  ghost.highlight_colour = options_.contact_colour;
  for (int k = 0; k < body_.part_count(); ++k) {
    const auto& frames = input.ghost_highlight_frames;
    if (std::find(frames.begin(), frames.end(), body_.parts[k].link) != frames.end())
      ghost.highlight_parts.push_back(k);
  }
  DrawOptions reported;
  reported.alpha = options_.reported_alpha;
  reported.colour = options_.reported_colour;
  DrawOptions real;  // VR: the arm as the robot reports it, opaque in its own colours
  DrawOptions predicted;
  predicted.style = DrawOptions::Style::kWireframe;
  predicted.colour = options_.predicted_colour;
  const bool draw_predicted = draws_predicted(input);
  DrawOptions at_capture;
  at_capture.style = DrawOptions::Style::kWireframe;
  at_capture.colour = options_.capture_colour;
  const bool draw_capture = video_ok && draws_capture_arm(input);

  overlay.render(eyes_[index],
                 [&](const Eigen::Matrix4f& projection, const Eigen::Matrix4f& T_view_base) {
                   if (virtual_scene) {
                     if (objects_) objects_->draw(projection, T_view_base, {});
                     if (draw_reported) reported_.draw(projection, T_view_base, real);
                   } else if (draw_reported && options_.show_reported_ghost) {
                     reported_.draw(projection, T_view_base, reported);
                   }
                   // Before the ghost, which writes depth: where the two coincide (the arm on
                   // its plan) the wire-frame stays visible through the translucent ghost.
                   if (draw_predicted) predicted_.draw(projection, T_view_base, predicted);
                   if (draw_capture) capture_.draw(projection, T_view_base, at_capture);
                   ghost_.draw(projection, T_view_base, ghost);
                 });
  draw_status_border(eyes_[index]);
}

void ArView::draw_status_border(const OffscreenTarget& target) const {
  const int b = options_.status_border_px;
  if (b <= 0) return;
  const Eigen::Vector3f colour = status_ == ViewStatus::kLive ? Eigen::Vector3f(0.1f, 0.8f, 0.2f)
                                 : status_ == ViewStatus::kVirtual
                                     ? Eigen::Vector3f(1.0f, 0.65f, 0.0f)
                                     : Eigen::Vector3f(0.9f, 0.1f, 0.1f);
  target.bind();
  glEnable(GL_SCISSOR_TEST);
  glClearColor(colour.x(), colour.y(), colour.z(), 1.0f);
  const int w = target.width(), h = target.height();
  const int rects[4][4] = {{0, 0, w, b}, {0, h - b, w, b}, {0, 0, b, h}, {w - b, 0, b, h}};
  for (const auto& r : rects) {
    glScissor(r[0], r[1], r[2], r[3]);
    glClear(GL_COLOR_BUFFER_BIT);
  }
  glDisable(GL_SCISSOR_TEST);
}

}  // namespace telear::render
