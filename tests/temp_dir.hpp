#pragma once
// Test helper shared by every test area: a fixture whose every test works in its own empty
// folder under the system temp folder, removed afterwards.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <system_error>

namespace exemplar::testing {

/// A fresh, empty folder for the running test: exemplar_<suite>_<pid>_<test> under the system
/// temp folder (the '/' of parameterized names replaced), so parallel ctest runs never share one.
inline std::filesystem::path fresh_test_dir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "exemplar_";
    if (info != nullptr) name.append(info->test_suite_name()).append("_");
    name.append(std::to_string(::getpid()));
    if (info != nullptr) name.append("_").append(info->name());
    std::replace(name.begin(), name.end(), '/', '_');
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

/// Fixture base: `dir_` is the running test's fresh folder, `path(name)` a file in it.
/// Fixtures that add set-up call `TempDirTest::SetUp()` first.
class TempDirTest : public ::testing::Test {
protected:
    void SetUp() override { dir_ = fresh_test_dir(); }
    void TearDown() override {
        std::error_code ec;
        std::filesystem::remove_all(dir_, ec);
    }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    std::filesystem::path dir_;
};

}  // namespace exemplar::testing
