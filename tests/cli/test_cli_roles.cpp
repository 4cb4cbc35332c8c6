// Every command's file roles, walked from the CLI's command table: an output
// over each of its inputs (directly, through a symbolic link and through a
// hard link) and over each other output is refused before any work, and an
// option whose value names a file cannot go without a role. A new command,
// or a new file option, that forgets its role fails here.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>

#include "cli_args.h"
#include "commands.h"
#include "file_values.h"
#include "habuffer/list_text.h"
#include "view_command.h"

namespace {

namespace fs = std::filesystem;
using habuffer::cli::Args;
using habuffer::cli::CommandSpec;
using habuffer::cli::FileRole;
using habuffer::cli::OptionSpec;
using habuffer::cli::UsageError;

// Every command's declaration: the CLI's table and the viewer's (held to the same rules).
std::vector<std::pair<std::string, const CommandSpec*>> every_spec() {
  std::vector<std::pair<std::string, const CommandSpec*>> specs;
  for (const auto& [name, spec] : habuffer::cli::all_command_specs()) specs.emplace_back(name, spec);
  specs.emplace_back("habuffer-view", &habuffer::view::view_spec());
  return specs;
}

std::string fill(const char* example, const std::string& path) {
  std::string s = example;
  return s.replace(s.find("{}"), 2, path);
}

// The message of the UsageError that Args(argv, spec) throws; "" when none.
std::string refusal(const std::vector<std::string>& argv, const CommandSpec& spec) {
  try {
    const Args checked(argv, spec);
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

class CliFileRoles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("habuffer_roles_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    victim_ = (dir_ / "victim.obj").string();
    std::ofstream(victim_) << "v 0 0 0\n";
    fs::create_symlink(victim_, dir_ / "link.obj");
    fs::create_hard_link(victim_, dir_ / "hard.obj");
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string contents() const {
    std::ifstream in(victim_);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  fs::path dir_;
  std::string victim_;
};

TEST_F(CliFileRoles, EveryCommandRefusesAnOutputOverEachOfItsInputsThroughLinksAndHardLinks) {
  int pairs = 0;
  for (const auto& [name, spec] : every_spec())
    for (const OptionSpec& in : spec->options)
      for (const OptionSpec& out : spec->options) {
        if (in.files.role != FileRole::Input || out.files.role != FileRole::Output) continue;
        for (const std::string& alias : {victim_, (dir_ / "link.obj").string(), (dir_ / "hard.obj").string()}) {
          const std::string why = refusal({"--" + in.name, fill(in.files.example, victim_), "--" + out.name,
                                           fill(out.files.example, alias)},
                                          *spec);
          EXPECT_NE(why.find("is the same file as --" + in.name), std::string::npos)
              << "habuffer " << name << " --" << in.name << " --" << out.name << " " << alias << ": '" << why << "'";
          ++pairs;
        }
      }
  EXPECT_GE(pairs, 3 * 40);  // every command that reads and writes files has at least one pair
  EXPECT_EQ(contents(), "v 0 0 0\n");
}

TEST_F(CliFileRoles, EveryCommandRefusesTwoOutputsOfOneFile) {
  int pairs = 0;
  for (const auto& [name, spec] : every_spec())
    for (std::size_t i = 0; i < spec->options.size(); ++i)
      for (std::size_t j = i + 1; j < spec->options.size(); ++j) {
        const OptionSpec &a = spec->options[i], &b = spec->options[j];
        if (a.files.role != FileRole::Output || b.files.role != FileRole::Output) continue;
        const std::string why = refusal(
            {"--" + a.name, fill(a.files.example, victim_), "--" + b.name, fill(b.files.example, victim_)}, *spec);
        EXPECT_NE(why.find("(two outputs)"), std::string::npos)
            << "habuffer " << name << " --" << a.name << " --" << b.name << ": '" << why << "'";
        ++pairs;
      }
  EXPECT_GE(pairs, 15);
}

TEST_F(CliFileRoles, AnOutputSetRefusesAnInputOrOutputInsideItsFolderAndAFolderOfOtherFiles) {
  int sets = 0;
  const std::string folder = (dir_ / "set").string();
  fs::create_directories(folder);
  const std::string inside = folder + "/victim.obj";
  std::ofstream(inside) << "v 0 0 0\n";
  for (const auto& [name, spec] : every_spec())
    for (const OptionSpec& set : spec->options) {
      if (set.files.role != FileRole::OutputSet) continue;
      ++sets;
      EXPECT_NE(refusal({"--" + set.name, folder}, *spec).find("which is not one of its"), std::string::npos) << name;
      for (const OptionSpec& other : spec->options) {
        if (other.files.role != FileRole::Input && other.files.role != FileRole::Output) continue;
        const std::string why =
            refusal({"--" + set.name, folder, "--" + other.name, fill(other.files.example, inside)}, *spec);
        EXPECT_FALSE(why.empty()) << "habuffer " << name << " --" << set.name << " --" << other.name;
      }
    }
  EXPECT_GE(sets, 1);
  EXPECT_TRUE(fs::exists(inside));
}

// The value naming `path` for option `o`: a list's item escaped (habuffer/list_text.h).
std::string value_naming(const OptionSpec& o, const std::string& path) {
  const bool list = o.value.find(',') != std::string::npos;
  return fill(o.files.example, list ? habuffer::escape_list_item(path, ',') : path);
}

TEST_F(CliFileRoles, AFileNameWithCommasIsOneFileToEveryOptionThatNamesIt) {
  // voxelize --mesh 'a,b.obj' --out 'a,b.obj' once split the input at the
  // comma and replaced the mesh (issue 46).
  const std::string comma = (dir_ / "a,b.obj").string();
  std::ofstream(comma) << "v 0 0 0\n";
  int pairs = 0;
  for (const auto& [name, spec] : every_spec())
    for (const OptionSpec& in : spec->options)
      for (const OptionSpec& out : spec->options) {
        if (in.files.role != FileRole::Input || out.files.role != FileRole::Output) continue;
        const std::string why = refusal({"--" + in.name, value_naming(in, comma), "--" + out.name, value_naming(out, comma)}, *spec);
        EXPECT_NE(why.find("is the same file as --" + in.name), std::string::npos)
            << name << " --" << in.name << " --" << out.name << ": '" << why << "'";
        ++pairs;
      }
  EXPECT_GE(pairs, 40);
  std::ifstream back(comma);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(back), {}), "v 0 0 0\n");
}

TEST_F(CliFileRoles, ACatalogSceneNameIsItsModelFileToEveryOptionThatTakesIt) {
  // With HABUFFER_ASSIMP_MODELS=models, "render --scene spider --stats
  // models/OBJ/spider.obj" once wrote JSON over the model (issue 46).
  const fs::path models = dir_ / "models";
  fs::create_directories(models / "OBJ");
  const std::string model = (models / "OBJ" / "spider.obj").string();
  std::ofstream(model) << "v 0 0 0\n";
  fs::create_symlink(model, dir_ / "link-to-model");
  const char* old = std::getenv("HABUFFER_ASSIMP_MODELS");
  const std::string saved = old != nullptr ? old : "";
  ::setenv("HABUFFER_ASSIMP_MODELS", models.c_str(), 1);
  const std::set<std::vector<std::string> (*)(const std::string&)> scene_readers{
      habuffer::cli::scene_file, habuffer::cli::mesh_file, habuffer::cli::mesh_files, habuffer::cli::scene_word_file,
      habuffer::cli::scene_word_files};
  int pairs = 0;
  std::set<std::string> commands;
  for (const auto& [name, spec] : every_spec())
    for (const OptionSpec& in : spec->options)
      for (const OptionSpec& out : spec->options) {
        if (in.files.role != FileRole::Input || out.files.role != FileRole::Output) continue;
        if (scene_readers.count(in.files.paths) == 0) continue;
        for (const std::string& alias : {model, (dir_ / "link-to-model").string()}) {
          const std::string why = refusal({"--" + in.name, fill(in.files.example, "spider"), "--" + out.name,
                                           fill(out.files.example, alias)}, *spec);
          EXPECT_NE(why.find("is the same file as --" + in.name), std::string::npos)
              << name << " --" << in.name << " spider --" << out.name << " " << alias << ": '" << why << "'";
          ++pairs;
        }
        commands.insert(name.substr(0, name.find(' ')));
      }
  if (old != nullptr) ::setenv("HABUFFER_ASSIMP_MODELS", saved.c_str(), 1);
  else ::unsetenv("HABUFFER_ASSIMP_MODELS");
  // render, voxelize, plan, sweep, bench, figure and the viewer take scene names.
  for (const char* c : {"render", "voxelize", "plan", "sweep", "bench", "figure", "habuffer-view"})
    EXPECT_EQ(commands.count(c), 1u) << c;
  std::ifstream back(model);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(back), {}), "v 0 0 0\n");
}

