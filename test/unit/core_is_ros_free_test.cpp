// The core library must build without ROS: no file under src/core or the core headers may include
// a ROS header. (The build enforces it too: tacs_core sees no catkin include directory.)
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "common/test_paths.h"

namespace {

TEST(CoreIsRosFree, NoRosIncludes) {
  namespace fs = std::filesystem;
  const fs::path root(tacs::test::sourceDir());
  const std::regex ros_include(
      R"(#\s*include\s*[<"](ros|rosbag|tf2_ros|tf2_eigen|sensor_msgs|geometry_msgs|nav_msgs|)"
      R"(visualization_msgs|std_msgs|pcl_conversions|pcl_ros|xmlrpcpp|tacs_graphs/ros|)"
      R"(tacs_graphs/[A-Z]\w*\.h)[/">])");
  int scanned = 0;
  for (const char* dir : {"src/core", "include/tacs_graphs"}) {
    for (const auto& entry : fs::recursive_directory_iterator(root / dir)) {
      if (!entry.is_regular_file()) continue;
      // The ROS layer's own headers live in include/tacs_graphs/ros/.
      if (entry.path().string().find("/include/tacs_graphs/ros/") != std::string::npos) continue;
      std::ifstream in(entry.path());
      std::string line;
      int line_no = 0;
      while (std::getline(in, line)) {
        ++line_no;
        EXPECT_FALSE(std::regex_search(line, ros_include))
            << entry.path() << ":" << line_no << ": " << line;
      }
      ++scanned;
    }
  }
  EXPECT_GT(scanned, 3);
}

}  // namespace
