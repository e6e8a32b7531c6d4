#include "telear/record/schema_descriptors.hpp"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/descriptor.pb.h>
#include <google/protobuf/dynamic_message.h>
#include <gtest/gtest.h>

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "foxglove/CameraCalibration.pb.h"
#include "foxglove/CompressedImage.pb.h"
#include "foxglove/FrameTransforms.pb.h"
#include "foxglove/JointStates.pb.h"
#include "foxglove/Log.pb.h"
#include "foxglove/SceneUpdate.pb.h"
#include "telear/net/latency_stages.hpp"
#include "telear/record/v1/latency_stages.pb.h"
#include "telear/record/v1/plan_event.pb.h"

namespace telear::record {
namespace {

namespace pb = google::protobuf;
using Type = pb::FieldDescriptor::Type;

// Every message type a recording has a channel of.
std::vector<const pb::Descriptor*> recorded_messages() {
  return {foxglove::CompressedImage::descriptor(), foxglove::CameraCalibration::descriptor(),
          foxglove::JointStates::descriptor(),     foxglove::FrameTransforms::descriptor(),
          foxglove::SceneUpdate::descriptor(),     foxglove::Log::descriptor(),
          v1::LatencyStages::descriptor(),         v1::PlanEvent::descriptor()};
}

pb::FileDescriptorSet parse_set(const std::string& data) {
  pb::FileDescriptorSet set;
  EXPECT_TRUE(set.ParseFromString(data));
  return set;
}

std::vector<std::string> file_names(const pb::FileDescriptorSet& set) {
  std::vector<std::string> names;
  for (const auto& file : set.file()) {
    names.push_back(file.name());
  }
  return names;
}

// What a reader such as Foxglove does with a Schema record: a pool with nothing but the set's
// files (no generated descriptors underneath, so a missing import fails), built in the set's
// order, and dynamic messages from it.
struct ReaderPool {
  pb::DescriptorPool pool;
  pb::DynamicMessageFactory factory{&pool};

