#include "telear/net/stereo_jpeg_decoder.hpp"

#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>

#include "telear/net/jpeg_codec.hpp"

namespace telear::net {

struct StereoJpegDecoder::Worker {
  JpegDecoder caller_decoder;  // the calling thread's (left eye)
  JpegDecoder worker_decoder;  // the worker's (right eye)
  std::mutex mutex;
  std::condition_variable wake, done;
  std::string_view job;                       // the JPEG to decode, valid while pending
  std::optional<Result<core::Image>> result;  // set by the worker
  bool pending = false, stopping = false;
  std::thread thread;

  void run() {
    std::unique_lock lock(mutex);
    while (true) {
      wake.wait(lock, [&] { return pending || stopping; });
      if (stopping) return;
      const std::string_view jpeg = job;
      lock.unlock();
      Result<core::Image> image = worker_decoder.decode(jpeg);
      lock.lock();
      result.emplace(std::move(image));
      pending = false;
      done.notify_one();
    }
  }
};

StereoJpegDecoder::StereoJpegDecoder() : worker_(std::make_unique<Worker>()) {
  worker_->thread = std::thread([w = worker_.get()] { w->run(); });
}

StereoJpegDecoder::~StereoJpegDecoder() {
  {
    std::lock_guard lock(worker_->mutex);
    worker_->stopping = true;
  }
  worker_->wake.notify_one();
  worker_->thread.join();
}

Result<DecodedPair> StereoJpegDecoder::decode(std::string_view left_jpeg,
                                              std::string_view right_jpeg) {
  Worker& w = *worker_;
  {
    std::lock_guard lock(w.mutex);
    w.job = right_jpeg;
    w.result.reset();
    w.pending = true;
  }
  w.wake.notify_one();
  Result<core::Image> left = w.caller_decoder.decode(left_jpeg);
  std::unique_lock lock(w.mutex);
  w.done.wait(lock, [&] { return !w.pending; });
  Result<core::Image> right = std::move(*w.result);
  w.result.reset();
  lock.unlock();
  if (!left) return Error{"left eye: " + left.error().message};
  if (!right) return Error{"right eye: " + right.error().message};
  return DecodedPair{std::move(*left), std::move(*right)};
}

}  // namespace telear::net
