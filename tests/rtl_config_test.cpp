// The named-builds file (sim/harness/builds.json) reader: its fault_hooks flag and the errors a
// malformed entry gets, each naming the file, the build and the field.
#include "sim/harness/rtl_config.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace shadesim {
namespace {

std::string write_builds(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("shadesim-rtl-config-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::string path = (dir / name).string();  // returned: moved
  std::ofstream(path) << text;
  return path;
}

std::string load_error(const std::string& path) {
  try {
    load_named_builds(path);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(RtlConfig, FaultHooksIsReadAndDefaultsOff) {
  const std::string path =
      write_builds("ok.json", R"({"a": {"unit": {}, "fault_hooks": true}, "b": {"unit": {}}})");
  const auto builds = load_named_builds(path);
  ASSERT_EQ(builds.size(), 2u);
  EXPECT_TRUE(builds[0].faults.hooks);
  EXPECT_FALSE(builds[1].faults.hooks);
  EXPECT_EQ(fault_text(builds[0].faults), " fault-hooks");
  EXPECT_EQ(fault_text(builds[1].faults), "");
}

TEST(RtlConfig, MalformedEntriesNameFileBuildAndField) {
  const std::string not_bool =
      write_builds("not_bool.json", R"({"a": {"unit": {}, "fault_hooks": 1}})");
  const std::string msg = load_error(not_bool);
  EXPECT_NE(msg.find(not_bool + ": a.fault_hooks: expected true or false, got 1"),
            std::string::npos)
      << msg;
  // A per-fault key ("faults") is not one the file has: it must not be ignored silently.
  const std::string old_key =
      write_builds("old_key.json", R"({"a": {"unit": {}, "faults": {"lsb_row": 17}}})");
  const std::string old = load_error(old_key);
  EXPECT_NE(old.find(old_key + ": a.faults: unknown key"), std::string::npos) << old;
}

}  // namespace
}  // namespace shadesim
