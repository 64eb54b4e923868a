#pragma once
// Helpers shared by the umbra_tables tests.

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "umbra/tables/Table.h"

namespace umbra::tables::test {

namespace fs = std::filesystem;

// A fresh directory under the system temporary directory, removed at the end of a test.
class TempDirTest : public ::testing::Test {
protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::random_device rd;
    dir_ = fs::temp_directory_path() /
           ("umbra-tables-" + std::string(info->name()) + "-" + std::to_string(::getpid()) + "-" +
            std::to_string(rd()));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::add, ec);
    for (auto it = fs::recursive_directory_iterator(dir_, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
      if (it->is_directory()) fs::permissions(it->path(), fs::perms::owner_all,
                                              fs::perm_options::add, ec);
    }
    fs::remove_all(dir_, ec);
  }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  // Names of the entries of a directory, sorted.
  static std::vector<std::string> entries(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    return names;
  }
  fs::path dir_;
};

inline std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

// A table whose values encode their position: v = 1000*c + 10*y + x (+ a fraction).
inline Table makeTable(int width, int height, std::vector<std::string> channels) {
  Table t;
  t.width = width;
  t.height = height;
  t.channels = std::move(channels);
  const size_t nc = t.channels.size();
  t.data.resize(static_cast<size_t>(width) * static_cast<size_t>(height) * nc);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (size_t c = 0; c < nc; ++c)
        t.data[(static_cast<size_t>(y) * width + x) * nc + c] =
            1000.0f * static_cast<float>(c) + 10.0f * static_cast<float>(y) +
            static_cast<float>(x) + 0.25f;
  return t;
}

// Sets or unsets an environment variable for the scope of a test, then restores it.
class ScopedEnv {
public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value) {
      ::setenv(name, value, 1);
    } else {
      ::unsetenv(name);
    }
  }
  ~ScopedEnv() {
    if (old_) {
      ::setenv(name_.c_str(), old_->c_str(), 1);
    } else {
      ::unsetenv(name_.c_str());
    }
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

private:
  std::string name_;
  std::optional<std::string> old_;
};

}  // namespace umbra::tables::test
