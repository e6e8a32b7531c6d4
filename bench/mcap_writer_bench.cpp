// Google Benchmark program of the MCAP writer (telear::record::McapWriter, docs/recording.md):
// its write throughput on a session-like mix of messages, zstd at the default level and other
// levels, and uncompressed, against a raw fwrite() of the same payload bytes to the same folder
// in the same run (what a recorder could not beat):
//   build/bench/mcap_writer_bench
// Each iteration writes the whole set into a fresh file (open, every message, close: the
// summary included) under TMPDIR (/tmp by default, usually page cache: the CPU cost is what is
// measured, not the disk). Wall-clock time; bytes_per_second counts message payload bytes,
// file_vs_payload is the file's size over them.

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "telear/record/mcap_writer.hpp"

namespace {

struct Payload {
  std::uint16_t channel;  // 1: joint states, 2: camera
  std::string bytes;
};

// 1800 joint-state-like JSON messages (~150 B, compressible) and 200 camera frames of 20 KiB of
// random bytes (JPEG does not compress further): ~4.3 MB, 90 % of it images, as in a session.
const std::vector<Payload>& session_mix() {
  static const std::vector<Payload> payloads = [] {
    std::vector<Payload> out;
    std::mt19937_64 rng(1);
    for (int i = 0; i < 2000; ++i) {
      if (i % 10 == 9) {
        std::string frame(20 * 1024, '\0');
        for (char& c : frame) c = static_cast<char>(rng());
        out.push_back({2, std::move(frame)});
      } else {
        std::string joints = "{\"t\":" + std::to_string(i) + ",\"position\":[";
        for (int j = 0; j < 6; ++j) joints += std::to_string((rng() % 2000000) / 1e6 - 1.0) + ",";
        joints += "0],\"velocity\":[0,0,0,0,0,0],\"effort\":[0,0,0,0,0,0]}";
        out.push_back({1, std::move(joints)});
      }
    }
    return out;
  }();
  return payloads;
}

std::int64_t payload_bytes() {
  std::int64_t total = 0;
  for (const Payload& p : session_mix()) total += static_cast<std::int64_t>(p.bytes.size());
  return total;
}

std::string bench_file(const char* name) {
  const char* tmp = std::getenv("TMPDIR");
  return std::string(tmp && *tmp ? tmp : "/tmp") + "/telear_" + name;
}

void raw_fwrite(benchmark::State& state) {
  const std::string path = bench_file("raw_fwrite.bin");
  for (auto _ : state) {
    std::FILE* file = std::fopen(path.c_str(), "wb");
    if (!file) {
      state.SkipWithError("cannot create the file");
      break;
    }
    for (const Payload& p : session_mix()) std::fwrite(p.bytes.data(), 1, p.bytes.size(), file);
    std::fclose(file);
  }
  state.SetBytesProcessed(state.iterations() * payload_bytes());
  std::remove(path.c_str());
}
BENCHMARK(raw_fwrite)->Unit(benchmark::kMillisecond)->UseRealTime();

// Argument: the zstd level, or -1000 for no compression.
void mcap_writer(benchmark::State& state) {
  const std::string path = bench_file("mcap_writer.mcap");
  telear::record::McapWriterOptions options;
  if (state.range(0) == -1000) {
    options.compression = telear::record::McapCompression::kNone;
  } else {
    options.zstd_level = static_cast<int>(state.range(0));
  }
  std::uint64_t file_size = 0;
  for (auto _ : state) {
    auto writer = telear::record::McapWriter::open(path, options);
    if (!writer) {
      state.SkipWithError(writer.error().message.c_str());
      break;
    }
    writer->add_channel(0, "/joint_states", "json");
    writer->add_channel(0, "/camera/left/compressed", "json");
    std::uint32_t sequence = 0;
    for (const Payload& p : session_mix()) {
      const std::uint64_t t = 1'000'000ull * ++sequence;
      if (!writer->write(p.channel, sequence, t, t, telear::record::mcap_bytes(p.bytes))) {
        state.SkipWithError("write failed");
        break;
      }
    }
    if (!writer->close()) state.SkipWithError("close failed");
    file_size = writer->bytes_written();
  }
  state.SetBytesProcessed(state.iterations() * payload_bytes());
  state.counters["file_vs_payload"] =
      static_cast<double>(file_size) / static_cast<double>(payload_bytes());
  std::remove(path.c_str());
}
BENCHMARK(mcap_writer)
    ->ArgName("zstd_level")
    ->Arg(1)      // McapWriterOptions' default
    ->Arg(3)      // zstd's own default
    ->Arg(-1000)  // no compression
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
