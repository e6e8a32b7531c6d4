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
  std::string_view job;  // the JPEG to decode, valid while pending
  bool job_planes = false;
  std::optional<Result<core::Image>> result;       // set by the worker (RGB)
  std::optional<Result<core::YCbCrImage>> planes;  // set by the worker (planes)
  bool pending = false, stopping = false;
  std::thread thread;

  void run() {
    std::unique_lock lock(mutex);
    while (true) {
      wake.wait(lock, [&] { return pending || stopping; });
      if (stopping) return;
      const std::string_view jpeg = job;
      const bool to_planes = job_planes;
      lock.unlock();
      if (to_planes) {
        Result<core::YCbCrImage> decoded = worker_decoder.decode_planes(jpeg);
        lock.lock();
        planes.emplace(std::move(decoded));
      } else {
        Result<core::Image> image = worker_decoder.decode(jpeg);
        lock.lock();
        result.emplace(std::move(image));
      }
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
  return decode_pair(left_jpeg, right_jpeg, false);
}

Result<DecodedPair> StereoJpegDecoder::decode_planes(std::string_view left_jpeg,
                                                     std::string_view right_jpeg) {
  return decode_pair(left_jpeg, right_jpeg, true);
}

Result<DecodedPair> StereoJpegDecoder::decode_pair(std::string_view left_jpeg,
                                                   std::string_view right_jpeg, bool planes) {
  Worker& w = *worker_;
  {
    std::lock_guard lock(w.mutex);
    w.job = right_jpeg;
    w.job_planes = planes;
    w.result.reset();
    w.planes.reset();
    w.pending = true;
  }
  w.wake.notify_one();
  DecodedPair pair;
  std::optional<Error> left_error;
  if (planes) {
    auto left = w.caller_decoder.decode_planes(left_jpeg);
    if (left)
      pair.left_planes = std::move(*left);
    else
      left_error = left.error();
  } else {
    auto left = w.caller_decoder.decode(left_jpeg);
    if (left)
      pair.left = std::move(*left);
    else
      left_error = left.error();
  }
  std::unique_lock lock(w.mutex);
  w.done.wait(lock, [&] { return !w.pending; });
  std::optional<Error> right_error;
  if (planes) {
    if (*w.planes)
      pair.right_planes = std::move(**w.planes);
    else
      right_error = w.planes->error();
  } else {
    if (*w.result)
      pair.right = std::move(**w.result);
    else
      right_error = w.result->error();
  }
  w.result.reset();
  w.planes.reset();
  lock.unlock();
  if (left_error) return Error{"left eye: " + left_error->message};
  if (right_error) return Error{"right eye: " + right_error->message};
  return pair;
}

}  // namespace telear::net
