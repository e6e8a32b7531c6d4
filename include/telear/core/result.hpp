#pragma once
// The one error policy of telear (docs/architecture.md): programmer errors assert; untrusted
// input (files, packets, CLI arguments) returns a Result whose error says what and why.

#include <cassert>
#include <string>
#include <utility>
#include <variant>

namespace telear {

struct Error {
  std::string message;
};

// Either a value or an Error. A minimal std::expected for C++20.
template <typename T>
class [[nodiscard]] Result {
 public:
  Result(T value) : storage_(std::move(value)) {}      // NOLINT(google-explicit-constructor)
  Result(Error error) : storage_(std::move(error)) {}  // NOLINT(google-explicit-constructor)

  bool ok() const { return std::holds_alternative<T>(storage_); }
  explicit operator bool() const { return ok(); }

  const T& value() const& {
    assert(ok() && "Result::value() called on an error");
    return std::get<T>(storage_);
  }
  T& value() & {
    assert(ok() && "Result::value() called on an error");
    return std::get<T>(storage_);
  }
  T&& value() && {
    assert(ok() && "Result::value() called on an error");
    return std::get<T>(std::move(storage_));
  }
  const T& operator*() const& { return value(); }
  T& operator*() & { return value(); }
  const T* operator->() const { return &value(); }
  T* operator->() { return &value(); }

  const Error& error() const {
    assert(!ok() && "Result::error() called on a value");
    return std::get<Error>(storage_);
  }

 private:
  std::variant<T, Error> storage_;
};

// Result<void>: success or an Error.
class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(Error error)
      : error_(std::move(error)), ok_(false) {}  // NOLINT(google-explicit-constructor)
  static Status Ok() { return {}; }

  bool ok() const { return ok_; }
  explicit operator bool() const { return ok_; }
  const Error& error() const {
    assert(!ok_ && "Status::error() called on success");
    return error_;
  }

 private:
  Error error_;
  bool ok_ = true;
};

}  // namespace telear
