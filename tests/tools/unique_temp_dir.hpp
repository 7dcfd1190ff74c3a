#pragma once
// A directory of the test's own under the temp directory, made by mkdtemp
// (a name no other process, clone or test has) and removed with what it
// holds when it goes. Tests that write files use it rather than a fixed
// name: two checkouts running their tests at once must not share a file.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace tnv::test {

class UniqueTempDir {
 public:
  explicit UniqueTempDir(const std::string& prefix = "tnv-test") {
    std::string templ = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
    if (::mkdtemp(templ.data()) != nullptr) path_ = templ;
    EXPECT_FALSE(path_.empty()) << "mkdtemp " << templ;
  }
  ~UniqueTempDir() {
    std::error_code ec;
    if (!path_.empty()) std::filesystem::remove_all(path_, ec);
  }
  UniqueTempDir(const UniqueTempDir&) = delete;
  UniqueTempDir& operator=(const UniqueTempDir&) = delete;

  const std::filesystem::path& path() const noexcept { return path_; }
  std::filesystem::path operator/(const std::string& leaf) const { return path_ / leaf; }

 private:
  std::filesystem::path path_;
};

}  // namespace tnv::test
