#pragma once
// The schemas of telear's recordings as MCAP stores them: each channel's Schema record names a
// protobuf message ("foxglove.CompressedImage"), says encoding "protobuf", and holds the
// serialized google.protobuf.FileDescriptorSet of the message's .proto file with every file it
// imports. A reader (Foxglove, @mcap/support, telear's replay) builds a descriptor pool from
// that set alone and decodes the messages with it, so the set must be self-contained:
// dependencies before the files that import them (the order a pool can build them in), each
// file once.
//
// The messages are generated from proto/ (telear::record_schemas_proto):
//   Foxglove's  foxglove/CompressedImage.pb.h, CameraCalibration, JointStates, FrameTransforms,
//               SceneUpdate, Log (and the messages they contain)
//   telear's    telear/record/v1/latency_stages.pb.h, plan_event.pb.h (telear.record.v1)

#include <string>
#include <string_view>

namespace google::protobuf {
class Descriptor;
}

namespace telear::record {

// The MCAP schema/message encoding of protobuf (MCAP's well-known encodings).
inline constexpr std::string_view kProtobufEncoding = "protobuf";

// What an MCAP Schema record holds for one message type.
struct SchemaInfo {
  std::string name;      // the message's full name: "foxglove.CompressedImage"
  std::string encoding;  // kProtobufEncoding
  std::string data;      // file_descriptor_set(message)
};

// The serialized google.protobuf.FileDescriptorSet of `message`'s file and all its transitive
// imports (google/protobuf/timestamp.proto included), dependencies first, each file once,
// without source comments (readers do not need them; they would triple the size).
std::string file_descriptor_set(const google::protobuf::Descriptor& message);

SchemaInfo schema_info(const google::protobuf::Descriptor& message);

// schema_for<foxglove::CompressedImage>(): the schema of a generated message class.
template <class Message>
SchemaInfo schema_for() {
  return schema_info(*Message::descriptor());
}

}  // namespace telear::record