  explicit ReaderPool(const SchemaInfo& schema) {
    // Named: a range-for over a temporary's member would outlive the temporary.
    const auto set = parse_set(schema.data);
    for (const auto& file : set.file()) {
      EXPECT_NE(pool.BuildFile(file), nullptr) << file.name() << " of " << schema.name;
    }
  }
  // Null, and a failure, where the set does not define the message.
  const pb::Descriptor* message(const std::string& name) {
    const auto* descriptor = pool.FindMessageTypeByName(name);
    EXPECT_NE(descriptor, nullptr) << name << " is not in its set";
    return descriptor;
  }
};

// Serialized with the generated class, parsed by the reader's dynamic message: every field
// reads back the same (the text form lists each set field with its value) and none is unknown
// (which a wrong number or type would make it).
std::unique_ptr<pb::Message> decode_as_reader(ReaderPool& reader, const pb::Message& message) {
  const auto* descriptor = reader.message(message.GetDescriptor()->full_name());
  if (descriptor == nullptr) {
    return nullptr;
  }
  std::unique_ptr<pb::Message> decoded(reader.factory.GetPrototype(descriptor)->New());
  EXPECT_TRUE(decoded->ParseFromString(message.SerializeAsString()));
  EXPECT_EQ(decoded->DebugString(), message.DebugString());
  EXPECT_TRUE(decoded->GetReflection()->GetUnknownFields(*decoded).empty());
  EXPECT_EQ(decoded->SerializeAsString(), message.SerializeAsString());
  return decoded;
}

void set_time(google::protobuf::Timestamp& stamp) {
  stamp.set_seconds(1'700'000'000);
  stamp.set_nanos(123'456'789);
}

foxglove::Pose make_pose() {
  foxglove::Pose pose;
  pose.mutable_position()->set_x(0.5);
  pose.mutable_position()->set_z(-1.25);
  pose.mutable_orientation()->set_z(0.7071);
  pose.mutable_orientation()->set_w(0.7071);
  return pose;
}

foxglove::Color make_color() {
  foxglove::Color color;
  color.set_r(1.0);
  color.set_g(0.5);
  color.set_a(0.25);
  return color;
}

TEST(RecordSchemas, NamesAndFilesAreFoxglovesExactly) {
  const SchemaInfo image = schema_for<foxglove::CompressedImage>();
  EXPECT_EQ(image.name, "foxglove.CompressedImage");
  EXPECT_EQ(image.encoding, "protobuf");
  EXPECT_EQ(schema_for<foxglove::CameraCalibration>().name, "foxglove.CameraCalibration");
  EXPECT_EQ(schema_for<foxglove::JointStates>().name, "foxglove.JointStates");
  EXPECT_EQ(schema_for<foxglove::FrameTransforms>().name, "foxglove.FrameTransforms");
  EXPECT_EQ(schema_for<foxglove::SceneUpdate>().name, "foxglove.SceneUpdate");
  EXPECT_EQ(schema_for<foxglove::Log>().name, "foxglove.Log");
  EXPECT_EQ(schema_for<v1::LatencyStages>().name, "telear.record.v1.LatencyStages");
  EXPECT_EQ(schema_for<v1::PlanEvent>().name, "telear.record.v1.PlanEvent");
  // Foxglove's file layout, one message per file named after it: the file names a reader
  // sees in the set are those of Foxglove's own descriptor sets.
  for (const auto* message : recorded_messages()) {
    if (message->file()->package() == "foxglove") {
      EXPECT_EQ(message->file()->name(), "foxglove/" + message->name() + ".proto");
      EXPECT_EQ(message->file()->syntax(), pb::FileDescriptor::SYNTAX_PROTO3);
    }
  }
}

TEST(RecordSchemas, EachSetHoldsItsFileAfterAllItsImportsOnce) {
  for (const auto* message : recorded_messages()) {
    SCOPED_TRACE(message->full_name());
    const auto set = parse_set(file_descriptor_set(*message));
    ASSERT_GT(set.file_size(), 0);
    EXPECT_EQ(set.file(set.file_size() - 1).name(), message->file()->name());
    std::set<std::string> before;
    for (const auto& file : set.file()) {
      for (const auto& import : file.dependency()) {
        EXPECT_TRUE(before.count(import)) << file.name() << " imports " << import << " later";
      }
      EXPECT_TRUE(before.insert(file.name()).second) << file.name() << " twice";
      // Comments are left out: readers do not need them.
      EXPECT_FALSE(file.has_source_code_info());
    }
    // Every message with a timestamp carries google's Timestamp with it.
    EXPECT_TRUE(before.count("google/protobuf/timestamp.proto"));
    ReaderPool reader(schema_info(*message));
    reader.message(message->full_name());
  }
}

TEST(RecordSchemas, SetsListTheTransitiveImportsInDependencyOrder) {
  EXPECT_EQ(file_names(parse_set(schema_for<foxglove::CompressedImage>().data)),
            (std::vector<std::string>{"google/protobuf/timestamp.proto",
                                      "foxglove/CompressedImage.proto"}));
  EXPECT_EQ(
      file_names(parse_set(schema_for<foxglove::FrameTransforms>().data)),
      (std::vector<std::string>{"foxglove/Quaternion.proto", "foxglove/Vector3.proto",
                                "google/protobuf/timestamp.proto", "foxglove/FrameTransform.proto",
                                "foxglove/FrameTransforms.proto"}));
  // SceneUpdate: 16 foxglove files (Pose, Color, Vector3 imported by every primitive, listed
  // once), Timestamp and Duration.
  const auto scene = file_names(parse_set(schema_for<foxglove::SceneUpdate>().data));
  EXPECT_EQ(scene.size(), 19U);
  EXPECT_EQ(std::set<std::string>(scene.begin(), scene.end()).size(), scene.size());
  for (const char* file : {"google/protobuf/duration.proto", "foxglove/Pose.proto",
                           "foxglove/Point3.proto", "foxglove/KeyValuePair.proto",
                           "foxglove/ModelPrimitive.proto", "foxglove/SceneEntityDeletion.proto"}) {
    EXPECT_EQ(std::count(scene.begin(), scene.end(), file), 1) << file;
  }
}

// Field numbers, types and names from Foxglove's published definitions
// (foxglove/foxglove-sdk schemas/proto/foxglove/*.proto, @foxglove/schemas 2.1.0), read from
// the pool a reader builds out of the set: a renumbered or retyped field would decode as
// garbage in Foxglove even though telear's own round trip still works.
struct FieldSpec {
  const char* name;
  int number;
  Type type;
  bool repeated = false;
  const char* type_name = "";  // a message or enum field's full type name
};

void expect_fields(const std::string& message, const std::vector<FieldSpec>& fields,
                   const SchemaInfo& schema) {
  SCOPED_TRACE(message);
  ReaderPool reader(schema);
  const pb::Descriptor* descriptor = reader.message(message);
  ASSERT_NE(descriptor, nullptr);
  EXPECT_EQ(descriptor->field_count(), static_cast<int>(fields.size()));
  for (const auto& spec : fields) {
    const auto* field = descriptor->FindFieldByName(spec.name);
    ASSERT_NE(field, nullptr) << spec.name;
    EXPECT_EQ(field->number(), spec.number) << spec.name;
    EXPECT_EQ(field->type(), spec.type) << spec.name;
    EXPECT_EQ(field->is_repeated(), spec.repeated) << spec.name;
    if (field->message_type()) {
      EXPECT_EQ(field->message_type()->full_name(), spec.type_name) << spec.name;
    } else if (field->enum_type()) {
      EXPECT_EQ(field->enum_type()->full_name(), spec.type_name) << spec.name;
    }
  }
}

constexpr const char* kTimestamp = "google.protobuf.Timestamp";

TEST(RecordSchemas, FieldNumbersAndTypesAreFoxglovesPublished) {
  expect_fields("foxglove.CompressedImage",
                {{"timestamp", 1, Type::TYPE_MESSAGE, false, kTimestamp},
                 {"frame_id", 4, Type::TYPE_STRING},
                 {"data", 2, Type::TYPE_BYTES},
                 {"format", 3, Type::TYPE_STRING}},
                schema_for<foxglove::CompressedImage>());
  expect_fields("foxglove.CameraCalibration",
                {{"timestamp", 1, Type::TYPE_MESSAGE, false, kTimestamp},
                 {"frame_id", 9, Type::TYPE_STRING},
                 {"width", 2, Type::TYPE_FIXED32},
                 {"height", 3, Type::TYPE_FIXED32},
                 {"distortion_model", 4, Type::TYPE_STRING},
                 {"D", 5, Type::TYPE_DOUBLE, true},
                 {"K", 6, Type::TYPE_DOUBLE, true},
                 {"R", 7, Type::TYPE_DOUBLE, true},
                 {"P", 8, Type::TYPE_DOUBLE, true}},
                schema_for<foxglove::CameraCalibration>());
  const auto joints = schema_for<foxglove::JointStates>();
  expect_fields("foxglove.JointStates",
                {{"timestamp", 1, Type::TYPE_MESSAGE, false, kTimestamp},
                 {"joints", 2, Type::TYPE_MESSAGE, true, "foxglove.JointState"}},
                joints);
  expect_fields("foxglove.JointState",
                {{"name", 1, Type::TYPE_STRING},
                 {"position", 2, Type::TYPE_DOUBLE},
                 {"velocity", 3, Type::TYPE_DOUBLE},
                 {"acceleration", 4, Type::TYPE_DOUBLE},
                 {"effort", 5, Type::TYPE_DOUBLE}},
                joints);
  const auto transforms = schema_for<foxglove::FrameTransforms>();
  expect_fields("foxglove.FrameTransforms",
                {{"transforms", 1, Type::TYPE_MESSAGE, true, "foxglove.FrameTransform"}},
                transforms);
  expect_fields("foxglove.FrameTransform",
                {{"timestamp", 1, Type::TYPE_MESSAGE, false, kTimestamp},
                 {"parent_frame_id", 2, Type::TYPE_STRING},
                 {"child_frame_id", 3, Type::TYPE_STRING},
                 {"translation", 4, Type::TYPE_MESSAGE, false, "foxglove.Vector3"},
                 {"rotation", 5, Type::TYPE_MESSAGE, false, "foxglove.Quaternion"}},
                transforms);
  expect_fields("foxglove.Quaternion",
                {{"x", 1, Type::TYPE_DOUBLE},
                 {"y", 2, Type::TYPE_DOUBLE},
                 {"z", 3, Type::TYPE_DOUBLE},
                 {"w", 4, Type::TYPE_DOUBLE}},
                transforms);
  const auto scene = schema_for<foxglove::SceneUpdate>();
  expect_fields("foxglove.SceneUpdate",
                {{"deletions", 1, Type::TYPE_MESSAGE, true, "foxglove.SceneEntityDeletion"},
                 {"entities", 2, Type::TYPE_MESSAGE, true, "foxglove.SceneEntity"}},
                scene);
  expect_fields("foxglove.SceneEntity",
                {{"timestamp", 1, Type::TYPE_MESSAGE, false, kTimestamp},
                 {"frame_id", 2, Type::TYPE_STRING},
                 {"id", 3, Type::TYPE_STRING},
                 {"lifetime", 4, Type::TYPE_MESSAGE, false, "google.protobuf.Duration"},
                 {"frame_locked", 5, Type::TYPE_BOOL},
                 {"metadata", 6, Type::TYPE_MESSAGE, true, "foxglove.KeyValuePair"},
                 {"arrows", 7, Type::TYPE_MESSAGE, true, "foxglove.ArrowPrimitive"},
                 {"cubes", 8, Type::TYPE_MESSAGE, true, "foxglove.CubePrimitive"},
                 {"spheres", 9, Type::TYPE_MESSAGE, true, "foxglove.SpherePrimitive"},
                 {"cylinders", 10, Type::TYPE_MESSAGE, true, "foxglove.CylinderPrimitive"},
                 {"lines", 11, Type::TYPE_MESSAGE, true, "foxglove.LinePrimitive"},
                 {"triangles", 12, Type::TYPE_MESSAGE, true, "foxglove.TriangleListPrimitive"},
                 {"texts", 13, Type::TYPE_MESSAGE, true, "foxglove.TextPrimitive"},
                 {"models", 14, Type::TYPE_MESSAGE, true, "foxglove.ModelPrimitive"}},
                scene);
  expect_fields("foxglove.SceneEntityDeletion",
                {{"timestamp", 1, Type::TYPE_MESSAGE, false, kTimestamp},
                 {"type", 2, Type::TYPE_ENUM, false, "foxglove.SceneEntityDeletion.Type"},
                 {"id", 3, Type::TYPE_STRING}},
                scene);
  expect_fields("foxglove.LinePrimitive",
                {{"type", 1, Type::TYPE_ENUM, false, "foxglove.LinePrimitive.Type"},
                 {"pose", 2, Type::TYPE_MESSAGE, false, "foxglove.Pose"},
                 {"thickness", 3, Type::TYPE_DOUBLE},
                 {"scale_invariant", 4, Type::TYPE_BOOL},
                 {"points", 5, Type::TYPE_MESSAGE, true, "foxglove.Point3"},
                 {"color", 6, Type::TYPE_MESSAGE, false, "foxglove.Color"},
                 {"colors", 7, Type::TYPE_MESSAGE, true, "foxglove.Color"},
                 {"indices", 8, Type::TYPE_FIXED32, true}},
                scene);
  expect_fields("foxglove.CylinderPrimitive",
                {{"pose", 1, Type::TYPE_MESSAGE, false, "foxglove.Pose"},
                 {"size", 2, Type::TYPE_MESSAGE, false, "foxglove.Vector3"},
                 {"bottom_scale", 3, Type::TYPE_DOUBLE},
                 {"top_scale", 4, Type::TYPE_DOUBLE},
                 {"color", 5, Type::TYPE_MESSAGE, false, "foxglove.Color"}},
                scene);
  expect_fields("foxglove.ModelPrimitive",
                {{"pose", 1, Type::TYPE_MESSAGE, false, "foxglove.Pose"},
                 {"scale", 2, Type::TYPE_MESSAGE, false, "foxglove.Vector3"},
                 {"color", 3, Type::TYPE_MESSAGE, false, "foxglove.Color"},
                 {"override_color", 4, Type::TYPE_BOOL},
                 {"url", 5, Type::TYPE_STRING},
                 {"media_type", 6, Type::TYPE_STRING},
                 {"data", 7, Type::TYPE_BYTES}},
                scene);
  expect_fields("foxglove.Log",
                {{"timestamp", 1, Type::TYPE_MESSAGE, false, kTimestamp},
                 {"level", 2, Type::TYPE_ENUM, false, "foxglove.Log.Level"},
                 {"message", 3, Type::TYPE_STRING},
                 {"name", 4, Type::TYPE_STRING},
                 {"file", 5, Type::TYPE_STRING},
                 {"line", 6, Type::TYPE_FIXED32}},
                schema_for<foxglove::Log>());
}

TEST(RecordSchemas, JointStateValuesAreProto3OptionalAndEnumsAreFoxglovesValues) {
  // JointState's position ... effort are `optional`: a joint without effort sensing records
  // "absent", not 0 Nm.
  for (const char* name : {"position", "velocity", "acceleration", "effort"}) {
    EXPECT_TRUE(foxglove::JointState::descriptor()->FindFieldByName(name)->has_optional_keyword())
        << name;
  }
  EXPECT_EQ(foxglove::Log::WARNING, 3);
  EXPECT_EQ(foxglove::Log::FATAL, 5);
  EXPECT_EQ(foxglove::LinePrimitive::LINE_LIST, 2);
  EXPECT_EQ(foxglove::SceneEntityDeletion::ALL, 1);
}

TEST(RecordSchemas, CompressedImageDecodesThroughTheSetAlone) {
  foxglove::CompressedImage image;
  set_time(*image.mutable_timestamp());
  image.set_frame_id("left_camera_optical");
  image.set_data(std::string("\xff\xd8\x00\x01\xff\xd9", 6));  // bytes, NULs included
  image.set_format("jpeg");
  ReaderPool reader(schema_for<foxglove::CompressedImage>());
  const auto decoded = decode_as_reader(reader, image);
  ASSERT_NE(decoded, nullptr);
  // Read as Foxglove reads it, by field name through reflection.
  const auto* reflection = decoded->GetReflection();
  const auto* descriptor = decoded->GetDescriptor();
  EXPECT_EQ(reflection->GetString(*decoded, descriptor->FindFieldByName("frame_id")),
            "left_camera_optical");
  EXPECT_EQ(reflection->GetString(*decoded, descriptor->FindFieldByName("data")), image.data());
  const auto& stamp = reflection->GetMessage(*decoded, descriptor->FindFieldByName("timestamp"));
  EXPECT_EQ(
      stamp.GetReflection()->GetInt64(stamp, stamp.GetDescriptor()->FindFieldByName("seconds")),
      1'700'000'000);
}

TEST(RecordSchemas, CalibrationJointsTransformsAndLogDecodeThroughTheirSets) {
  foxglove::CameraCalibration calibration;
  set_time(*calibration.mutable_timestamp());
  calibration.set_frame_id("right_camera_optical");
  calibration.set_width(1280);
  calibration.set_height(720);
  calibration.set_distortion_model("plumb_bob");
  for (double d : {-0.1, 0.02, 0.0, 0.0, 0.001}) calibration.add_d(d);
  for (double k : {600.0, 0.0, 640.0, 0.0, 601.0, 360.0, 0.0, 0.0, 1.0}) calibration.add_k(k);
  ReaderPool calibration_reader(schema_for<foxglove::CameraCalibration>());
  decode_as_reader(calibration_reader, calibration);

  foxglove::JointStates joints;
  set_time(*joints.mutable_timestamp());
  auto* shoulder = joints.add_joints();
  shoulder->set_name("shoulder");
  shoulder->set_position(0.0);  // present though zero
  shoulder->set_velocity(-0.5);
  joints.add_joints()->set_name("gripper");
  ReaderPool joint_reader(schema_for<foxglove::JointStates>());
  const auto decoded_joints = decode_as_reader(joint_reader, joints);
  ASSERT_NE(decoded_joints, nullptr);
  // Presence survives the trip: position 0 is there, effort is not.
  const auto* joints_field = decoded_joints->GetDescriptor()->FindFieldByName("joints");
  const auto& first =
      decoded_joints->GetReflection()->GetRepeatedMessage(*decoded_joints, joints_field, 0);
  EXPECT_TRUE(
      first.GetReflection()->HasField(first, first.GetDescriptor()->FindFieldByName("position")));
  EXPECT_FALSE(
      first.GetReflection()->HasField(first, first.GetDescriptor()->FindFieldByName("effort")));

  foxglove::FrameTransforms transforms;
  auto* transform = transforms.add_transforms();
  set_time(*transform->mutable_timestamp());
  transform->set_parent_frame_id("world");
  transform->set_child_frame_id("base_link");
  transform->mutable_translation()->set_y(0.25);
  transform->mutable_rotation()->set_w(1.0);
  ReaderPool transform_reader(schema_for<foxglove::FrameTransforms>());
  decode_as_reader(transform_reader, transforms);

  foxglove::Log log;
  set_time(*log.mutable_timestamp());
  log.set_level(foxglove::Log::WARNING);
  log.set_message("plan validated with 1 warning");
  log.set_name("telear");
  log.set_file("session.cpp");
  log.set_line(42);
  ReaderPool log_reader(schema_for<foxglove::Log>());
  decode_as_reader(log_reader, log);
}

TEST(RecordSchemas, SceneUpdateWithEveryPrimitiveDecodesThroughItsSet) {
  foxglove::SceneUpdate update;
  auto* deletion = update.add_deletions();
  set_time(*deletion->mutable_timestamp());
  deletion->set_type(foxglove::SceneEntityDeletion::ALL);
  auto* entity = update.add_entities();
  set_time(*entity->mutable_timestamp());
  entity->set_frame_id("base_link");
  entity->set_id("ghost");
  entity->mutable_lifetime()->set_nanos(500'000'000);
  entity->set_frame_locked(true);
  auto* pair = entity->add_metadata();
  pair->set_key("plan_id");
  pair->set_value("p1");
  auto* arrow = entity->add_arrows();
  *arrow->mutable_pose() = make_pose();
  arrow->set_shaft_length(0.2);
  arrow->set_head_diameter(0.03);
  *arrow->mutable_color() = make_color();
  auto* cube = entity->add_cubes();
  *cube->mutable_pose() = make_pose();
  cube->mutable_size()->set_x(0.1);
  auto* sphere = entity->add_spheres();
  sphere->mutable_size()->set_z(0.05);
  *sphere->mutable_color() = make_color();
  auto* cylinder = entity->add_cylinders();
  cylinder->set_bottom_scale(1.0);
  cylinder->set_top_scale(0.5);
  auto* line = entity->add_lines();
  line->set_type(foxglove::LinePrimitive::LINE_LIST);
  line->set_thickness(2.0);
  line->set_scale_invariant(true);
  line->add_points()->set_x(1.0);
  line->add_points()->set_y(1.0);
  *line->add_colors() = make_color();
  line->add_indices(1);
  line->add_indices(0);
  auto* triangles = entity->add_triangles();
  for (int i = 0; i < 3; ++i) triangles->add_points()->set_z(i);
  triangles->add_indices(2);
  auto* text = entity->add_texts();
  text->set_billboard(true);
  text->set_font_size(12.0);
  text->set_text("collision: link 3 / table");
  auto* model = entity->add_models();
  *model->mutable_pose() = make_pose();
  model->mutable_scale()->set_x(1.0);
  model->set_override_color(true);
  model->set_media_type("model/gltf-binary");
  model->set_data(std::string("glTF\x02\x00", 6));
  ReaderPool reader(schema_for<foxglove::SceneUpdate>());
  decode_as_reader(reader, update);
}

TEST(RecordSchemas, LatencyStagesHaveAFieldPerNetStageNamedByItsKey) {
  // One field per kLatencyStages entry, key + "_s", in the table's order: the recorder maps a
  // StageLatency onto the message by the table, and a stage added there fails here until the
  // schema has it.
  const auto* descriptor = v1::LatencyStages::descriptor();
  int number = 3;
  for (const auto& stage : net::kLatencyStages) {
    const auto* field = descriptor->FindFieldByName(std::string(stage.key) + "_s");
    ASSERT_NE(field, nullptr) << stage.key;
    EXPECT_EQ(field->type(), Type::TYPE_DOUBLE) << stage.key;
    EXPECT_EQ(field->number(), number++) << stage.key;
  }
  EXPECT_TRUE(descriptor->FindFieldByName("decoded_to_shown_s")->has_optional_keyword());

  v1::LatencyStages stages;
  set_time(*stages.mutable_timestamp());
  stages.set_frame_id(981);
  stages.set_capture_to_encode_s(0.002);
  stages.set_network_s(0.011);
  stages.set_total_s(0.031);
  stages.set_decoded_to_shown_s(0.0);
  ReaderPool reader(schema_for<v1::LatencyStages>());
  decode_as_reader(reader, stages);
}

TEST(RecordSchemas, PlanEventCarriesKindTextPlanAndHash) {
  expect_fields("telear.record.v1.PlanEvent",
                {{"timestamp", 1, Type::TYPE_MESSAGE, false, kTimestamp},
                 {"kind", 2, Type::TYPE_ENUM, false, "telear.record.v1.PlanEvent.Kind"},
                 {"text", 3, Type::TYPE_STRING},
                 {"plan_id", 4, Type::TYPE_STRING},
                 {"plan_hash", 5, Type::TYPE_STRING}},
                schema_for<v1::PlanEvent>());
  v1::PlanEvent event;
  set_time(*event.mutable_timestamp());
  event.set_kind(v1::PlanEvent::VALIDATE);
  event.set_text("ok");
  event.set_plan_id("plan-7");
  event.set_plan_hash(std::string(64, 'a'));
  ReaderPool reader(schema_for<v1::PlanEvent>());
  const auto decoded = decode_as_reader(reader, event);
  ASSERT_NE(decoded, nullptr);
  const auto* kind = decoded->GetDescriptor()->FindFieldByName("kind");
  EXPECT_EQ(decoded->GetReflection()->GetEnum(*decoded, kind)->name(), "VALIDATE");
}

}  // namespace
}  // namespace telear::record
