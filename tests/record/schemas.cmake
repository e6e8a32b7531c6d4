# The recording's schemas: each FileDescriptorSet self-contained and decodable the way Foxglove
# decodes it (a pool built from the set alone), and the wire definitions Foxglove's.
telear_test(record_schemas_test
  SOURCES schema_descriptors_test.cpp
  LIBS telear::record_schemas)
