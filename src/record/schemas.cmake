# record_schemas: the recording's protobuf schemas (proto/: Foxglove's and telear.record.v1),
# each with the FileDescriptorSet an MCAP Schema record stores (encoding "protobuf").
#
# No precompiled header, as record_mcap: one unit that includes only protobuf's headers, while
# telear_pch_level would give it the network layer's set (Eigen, OpenCV, gRPC, spdlog), whose
# include paths and definitions this library does not have. TELEAR_PCH is off for this one call
# (a normal variable over the cache entry), then the cache entry shows again.
set(TELEAR_PCH OFF)
telear_library(record_schemas schema_descriptors.cpp)
unset(TELEAR_PCH)
target_link_libraries(telear_record_schemas PUBLIC telear::record_schemas_proto
                                                   protobuf::libprotobuf)
