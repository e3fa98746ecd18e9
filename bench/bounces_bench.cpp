// The table of the README's "Bounces": every built-in scene's mean luminance at 8, 12, 16
// and 24 bounces against 64, and 64 against 128 (the reference's convergence), 128 pixels
// wide, 64 spp, the same seed (tests/support/bounce_deficit.h: the difference holds only
// the deeper paths). Several CPU minutes (5 on two shared cores). Prints Markdown rows.
#include <cstdio>
#include <string>

#include "pbrkit/scene/load.h"
#include "support/bounce_deficit.h"

int main() {
  using namespace pbrkit;
  using namespace pbrkit::test;
  std::printf(
      "deficit of the image's mean luminance against %d bounces, +- its standard error; in "
      "brackets the worst 16x16 block's\n",
      kConverged);
  for (const std::string& name : builtin_scene_names()) {
    const Scene scene = builtin_scene(name);
    const Luminance deep = render_luminance(scene, 128, 64, kConverged);
    std::string row;
    for (int shallow : {8, 12, 16, 24}) {
      const Deficit d = deficit(render_luminance(scene, 128, 64, shallow), deep);
      char cell[64];
      std::snprintf(cell, sizeof cell, " | %.2f%% +- %.2f%% (%.1f%%)", 100.0 * d.deficit,
                    100.0 * d.std_error, 100.0 * d.worst_block);
      row += cell;
    }
    const Deficit c = deficit(deep, render_luminance(scene, 128, 64, 2 * kConverged));
    std::printf("| %s%s | %.2f%% +- %.2f%% (%.1f%%) |\n", name.c_str(), row.c_str(),
                100.0 * c.deficit, 100.0 * c.std_error, 100.0 * c.worst_block);
    std::fflush(stdout);
  }
  return 0;
}
