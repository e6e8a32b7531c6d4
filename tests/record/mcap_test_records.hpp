#pragma once
// A test-side view of an MCAP file's bytes, written from the specification
// (https://mcap.dev/spec) independently of src/record: it finds records and reads their
// little-endian fields, so that tests can check the layout the writer produced byte by byte.
// It trusts its input no further than a test needs: out-of-range reads fail the test.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace telear::record::mcap_test {

inline std::vector<std::uint8_t> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in.good()) << "cannot open " << path;
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline const std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

// Reads fields in order from [at, end) of a file's bytes.
class FieldReader {
 public:
  FieldReader(const std::vector<std::uint8_t>& bytes, std::uint64_t at, std::uint64_t end)
      : bytes_(bytes), at_(at), end_(end) {}

  template <typename T>
  T get() {
    T value{};
    if (at_ + sizeof(T) > end_ || end_ > bytes_.size()) {
      ADD_FAILURE() << "read of " << sizeof(T) << " bytes at " << at_ << " past " << end_;
      return value;
    }
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  std::string bytes(std::uint64_t n) {
    if (at_ + n > end_ || end_ > bytes_.size()) {
      ADD_FAILURE() << "read of " << n << " bytes at " << at_ << " past " << end_;
      return {};
    }
    std::string out(reinterpret_cast<const char*>(bytes_.data() + at_), n);
    at_ += n;
    return out;
  }
  std::string string() { return bytes(get<std::uint32_t>()); }
  std::uint64_t at() const { return at_; }
  std::uint64_t left() const { return end_ - at_; }

 private:
  const std::vector<std::uint8_t>& bytes_;
  std::uint64_t at_;
  std::uint64_t end_;
};

// One record: <opcode uint8><content length uint64><content>.
struct Record {
  std::uint8_t opcode = 0;
  std::uint64_t offset = 0;          // of the opcode, from the start of the file
  std::uint64_t content_offset = 0;  // offset + 9
  std::uint64_t length = 0;          // content length
  std::uint64_t end() const { return content_offset + length; }
  FieldReader fields(const std::vector<std::uint8_t>& bytes) const {
    return {bytes, content_offset, end()};
  }
};

inline Record record_at(const std::vector<std::uint8_t>& bytes, std::uint64_t offset) {
  Record r;
  r.offset = offset;
  FieldReader f(bytes, offset, bytes.size());
  r.opcode = f.get<std::uint8_t>();
  r.length = f.get<std::uint64_t>();
  r.content_offset = f.at();
  EXPECT_LE(r.end(), bytes.size()) << "record at " << offset << " runs past the file";
  return r;
}

// Consecutive records in [begin, end).
inline std::vector<Record> records_in(const std::vector<std::uint8_t>& bytes, std::uint64_t begin,
                                      std::uint64_t end) {
  std::vector<Record> out;
  for (std::uint64_t at = begin; at < end;) {
    out.push_back(record_at(bytes, at));
    if (out.back().end() > end) {
      ADD_FAILURE() << "record at " << at << " runs past " << end;
      break;
    }
    at = out.back().end();
  }
  return out;
}

}  // namespace telear::record::mcap_test
