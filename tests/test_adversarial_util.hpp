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

#include "support/cli_fixture.hpp"

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

// A fresh directory per test (removed afterwards unless the test failed).
class TempDirTest : public CliDirTest {
 protected:
  TempDirTest() : CliDirTest("deltamesh_adv") {}

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    CliDirTest::write(name, text);
    return path(name);
  }

  // Runs the CLI in the temporary directory; `args` is passed to the shell.
  CliResult run(const std::string& args) const { return run_program(DELTAMESH_CLI, args); }

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
};

}  // namespace deltamesh::test

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << "expected '" << (needle) << "' in:\n" << (haystack)
