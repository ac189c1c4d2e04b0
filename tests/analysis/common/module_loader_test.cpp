// Finding and loading Oscilab's modules, and the one error each way of failing gives. The module
// under test is a tiny one of the tests' own (test_module.cpp, built into OSCILAB_TEST_MODULE_DIR)
// and names no real module is loaded here: the loader keeps what it loaded for the process.
#include "analysis/common/module_loader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <unistd.h>

#include "tests/input_error_of.h"

namespace oscilab {
namespace {

namespace fs = std::filesystem;
using testing::input_error_of;

// Sets OSCILAB_MODULE_DIR for the scope of one test, and an empty directory to point it at.
class ModuleDirOverride {
 public:
  ModuleDirOverride()
      : empty_(fs::temp_directory_path() / ("oscilab_modules_" + std::to_string(::getpid()))) {
    fs::create_directories(empty_);
  }
  ~ModuleDirOverride() {
    ::unsetenv(kModuleDirVariable);
    fs::remove_all(empty_);
  }
  void set(const fs::path& directory) { ::setenv(kModuleDirVariable, directory.c_str(), 1); }
  const fs::path& empty() const { return empty_; }

 private:
  fs::path empty_;
};

TEST(ModuleLoader, SearchesBesideTheBinaryFirstThenTheInstallationAndTheBuildTree) {
  ::unsetenv(kModuleDirVariable);
  const std::vector<std::string> directories = module_directories();
  ASSERT_FALSE(directories.empty());
  // This test runs from build/tests: build/tests/../lib/oscilab, where the build puts modules.
  const fs::path own = fs::canonical("/proc/self/exe").parent_path();
  EXPECT_EQ(fs::weakly_canonical(directories.front()),
            fs::weakly_canonical(own / OSCILAB_MODULE_RELATIVE_DIR));
  // The configured installation and build tree follow, each directory once (in the build tree the
  // first one is the build tree's).
  const auto position = [&](const std::string& directory) {
    return std::find(directories.begin(), directories.end(),
                     fs::path(directory).lexically_normal().string()) -
           directories.begin();
  };
  const auto count = static_cast<std::ptrdiff_t>(directories.size());
  EXPECT_LT(position(OSCILAB_MODULE_INSTALL_DIR), count);
  EXPECT_LT(position(OSCILAB_MODULE_BUILD_DIR), count);
  EXPECT_EQ(std::set<std::string>(directories.begin(), directories.end()).size(),
            directories.size());
}

TEST(ModuleLoader, TheEnvironmentOverrideIsTheOnlyDirectorySearched) {
  ModuleDirOverride override_dir;
  override_dir.set(override_dir.empty());
  EXPECT_EQ(module_directories(), std::vector<std::string>{override_dir.empty().string()});
}

TEST(ModuleLoader, ThrowsOneInputErrorNamingTheModuleAndTheDirectoriesWhenNotFound) {
  ModuleDirOverride override_dir;
  override_dir.set(override_dir.empty());
  EXPECT_EQ(input_error_of([] {
              module_entry("oscilab_hdf5_module.so", "oscilab_hdf5_module_v1", "reading x.mat");
            }),
            "reading x.mat needs oscilab_hdf5_module.so: not found in " +
                override_dir.empty().string() + " (OSCILAB_MODULE_DIR)");
}

TEST(ModuleLoader, SaysWhereItLookedWithoutTheOverride) {
  ::unsetenv(kModuleDirVariable);
  const std::string message = input_error_of(
      [] { module_entry("oscilab_no_such_module.so", "entry_v1", "writing fig.png"); });
  EXPECT_EQ(message.rfind("writing fig.png needs oscilab_no_such_module.so: not found in ", 0), 0u)
      << message;
  for (const std::string& directory : module_directories()) {
    EXPECT_NE(message.find(directory), std::string::npos) << directory << " in " << message;
  }
}

TEST(ModuleLoader, FindsAModuleAndItsEntryPoint) {
  ModuleDirOverride override_dir;
  override_dir.set(OSCILAB_TEST_MODULE_DIR);
  const auto answer = reinterpret_cast<int (*)()>(
      module_entry("oscilab_test_module.so", "oscilab_test_module_answer_v1", "testing"));
  ASSERT_NE(answer, nullptr);
  EXPECT_EQ(answer(), 42);
}

TEST(ModuleLoader, ThrowsWhenTheModuleLacksTheEntryPoint) {
  ModuleDirOverride override_dir;
  override_dir.set(OSCILAB_TEST_MODULE_DIR);
  const std::string path = std::string(OSCILAB_TEST_MODULE_DIR) + "/oscilab_test_module.so";
  EXPECT_EQ(input_error_of([] {
              module_entry("oscilab_test_module.so", "oscilab_test_module_answer_v2", "testing");
            }),
            "testing needs oscilab_test_module.so: " + fs::path(path).lexically_normal().string() +
                " has no entry point oscilab_test_module_answer_v2 (a module of another Oscilab "
                "version?)");
}

TEST(ModuleLoader, ThrowsWhenTheModuleCannotBeLoaded) {
  ModuleDirOverride override_dir;
  override_dir.set(override_dir.empty());
  const fs::path broken = override_dir.empty() / "oscilab_broken_module.so";
  std::ofstream(broken) << "not a shared object\n";
  const std::string message =
      input_error_of([] { module_entry("oscilab_broken_module.so", "entry_v1", "testing"); });
  EXPECT_EQ(message.rfind(
                "testing needs oscilab_broken_module.so: cannot load " + broken.string() + ": ", 0),
            0u)
      << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

}  // namespace
}  // namespace oscilab
