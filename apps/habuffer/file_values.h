/// @file
/// The files named inside option values that are not simply one path, for
/// the options' declared roles (FileUse::paths, cli_args.h): each returns the
/// files a value names and none for built-in names, and never throws (a value
/// it cannot read is the command's own parser's to refuse).
#pragma once

#include <string>
#include <vector>

namespace habuffer::cli {

/// A comma-separated list of files ("F.json,F.csv"; "a\,b.csv" is one file,
/// habuffer/list_text.h).
std::vector<std::string> listed_files(const std::string& value);
/// One scene, the value whole (commas and all): a catalog mesh names the
/// model file it resolves to, a procedural scene none, anything else is a
/// mesh file (habuffer::scene_input_file).
std::vector<std::string> scene_file(const std::string& value);
/// One mesh, the value whole: sphere, torus and box name no file; otherwise
/// as scene_file.
std::vector<std::string> mesh_file(const std::string& value);
/// One harness scene word, the value whole ("my,mesh.obj:opacity=0.5"): its
/// mesh or fragment file, or a catalog name's model file.
std::vector<std::string> scene_word_file(const std::string& value);
/// Harness scene words, comma-separated ("engine,my.obj:opacity=0.5,frags.csv"):
/// each word's mesh or fragment file.
std::vector<std::string> scene_word_files(const std::string& value);
/// Meshes, comma-separated, each as mesh_file.
std::vector<std::string> mesh_files(const std::string& value);
/// csg's solids, "NAME=SPEC;...": each SPEC that is not a primitive (box:, sphere:, cylinder:, torus:).
std::vector<std::string> solid_files(const std::string& value);
/// --offsets: random and farthest name no file.
std::vector<std::string> offsets_file(const std::string& value);
/// --heatmap KIND:IMAGE[,...]: the images.
std::vector<std::string> heatmap_files(const std::string& value);

}  // namespace habuffer::cli
