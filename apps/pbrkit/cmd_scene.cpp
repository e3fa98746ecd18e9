// pbrkit scene: the built-in scenes. `pbrkit scene list`, `pbrkit scene write NAME OUT.glb`
// (so any glTF tool can render exactly the scene our renderers use).
#include <cstdio>
#include <memory>

#include "commands.h"
#include "pbrkit/scene/load.h"

namespace pbrkit::cli {

namespace {

struct SceneWriteOptions {
  std::string name;
  std::string output;
  bool flatten_instances = false;
};

}  // namespace

void register_scene_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("scene", "Built-in scenes: list them or write one as .glb");
  cmd->require_subcommand(1);

  CLI::App* list = cmd->add_subcommand("list", "List the built-in scenes");
  list->callback([] {
    for (const std::string& name : builtin_scene_names()) std::printf("%s\n", name.c_str());
  });

  auto opt = std::make_shared<SceneWriteOptions>();
  CLI::App* write = cmd->add_subcommand("write", "Write a built-in scene as binary glTF");
  write->add_option("name", opt->name, "the built-in scene: " + builtin_scene_list())->required();
  write->add_option("output", opt->output, "Output .glb path")->required();
  write->add_flag("--flatten-instances", opt->flatten_instances,
                  "write each placement of a repeated mesh as a node of its own (sharing the "
                  "mesh) instead of EXT_mesh_gpu_instancing, which Blender 3.4 and some other "
                  "importers refuse");
  write->callback([opt] {
    const Scene scene = builtin_scene(opt->name);
    GltfWriteOptions options;
    options.flatten_instances = opt->flatten_instances;
    write_glb(scene, opt->output, options);
    std::printf("wrote %s (%zu triangles)\n", opt->output.c_str(), scene.triangle_count());
  });
}

}  // namespace pbrkit::cli
