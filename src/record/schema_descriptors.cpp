#include "telear/record/schema_descriptors.hpp"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/descriptor.pb.h>

#include <set>

namespace telear::record {

namespace {

// Depth-first, a file after its imports: the order DescriptorPool::BuildFile accepts them in
// (a file whose import is not yet in the pool fails to build). `added` keeps a file imported
// along two paths (foxglove/Pose.proto by every primitive) to its first place.
void add_with_dependencies(const google::protobuf::FileDescriptor& file,
                           std::set<std::string>& added, google::protobuf::FileDescriptorSet& set) {
  if (!added.insert(file.name()).second) {
    return;
  }
  for (int i = 0; i < file.dependency_count(); ++i) {
    add_with_dependencies(*file.dependency(i), added, set);
  }
  // CopyTo leaves out source_code_info (the comments): readers decode without them.
  file.CopyTo(set.add_file());
}

}  // namespace

std::string file_descriptor_set(const google::protobuf::Descriptor& message) {
  google::protobuf::FileDescriptorSet set;
  std::set<std::string> added;
  add_with_dependencies(*message.file(), added, set);
  return set.SerializeAsString();
}

SchemaInfo schema_info(const google::protobuf::Descriptor& message) {
  return {message.full_name(), std::string(kProtobufEncoding), file_descriptor_set(message)};
}

}  // namespace telear::record
