// SPDX-License-Identifier: MIT
#pragma once
// A fresh directory under the test temp dir, named after the test and the
// process, removed when the test passes and kept for inspection when it
// fails.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace rwd::test {

class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name)
      : path_(std::filesystem::path(testing::TempDir()) /
              (name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    if (!::testing::Test::HasFailure()) std::filesystem::remove_all(path_);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace rwd::test
