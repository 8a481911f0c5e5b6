// Helpers of the adversarial-input and regression tests: a temporary
// directory per test, the CLI run as a process (exit code, stdout, stderr),
// and whether the build is instrumented by a sanitizer (slow tests scale
// down then, as they do when DELTAMESH_TEST_QUICK is set).
#pragma once
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#ifndef DELTAMESH_CLI
#error "DELTAMESH_CLI (path of the deltamesh binary) must be defined by the build"
#endif

namespace deltamesh::test {

// True in ASan/UBSan/TSan builds and when DELTAMESH_TEST_QUICK is set in the
// environment: tests with large inputs use smaller ones.
inline bool quick_tests() {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  return true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
  return true;
#endif
#endif
  const char* q = std::getenv("DELTAMESH_TEST_QUICK");
  return q != nullptr && *q != '\0' && *q != '0';
}

struct CliResult {
  int code = -1;  // exit code; -1 when killed by a signal
  std::string out;
  std::string err;
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A fresh directory per test (removed afterwards unless the test failed).
class TempDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("deltamesh_adv_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    if (!HasFailure()) {
      std::error_code ec;
      std::filesystem::permissions(dir_, std::filesystem::perms::owner_all, std::filesystem::perm_options::add, ec);
      std::filesystem::remove_all(dir_, ec);
    }
  }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return path(name);
  }
  bool exists(const std::string& name) const { return std::filesystem::exists(dir_ / name); }

  // Runs the CLI in the temporary directory; `args` is passed to the shell.
  CliResult run(const std::string& args) const {
    const auto out = dir_ / ".stdout", err = dir_ / ".stderr";
    const std::string cmd = "cd '" + dir_.string() + "' && '" + std::string(DELTAMESH_CLI) + "' " + args + " > '" +
                            out.string() + "' 2> '" + err.string() + "'";
    const int status = std::system(cmd.c_str());
    CliResult r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    std::filesystem::remove(out);
    std::filesystem::remove(err);
    return r;
  }

  // Names in a directory (default: the test's), sorted; the captured
  // stdout/stderr files are not listed.
  std::vector<std::string> listing(const std::string& sub = {}) const {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(sub.empty() ? dir_ : dir_ / sub)) {
      const std::string n = e.path().filename().string();
      if (n != ".stdout" && n != ".stderr") names.push_back(n);
    }
    std::sort(names.begin(), names.end());
    return names;
  }

  std::filesystem::path dir_;
};

}  // namespace deltamesh::test

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << "expected '" << (needle) << "' in:\n" << (haystack)
