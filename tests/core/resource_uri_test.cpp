// package:// search order (--package-path, robot file, ROS_PACKAGE_PATH), the depth search,
// the other URI forms and the error messages listing every place looked.

#include "telear/core/resource_uri.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>

#include "test_util/temp_dir.hpp"

namespace telear::core {
namespace {

using ::testing::ElementsAre;
using namespace test_files;

class MeshUriTest : public ::testing::Test {
 protected:
  std::string dir(const std::string& relative) const { return (tmp.path() / relative).string(); }
  std::string file(const std::string& relative) const {
    return tmp.write(relative, "solid x\nendsolid x\n");
  }
  TempDir tmp;
};

TEST_F(MeshUriTest, CallerPathsComeBeforeTheRobotFileBeforeRosPackagePath) {
  const std::string caller = file("caller/arm/meshes/link.stl");
  const std::string robot = file("robot/arm/meshes/link.stl");
  const std::string ros = file("ros/arm/meshes/link.stl");
  ResourceSearchPaths s;
  s.package_paths = {dir("caller")};
  s.robot_package_paths = {dir("robot")};
  s.ros_package_path = {dir("ros")};
  EXPECT_EQ(*resolve_resource_uri("package://arm/meshes/link.stl", s), caller);
  s.package_paths.clear();
  EXPECT_EQ(*resolve_resource_uri("package://arm/meshes/link.stl", s), robot);
  s.robot_package_paths.clear();
  EXPECT_EQ(*resolve_resource_uri("package://arm/meshes/link.stl", s), ros);
  // A package holding the file wins over an earlier one that lacks it.
  file("early/arm/other.stl");
  s.package_paths = {dir("early")};
  EXPECT_EQ(*resolve_resource_uri("package://arm/meshes/link.stl", s), ros);
}

TEST_F(MeshUriTest, ADirectoryNamedLikeThePackageIsThePackage) {
  const std::string path = file("src/arm/meshes/link.stl");
  ResourceSearchPaths s;
  s.package_paths = {dir("src/arm") + "/"};
  EXPECT_EQ(*resolve_resource_uri("package://arm/meshes/link.stl", s), path);
}

TEST_F(MeshUriTest, DepthSearchFindsPackagesWithAPackageXmlUpToThreeLevels) {
  const std::string deep = file("ws/src/group/arm/meshes/link.stl");
  tmp.write("ws/src/group/arm/package.xml", "<package/>");
  ResourceSearchPaths s;
  s.ros_package_path = {dir("ws")};
  EXPECT_EQ(*resolve_resource_uri("package://arm/meshes/link.stl", s), deep);
  EXPECT_THAT(find_package_dirs("arm", s), ElementsAre(dir("ws/src/group/arm")));

  // Without package.xml, or one level deeper, it is not a package.
  file("ws2/src/group/arm/meshes/link.stl");
  file("ws3/a/b/c/arm/meshes/link.stl");
  tmp.write("ws3/a/b/c/arm/package.xml", "<package/>");
  s.ros_package_path = {dir("ws2"), dir("ws3")};
  EXPECT_TRUE(find_package_dirs("arm", s).empty());
}

TEST_F(MeshUriTest, NotFoundListsEveryPlaceLookedAndTheFix) {
  ResourceSearchPaths s;
  s.package_paths = {dir("a")};
  s.ros_package_path = {dir("b")};
  auto r = resolve_resource_uri("package://arm/meshes/forearm.stl", s);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message, "mesh 'package://arm/meshes/forearm.stl' not found (looked in " +
                                   dir("a/arm") + ", " + dir("b/arm") +
                                   "; set ROS_PACKAGE_PATH or add a package path)");
  // A package found without the file: it is named as the place looked.
  file("b/arm/meshes/upper.stl");
  r = resolve_resource_uri("package://arm/meshes/forearm.stl", s);
  ASSERT_FALSE(r);
  EXPECT_THAT(r.error().message, ::testing::HasSubstr("(looked in " + dir("b/arm") + ";"));

  r = resolve_resource_uri("package://arm/meshes/forearm.stl", ResourceSearchPaths{});
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message,
            "mesh 'package://arm/meshes/forearm.stl' not found (no package search path; set "
            "ROS_PACKAGE_PATH or add a package path)");
}

TEST_F(MeshUriTest, FileUrisAbsoluteAndRelativePaths) {
  const std::string path = file("urdf/meshes/link.stl");
  ResourceSearchPaths s;
  s.base_dir = dir("urdf");
  EXPECT_EQ(*resolve_resource_uri("file://" + path, s), path);
  EXPECT_EQ(*resolve_resource_uri(path, s), path);
  EXPECT_EQ(*resolve_resource_uri("meshes/link.stl", s), path);
  auto r = resolve_resource_uri("meshes/none.stl", s);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message,
            "mesh 'meshes/none.stl' not found: " + dir("urdf") + "/meshes/none.stl does not exist");
}

TEST_F(MeshUriTest, MalformedUrisAreErrors) {
  const ResourceSearchPaths s;
  EXPECT_EQ(resolve_resource_uri("package://arm", s).error().message,
            "mesh 'package://arm' is not a package URI of the form package://PKG/PATH");
  EXPECT_EQ(resolve_resource_uri("file://rel/x.stl", s).error().message,
            "mesh 'file://rel/x.stl' is not an absolute file:// URI (file:///PATH)");
  EXPECT_EQ(resolve_resource_uri("http://example.org/x.stl", s).error().message,
            "mesh 'http://example.org/x.stl' has the unsupported scheme 'http' (use package://, "
            "file:// or a path)");
  EXPECT_EQ(resolve_resource_uri("", s).error().message, "mesh filename is empty");
}

TEST(PackagePathTest, SplitsOnColonsSkippingEmptyEntriesAndReadsTheEnvironment) {
  EXPECT_THAT(split_package_path("/a::/b:"), ElementsAre("/a", "/b"));
  EXPECT_TRUE(split_package_path("").empty());
  ::setenv("ROS_PACKAGE_PATH", "/x:/y", 1);
  EXPECT_THAT(ros_package_path_from_environment(), ElementsAre("/x", "/y"));
  ::unsetenv("ROS_PACKAGE_PATH");
  EXPECT_TRUE(ros_package_path_from_environment().empty());
}

}  // namespace
}  // namespace telear::core
