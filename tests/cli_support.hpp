// Running the hgrid binary from a test, and a temporary folder per test.
#pragma once
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace hgrid::test {

namespace fs = std::filesystem;

struct Result {
  int status;
  std::string out;
  std::string err;
};

/// Runs the hgrid binary with the given arguments (and `env`, "NAME='value'
/// ...", set for it); stdout and stderr captured.
inline Result hgrid_run(const std::string& args, const std::string& env = "") {
  static int counter = 0;
  const fs::path err = fs::temp_directory_path() / ("hgrid_test_err_" + std::to_string(::getpid()) + "_" +
                                                    std::to_string(counter++));
  const std::string cmd = env + (env.empty() ? "" : " ") + std::string(HGRID_BINARY) + " " + args + " 2>" + err.string();
  Result r{};
  FILE* pipe = ::popen(cmd.c_str(), "r");
  std::array<char, 4096> buf;
  std::size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
  const int st = ::pclose(pipe);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  std::ifstream e(err);
  r.err.assign(std::istreambuf_iterator<char>(e), {});
  fs::remove(err);
  return r;
}

class TempDir : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("hgridlab_" + std::to_string(::getpid()) + "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

}  // namespace hgrid::test
