# record_mcap: the MCAP writer and reader (include/telear/record/mcap_writer.hpp,
# mcap_reader.hpp, docs/recording.md) over Debian's libzstd (libzstd-dev); no MCAP library is
# packaged, so the format is written here from the public specification.
#
# No precompiled header: the writer includes none of the third-party headers of telear's header
# sets, and telear_pch_level would give it the network layer's (gRPC, OpenCV), whose textual
# fallback needs include paths this library does not have. TELEAR_PCH is switched off for this
# one call (a normal variable over the cache entry), then the cache entry shows again.
set(TELEAR_PCH OFF)
telear_library(record_mcap mcap_reader.cpp mcap_reader_messages.cpp mcap_writer.cpp)
unset(TELEAR_PCH)
# By path rather than pkg-config's imported target: the installed package's config then needs no
# extra dependency lookup (cmake/telearConfig.cmake.in) for a library every Debian has.
find_path(TELEAR_ZSTD_INCLUDE_DIR zstd.h REQUIRED)
find_library(TELEAR_ZSTD_LIBRARY zstd REQUIRED)
target_include_directories(telear_record_mcap SYSTEM PRIVATE ${TELEAR_ZSTD_INCLUDE_DIR})
target_link_libraries(telear_record_mcap PRIVATE ${TELEAR_ZSTD_LIBRARY})
# The CRC-32 every chunk, the data section and the summary carry (telear/core/crc32.hpp).
target_link_libraries(telear_record_mcap PRIVATE telear::core)
