// pbrkit brdf: the BRDF's building blocks in LearnOpenGL's form (de Vries, "PBR: Theory")
// as CSV tables and gnuplot PNGs (data from
// brdf_plots.h, i.e. from the very functions the renderers call).
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "brdf_plots.h"
#include "commands.h"
#include "pbrkit/core/color.h"
#include "pbrkit/util/atomic_file.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"

extern char** environ;

namespace pbrkit::cli {
namespace {

namespace fs = std::filesystem;

constexpr const char* kHelp =
    "Writes <dir>/brdf_{D,G1,fresnel,albedo}.{csv,png} (the PNGs need gnuplot):\n"
    "  brdf_D        GGX D vs n.h for alpha 0.1..1 (log y). D is a density over solid angle\n"
    "                (1/sr), so it exceeds 1 for small alpha (peak 1/(pi alpha^2) = 31.8 at\n"
    "                alpha 0.1); what integrates to 1 over the hemisphere is D(h) (n.h).\n"
    "  brdf_G1       G1 vs n.v: Schlick-GGX with k_direct = (r+1)^2/8 and k_IBL = alpha/2,\n"
    "                and Smith's exact G1 for GGX, at roughness 0.25, 0.5, 1. All fall to 0\n"
    "                at grazing angles; k_direct masks more than the exact G1 at low r.\n"
    "  brdf_fresnel  Fresnel-Schlick (luminance) vs v.h for LearnOpenGL's F0 table (water ..\n"
    "                silver), coloured by F0. Every curve rises to 1 at v.h = 0.\n"
    "  brdf_albedo   directional albedo E(mu) of a white metal (F0 = 1), integrated over\n"
    "                the hemisphere from the BRDF itself: single scattering loses energy at\n"
    "                high roughness; Kulla-Conty compensation brings it back to 1.";

// Runs gnuplot on a script file without a shell. Returns false when gnuplot cannot be
// started (not installed); throws when it runs and fails.
bool run_gnuplot(const fs::path& script, const std::string& what) {
  const std::string exe = "gnuplot", arg = script.string();
  std::vector<char*> argv = {const_cast<char*>(exe.c_str()), const_cast<char*>(arg.c_str()),
                             nullptr};
  pid_t pid = 0;
  if (posix_spawnp(&pid, "gnuplot", nullptr, nullptr, argv.data(), environ) != 0) return false;
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) fail("{}: waiting for gnuplot failed", what);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 127) return false;  // exec failed
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    fail("{}: gnuplot failed (exit status {})", what, WIFEXITED(status) ? WEXITSTATUS(status) : -1);
  return true;
}

std::string quoted(const fs::path& p) {
  const std::string s = p.string();
  if (s.find('\'') != std::string::npos || s.find('\n') != std::string::npos)
    fail("{}: output paths for gnuplot may not contain quotes or newlines", s);
  return "'" + s + "'";
}

std::string hex_colour(glm::vec3 linear) {
  const glm::vec3 c = srgb_encode(linear);
  return fmt::format("#{:02x}{:02x}{:02x}", int(std::lround(c.r * 255)),
                     int(std::lround(c.g * 255)), int(std::lround(c.b * 255)));
}

// One plot: the gnuplot commands after "set output"; `plot_body` uses DATA for the CSV.
struct Plot {
  std::string name;  // brdf_D
  PlotTable table;
  std::string body;  // gnuplot commands; the token DATA is replaced by the CSV path
};

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + to.size()))
    s.replace(p, from.size(), to);
  return s;
}