TEST(CliOptionRoles, EveryOptionWhoseValueNamesAFileDeclaresARole) {
  // Value shapes that name files (FILE, IMAGE, DIR, GRID, TABLE, CSV, a .csv or .json name, NAME=SPEC solids).
  const auto names_a_file = [](const std::string& shape) {
    for (const char* word : {"FILE", "IMAGE", "DIR", "GRID", "TABLE", "CSV", "MESH", ".csv", ".json", "NAME=SPEC"})
      if (shape.find(word) != std::string::npos) return true;
    return false;
  };
  int declared = 0;
  for (const auto& [name, spec] : every_spec())
    for (const OptionSpec& o : spec->options) {
      if (o.files.role != FileRole::None) ++declared;
      if (names_a_file(o.value)) {
        EXPECT_NE(o.files.role, FileRole::None) << "habuffer " << name << " --" << o.name << " " << o.value;
      }
    }
  EXPECT_GE(declared, 50);
}

TEST(CliOptionRoles, EveryRunnableCommandHasItsDeclarationsInTheTable) {
  std::set<std::string> declared;
  for (const auto& [name, spec] : habuffer::cli::all_command_specs()) declared.insert(name.substr(0, name.find(' ')));
  for (const auto& [name, run] : habuffer::cli::command_runners()) EXPECT_EQ(declared.count(name), 1u) << name;
}

}  // namespace
