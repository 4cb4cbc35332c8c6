/// @file
/// The options that choose a scene and look at it, shared by `habuffer
/// render` and `habuffer-view` (one declaration, one rule each): the scene's
/// own options (the catalog's rules, refused on scenes that ignore them), the
/// opaque meshes, the camera (--yaw, --pitch, --fov) and the background.
#pragma once

#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "cli_args.h"
#include "habuffer/camera.h"
#include "habuffer/scene.h"
#include "habuffer/scene_catalog.h"

namespace habuffer::cli {

/// The scene options (scene_catalog.h's rules), with the scenes that take each.
std::vector<OptionSpec> scene_option_specs();
/// X,Y,Z of finite numbers; UsageError naming --`option`.
glm::vec3 parse_point(const char* option, const std::string& text);
/// R,G,B each in [0, 1]; UsageError naming --background.
glm::vec3 parse_background(const std::string& text);
/// Refuses the scene options given for a scene that ignores them (the catalog says which scenes take which).
void refuse_scene_options_that_do_not_apply(const Args& args);
/// The scene options given, by the catalog's rules.
SceneOptions parse_scene_options(const Args& args);
/// Before any file is read or context made: camera values out of range are bad usage.
void check_camera_args(const Args& args);
/// --yaw and --pitch (the scene's own where absent) and --fov.
CameraParams camera_params(const Args& args, const Scene& scene);
/// Makes the meshes at `indices` (text, in file order) opaque; UsageError for a bad or missing index.
void make_opaque(const std::vector<std::string>& indices, Scene& scene);

}  // namespace habuffer::cli