std::vector<Plot> make_plots() {
  std::vector<Plot> plots;
  const std::string common =
      "set datafile separator ','\n"
      "set grid lc rgb '#dddddd'\n"
      "set key outside right top box\n";
  {
    Plot p{"brdf_D", ndf_plot_table(), ""};
    p.body = common +
             "set title \"GGX NDF D(h) vs n.h.  D is a density over solid angle (1/sr): it can "
             "exceed 1,\\npeak 1/({/Symbol p} {/Symbol a}^2) = 31.8 at {/Symbol a} = 0.1.  "
             "What integrates to 1 over the hemisphere is D(h)(n.h).\"\n"
             "set xlabel 'n.h'\nset ylabel 'D  [1/sr]'\nset logscale y\n"
             "set yrange [1e-3:100]\nset xrange [0:1]\n"
             "plot for [i=2:6] DATA using 1:i with lines lw 2 title columnhead(i) noenhanced\n";
    plots.push_back(std::move(p));
  }
  {
    Plot p{"brdf_G1", g1_plot_table(), ""};
    p.body = common +
             "set title \"Masking G1 vs n.v: Schlick-GGX with k_{direct} = (r+1)^2/8 (dashed), "
             "k_{IBL} = {/Symbol a}/2 (dotted),\\nand Smith's exact G1 for GGX (solid), "
             "{/Symbol a} = r^2.  All fall to 0 at grazing angles; at r = 1 all three are 2 n.v / "
             "(1 + n.v).\"\n"
             "set xlabel 'n.v'\nset ylabel 'G1'\nset xrange [0:1]\nset yrange [0:1.05]\n"
             "colours = \"#1b9e77 #d95f02 #7570b3\"\n"
             "plot for [j=0:2] DATA using 1:(column(2+3*j)) with lines lw 2 dt 2 "
             "lc rgb word(colours, j+1) title columnhead(2+3*j) noenhanced, \\\n"
             "     for [j=0:2] DATA using 1:(column(3+3*j)) with lines lw 2 dt 3 "
             "lc rgb word(colours, j+1) title columnhead(3+3*j) noenhanced, \\\n"
             "     for [j=0:2] DATA using 1:(column(4+3*j)) with lines lw 2 dt 1 "
             "lc rgb word(colours, j+1) title columnhead(4+3*j) noenhanced\n";
    plots.push_back(std::move(p));
  }
  {
    Plot p{"brdf_fresnel", fresnel_plot_table(), ""};
    std::string colours;
    for (const auto& m : fresnel_materials())
      colours += (colours.empty() ? "" : " ") + hex_colour(m.F0);
    p.body =
        common +
        "set title \"Fresnel-Schlick F = F0 + (1 - F0)(1 - v.h)^5 (luminance) for LearnOpenGL's "
        "F0 table,\\ncurves coloured by F0 (sRGB).  Every curve rises to 1 at v.h = 0 "
        "(grazing).\"\nset key opaque\n"
        "set object 1 rectangle from graph 0,0 to graph 1,1 behind fc rgb '#f4f4f4' "
        "fs solid noborder\n"
        "set xlabel 'v.h'\nset ylabel 'F (luminance)'\nset xrange [0:1]\n"
        "set yrange [0:1.02]\n"
        "colours = \"" +
        colours +
        "\"\n"
        "plot for [i=2:11] DATA using 1:i with lines lw 4.5 lc rgb '#202020' notitle, \\\n"
        "     for [i=2:11] DATA using 1:i with lines lw 3.5 lc rgb word(colours, i-1) "
        "title columnhead(i) noenhanced\n";
    plots.push_back(std::move(p));
  }
  {
    Plot p{"brdf_albedo", albedo_plot_table(), ""};
    p.body = common +
             "set title \"Directional albedo E({/Symbol m}) of a white metal (F0 = 1), "
             "integrated from the BRDF: single scattering (dashed)\\nloses energy as roughness "
             "grows; with Kulla-Conty multiple-scattering compensation (solid) it is 1.  "
             "Points: EnergyTable.\"\n"
             "set xlabel '{/Symbol m} = n.v'\nset ylabel 'E({/Symbol m})'\nset xrange [0:1]\n"
             "set yrange [0:1.05]\n"
             "colours = \"#440154 #3b528b #21918c #5ec962 #c8a800\"\n"
             "plot for [j=0:4] DATA using 1:(column(3+3*j)) with lines lw 2 dt 1 "
             "lc rgb word(colours, j+1) title columnhead(3+3*j) noenhanced, \\\n"
             "     for [j=0:4] DATA using 1:(column(2+3*j)) with lines lw 2 dt 2 "
             "lc rgb word(colours, j+1) title columnhead(2+3*j) noenhanced, \\\n"
             "     for [j=0:4] DATA using 1:(column(4+3*j)) every 4 with points pt 7 ps 0.6 "
             "lc rgb word(colours, j+1) notitle\n";
    plots.push_back(std::move(p));
  }
  return plots;
}

void run_brdf(const std::string& out_dir) {
  const fs::path dir(out_dir);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir)) fail("{}: cannot create the output directory", out_dir);
  const std::vector<Plot> plots = make_plots();
  for (const Plot& p : plots) {
    const fs::path csv = dir / (p.name + ".csv");
    write_bytes_atomically(csv, p.table.to_csv());
    std::printf("wrote %s\n", csv.string().c_str());
  }
  bool have_gnuplot = true;
  for (const Plot& p : plots) {
    const fs::path csv = fs::absolute(dir / (p.name + ".csv"));
    const fs::path png = dir / (p.name + ".png");
    const fs::path script = dir / fmt::format(".{}.{}.gp", p.name, ::getpid());
    write_file_atomically(png, [&](const fs::path& temp) {
      const std::string text =
          "set terminal pngcairo size 1100,650 enhanced font 'DejaVu Sans,11'\n"
          "set output " +
          quoted(fs::absolute(temp)) + "\n" + replace_all(p.body, "DATA", quoted(csv)) +
          "unset output\n";
      write_bytes_atomically(script, text);
      bool ran = false;
      try {
        ran = run_gnuplot(script, png.string());
      } catch (...) {
        fs::remove(script, ec);
        throw;
      }
      fs::remove(script, ec);
      if (!ran) {
        have_gnuplot = false;
        throw ExitRequest{0};  // abandons this PNG; reported below
      }
      if (!fs::exists(temp) || fs::file_size(temp) == 0)
        fail("{}: gnuplot produced no image", png.string());
    });
    std::printf("wrote %s\n", png.string().c_str());
  }
}

}  // namespace

void register_brdf_command(CLI::App& app) {
  auto out = std::make_shared<std::string>("out");
  auto* cmd = app.add_subcommand(
      "brdf",
      "Plot the BRDF's building blocks (GGX D, G1, Fresnel, albedo) as CSV + PNG (gnuplot).");
  cmd->add_option("-o,--output", *out, "output directory (created if missing)")
      ->capture_default_str();
  cmd->footer(kHelp);
  cmd->callback([out] {
    try {
      run_brdf(*out);
    } catch (const ExitRequest&) {
      fail(
          "the CSV tables are written to {}, but the PNG plots need gnuplot, which was not "
          "found on PATH (Debian: apt-get install gnuplot-nox)",
          *out);
    }
  });
}

}  // namespace pbrkit::cli
