#include "scene_options.h"

#include <cmath>
#include <sstream>

#include "habuffer/printable.h"

namespace habuffer::cli {

std::vector<OptionSpec> scene_option_specs() {
  const std::pair<const char*, const char*> shapes[] = {
      {"count", "N"}, {"scene-seed", "N"}, {"opacity", "A"}, {"spread", "S"}, {"order", "front|back"}};
  std::vector<OptionSpec> specs;
  for (const SceneOptionRule& r : scene_option_rules())
    for (const auto& [flag, shape] : shapes)
      if (std::string(r.flag) == flag)
        specs.push_back(
            {flag, shape, "", std::string("the scene's ") + r.key + " (" + scenes_taking_text(r.key) + ")"});
  return specs;
}

glm::vec3 parse_point(const char* option, const std::string& text) {
  glm::vec3 v(0.0f);
  std::istringstream in(text);
  char comma = 0;
  if (!(in >> v.x >> comma >> v.y >> comma >> v.z) || !in.eof() || !std::isfinite(v.x) || !std::isfinite(v.y) ||
      !std::isfinite(v.z))
    throw UsageError(std::string("option --") + option + ": '" + text + "' is not X,Y,Z of finite numbers");
  return v;
}

glm::vec3 parse_background(const std::string& text) {
  glm::vec3 c(1.0f);
  try {
    c = parse_point("background", text);
  } catch (const UsageError&) {
    c = glm::vec3(-1.0f);  // refused below with the option's own wording
  }
  if (glm::any(glm::lessThan(c, glm::vec3(0.0f))) || glm::any(glm::greaterThan(c, glm::vec3(1.0f))))
    throw UsageError("option --background: '" + text + "' is not R,G,B with each in [0, 1]");
  return c;
}

void refuse_scene_options_that_do_not_apply(const Args& args) {
  const std::string scene = args.has("scene") ? args.required("scene") : "";
  for (const SceneOptionRule& r : scene_option_rules())
    if (!scene.empty() && !r.takers.empty())
      args.refuse_unless(scene_takes(scene, r.key), {r.flag},
                         "on scene " + excerpt(scene) + " (" + scenes_taking_text(r.key) + ")");
}

SceneOptions parse_scene_options(const Args& args) {
  SceneOptions o;
  for (const SceneOptionRule& r : scene_option_rules())
    if (args.has(r.flag)) usage_errors(r.flag, [&] { set_scene_option(o, r.key, args.str(r.flag, "")); });
  return o;
}

void check_camera_args(const Args& args) {
  if (!std::isfinite(static_cast<float>(args.real("yaw", 0.0))))
    throw UsageError("option --yaw: must be a finite angle in degrees");
  if (!(std::abs(args.real("pitch", 0.0)) <= kMaxPitch)) throw UsageError("option --pitch: must be in [-90, 90] degrees");
  const double fov = args.real("fov");
  if (!(fov > kMinFov && fov < kMaxFov)) throw UsageError("option --fov: must be in (1, 179) degrees");
}

void make_opaque(const std::vector<std::string>& indices, Scene& scene) {
  for (const std::string& item : indices) {
    std::size_t used = 0;
    unsigned long index = 0;
    try {
      index = std::stoul(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size() || item.empty())
      throw UsageError("option --opaque-meshes: " + excerpt(item) + " is not a mesh index");
    if (index >= scene.meshes.size())
      throw UsageError("option --opaque-meshes: mesh " + item + " does not exist (the scene has " +
                       std::to_string(scene.meshes.size()) + " meshes)");
    scene.meshes[index].opacity = 1.0f;
  }
}
CameraParams camera_params(const Args& args, const Scene& scene) {
  CameraParams c;
  c.yaw = static_cast<float>(args.real("yaw", scene.default_yaw));
  c.pitch = static_cast<float>(args.real("pitch", scene.default_pitch));
  c.fov = static_cast<float>(args.real("fov"));
  return c;
}

}  // namespace habuffer::cli
