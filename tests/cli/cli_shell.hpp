// Test helper for the CLI tests: run a shell command and collect its exit code
// and output; a scratch folder per test.
#pragma once
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

namespace mfsd::test {

struct Result {
  int code;            // exit code, or -1 when killed by a signal
  std::string output;  // stdout + stderr
};

inline Result shell(const std::string& command) {
  FILE* p = popen((command + " 2>&1").c_str(), "r");
  std::string out;
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, p)) out.append(buf, n);
  const int status = pclose(p);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

// `mfsd ARGS`, with `prefix` run before it in the same shell (e.g. a ulimit).
inline Result run_mfsd(const std::string& args, const std::string& prefix = "") {
  return shell(prefix + std::string(MFSD_BINARY) + " " + args);
}

// A fresh folder under the system's temporary folder, removed after the test.
class ScratchTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("mfsd_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->test_suite_name() + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

}  // namespace mfsd::test
