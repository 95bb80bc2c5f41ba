#pragma once
// The error of bad input (exit code 2): a model file, a file it reads (grains, specimen) or a
// value given on the command line. Its message names the file, the key and the line.
#include <stdexcept>
#include <string>
#include <utility>

namespace vorodec::io {

// Bad input: the message already names the file, the key and the line.
class ModelFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  // An error about one key: its dotted path ("stage[0].end_time") and the message without location.
  ModelFileError(const std::string& what, std::string key, std::string reason)
      : std::runtime_error(what), key_(std::move(key)), reason_(std::move(reason)) {}
  const std::string& key() const noexcept { return key_; }
  const std::string& reason() const noexcept { return reason_; }

 private:
  std::string key_, reason_;
};

}  // namespace vorodec::io
