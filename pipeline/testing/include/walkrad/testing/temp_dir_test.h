// A test fixture with its own empty temporary folder, removed afterwards (bakes write there).
#pragma once

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

namespace walkrad::test {

class TempDirTest : public testing::Test {
 protected:
  void SetUp() override {
    const testing::TestInfo* info = testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::path(testing::TempDir()) /
           ("walkrad-" + std::string(info->test_suite_name()) + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

// Every file of bake folder a but its report (which holds times) has the same bytes in b.
inline void expect_same_bake_files(const std::string& a, const std::string& b) {
  for (const auto& f : std::filesystem::directory_iterator(a)) {
    if (f.path().filename() == "report.json") continue;
    std::ifstream x(f.path(), std::ios::binary), y(std::filesystem::path(b) / f.path().filename(), std::ios::binary);
    EXPECT_TRUE(y.good()) << f.path().filename() << " missing from " << b;
    EXPECT_TRUE(std::equal(std::istreambuf_iterator<char>(x), {}, std::istreambuf_iterator<char>(y), {})) << f.path();
  }
}

}  // namespace walkrad::test
