// Scenes and the camera of `habuffer render`, without GL.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>

#include "habuffer/camera.h"
#include "habuffer/scene_catalog.h"

namespace habuffer {
namespace {

TEST(Scene, NamedMeshesLoadWithTrianglesAndColours) {
  for (const char* name : {"engine", "wuson", "spider"}) {
    SCOPED_TRACE(name);
    const Scene s = make_scene(name, {});
    EXPECT_GT(s.triangle_count(), 1000u);
    EXPECT_FALSE(s.bounds().empty());
    for (const Mesh& m : s.meshes) {
      EXPECT_EQ(m.indices.size() % 3, 0u);
      for (std::uint32_t i : m.indices) ASSERT_LT(i, m.positions.size());
      EXPECT_FLOAT_EQ(m.opacity, 0.5f);
    }
  }
}

TEST(Scene, ProceduralScenesFollowTheirParameters) {
  SceneOptions o;
  o.count = 40;
  o.opacity = 0.25f;
  const Scene hair = make_scene("hairball", o);
  EXPECT_GT(hair.triangle_count(), 40u * 24u * 4u);
  EXPECT_LE(hair.radius_around(glm::vec3(0.0f)), 1.0f + 0.01f);  // tubes stay in the unit ball
  o.spread = 0.0f;
  const Scene stacked = make_scene("quads", o);
  ASSERT_EQ(stacked.meshes.size(), 40u);
  for (const Mesh& m : stacked.meshes) {  // spread 0: every quad exactly over the centre
    EXPECT_FLOAT_EQ(m.positions[0].x, -0.25f);
    EXPECT_FLOAT_EQ(m.positions[2].y, 0.25f);
  }
  o.order = PlaneOrder::FrontToBack;
  const Scene front = make_scene("planes", o);
  o.order = PlaneOrder::BackToFront;
  const Scene back = make_scene("planes", o);
  ASSERT_EQ(front.meshes.size(), 40u);
  EXPECT_GT(front.meshes.front().positions[0].z, front.meshes.back().positions[0].z);  // nearest first
  EXPECT_EQ(front.meshes.front().positions, back.meshes.back().positions);
}

TEST(Scene, ErrorsNameTheSceneOrFile) {
  const auto message = [](const std::string& what, const SceneOptions& o = {}) {
    try {
      (void)make_scene(what, o);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("teapotx").find("unknown scene 'teapotx'"), std::string::npos);
  const std::string bad = testing::TempDir() + "/garbage.obj";
  std::ofstream(bad) << "this is not a mesh\n";
  EXPECT_NE(message(bad).find(bad), std::string::npos);
  SceneOptions transparent_zero;
  transparent_zero.opacity = 0.0f;
  EXPECT_NE(message("quads", transparent_zero).find("opacity 0 is not in (0, 1]"), std::string::npos);
  SceneOptions too_many;
  too_many.count = kMaxSceneCount + 1;
  EXPECT_NE(message("planes", too_many).find("count 1048577 is above 1048576"), std::string::npos);
}

// Depth t is linear eye depth between near and far (the paper's mapping):
// the bounding sphere lies inside [0, 1].
// assimp trusts a PLY header: a truncated ASCII file aborted the process
// inside its assertions, a short binary one claiming 4e9 vertices ran out of
// memory. Both are refused before assimp reads them, naming the element.
TEST(Scene, PlyFilesThatCannotHoldWhatTheirHeaderDeclaresAreRefusedBeforeImport) {
  const auto message = [](const std::string& name, const std::string& text) {
    const std::string path = testing::TempDir() + "/" + name;
    std::ofstream(path, std::ios::binary) << text;
    try {
      (void)make_scene(path, {});
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string ascii_head =
      "ply\nformat ascii 1.0\nelement vertex 1000\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string truncated = message("truncated.ply", ascii_head + "0 0 0\n1 0 0\n0 1 0\n");
  EXPECT_NE(truncated.find("declares 1001 rows but the file has 3 lines"), std::string::npos) << truncated;
  EXPECT_NE(truncated.find("truncated.ply"), std::string::npos);
  const std::string huge = message("huge.ply",
      "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n");
  EXPECT_NE(huge.find("'vertex' claims 4000000000 rows of at least 12 bytes, but the file holds 0 bytes"),
            std::string::npos) << huge;
  EXPECT_NE(message("beyond.ply", "ply\nformat ascii 1.0\nelement vertex 99999999999\nend_header\n").find("more than 2^32"),
            std::string::npos);
  EXPECT_NE(message("count.ply", "ply\nformat ascii 1.0\nelement vertex -3\nend_header\n").find("count '-3'"),
            std::string::npos);
  EXPECT_NE(message("noend.ply", "ply\nformat ascii 1.0\nelement vertex 3\n").find("no end_header"), std::string::npos);
  EXPECT_NE(message("type.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty quad x\nend_header\n")
                .find("unknown type"),
            std::string::npos);
  // A header line without end (binary data after "ply"): refused at 64 KiB, never read whole (issue 34).
  const std::string long_line = message("long.ply", "ply\n" + std::string(100000, '\x01'));
  EXPECT_NE(long_line.find("PLY header line longer than 65536 bytes"), std::string::npos) << long_line;
  // Exactly what the header declares: read (one triangle).
  std::string ok = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                   "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_EQ(message("whole.ply", ok), "no error");
}

TEST(Camera, FramesTheSceneWithLinearDepthInZeroOne) {
  const Scene s = make_scene("hairball", {});
  for (float yaw : {0.0f, 90.0f, 217.0f}) {
    const Camera c = frame_scene(s, {yaw, 20.0f, 45.0f}, {640, 480});
    for (const Mesh& m : s.meshes)
      for (std::size_t i = 0; i < m.positions.size(); i += 97) {
        const glm::vec4 eye = c.view * glm::vec4(m.positions[i], 1.0f);
        const float t = c.depth(eye.z);
        ASSERT_GE(t, 0.0f);
        ASSERT_LE(t, 1.0f);
        const glm::vec4 clip = c.projection * eye;
        ASSERT_LE(std::abs(clip.x / clip.w), 1.0f);  // in view horizontally and vertically
        ASSERT_LE(std::abs(clip.y / clip.w), 1.0f);
      }
  }
  EXPECT_THROW(frame_scene(s, {0.0f, 95.0f, 45.0f}, {64, 64}), SceneError);
  EXPECT_THROW(frame_scene(s, {0.0f, 0.0f, 0.0f}, {64, 64}), SceneError);
}

}  // namespace
}  // namespace habuffer
