/// impactfe command-line interface: run a deck, query a results file, export, report, mesh a CAD
/// file, Houbolt spectrum. Each subcommand's options are declared in a function of their own;
/// main parses and dispatches.
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "app/exit_status.h"
#include "app/run_command.h"
#include "app/version.h"
#include "core/errors.h"
#include "deck/cad_meshing.h"
#include "deck/cdb_writer.h"
#include "deck/command_reference.h"
#include "results/post_csv.h"
#include "results/report.h"
#include "results/results_file.h"
#include "results/vtk_export.h"
#include "time/houbolt_spectrum.h"

namespace fs = std::filesystem;
using namespace impactfe;
using namespace impactfe::app;

namespace {

/// glibc raises its mmap threshold to the size of every mapped block freed (up to 32 MB); from
/// then on, blocks of that size come from the heap, and a freed one below live data is not given
/// back. A run frees model-size arrays on its way to the factorization (pattern, products,
/// CHOLMOD's copies), so the peak resident memory grew by those holes: 0.73 GB for the shell
/// dome 160, 0.68 GB with a fixed threshold. Setting the threshold also stops its raising:
/// blocks of 1 MB and more are mapped on their own and returned when freed.
void map_large_blocks_on_their_own() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
#endif
}

CLI::App* add_run(CLI::App& app, RunArgs& run) {
  CLI::App* cmd = app.add_subcommand("run", "run an APDL deck (ANSYS 4.2 or modern)");
  cmd->add_option("deck", run.deck, "input deck")->required();
  cmd->add_option("-o,--output", run.out_dir, "working directory for results (default .)");
  cmd->add_option("-j,--jobname", run.jobname, "job name (default: deck file stem)");
  cmd->add_option("--memory", run.memory,
                  "the most memory the run may use (e.g. 4G, 512M; default: what the machine "
                  "has available)");
  cmd->add_option(
      "--threads", run.threads,
      "threads for element loops, the solves and products of large models and results "
      "compression (default: all cores where the work pays for them; BLAS runs on one thread)");
  cmd->add_option("--results-thread", run.results_thread,
                  "write the results file on a thread of its own: auto (default: when the run "
                  "may use two threads and a core is idle at the start), on or off")
      ->check(CLI::IsMember({"auto", "on", "off"}));
  cmd->add_flag("--skip-unknown", run.skip_unknown, "warn and skip unknown commands");
  cmd->add_option("--dialect", run.dialect, "4x|modern|auto")
      ->check(CLI::IsMember({"4x", "modern", "auto"}));
  cmd->add_option("--results", run.results,
                  "results file read by the POST1/POST26/*GET commands of a deck that "
                  "solves nothing");
  cmd->add_option("--se", run.superelement, "superelement file for MATRIX50 elements");
  cmd->add_flag("--continue-on-nonconvergence", run.continue_on_nonconvergence,
                "accept non-converged steps with a warning");
  cmd->add_flag("--accept-energy-error", run.accept_energy_error,
                "go on (with a warning) when a transient creates more energy than the bound "
                "of the energy check");
  cmd->add_flag("--no-condense", run.no_condense,
                "full Newton on all DOFs in a transient, never the condensed linear part");
  cmd->add_option("--solver", run.solver,
                  "sparse direct solver: cholmod (default, one process) or mumps (MPI: "
                  "mpirun -n N impactfe run DECK --solver mumps)")
      ->check(CLI::IsMember({"cholmod", "mumps"}));
  cmd->add_flag("--mumps-ooc", run.mumps_ooc,
                "MUMPS out-of-core: factors on disk (for factors larger than memory)");
  cmd->add_option("--mumps-ooc-dir", run.mumps_ooc_dir,
                  "directory of the out-of-core factor files (default $TMPDIR or /tmp)");
  cmd->add_flag("--mumps-no-refine", run.mumps_no_refine,
                "MUMPS on several ranks: no double-double refinement of the solves (faster; "
                "results then agree to round-off but are not bitwise repeatable)");
  return cmd;
}

struct PostArgs {
  std::string file;
  std::vector<std::string> nsol, esol, gapf, rcforc, part;
  bool freq = false;
  int mode = 0;
};

CLI::App* add_post(CLI::App& app, PostArgs& post) {
  CLI::App* cmd = app.add_subcommand("post", "print time histories / modal results as CSV");
  cmd->add_option("results", post.file, "results file (.h5)")->required();
  cmd->add_option("--nsol", post.nsol, "NODE,LAB (UX..ROTZ, VX..VZ, AX..AZ, FX..MZ)");
  cmd->add_option("--esol", post.esol, "ELEM,ITEM (SAXL, FORC, STAT, ...)");
  cmd->add_option("--gapf", post.gapf, "GP gap-condition number");
  cmd->add_option("--rcforc", post.rcforc,
                  "N,FX|FY|FZ: force on the contact surface of explicit contact N (EDCGEN order)");
  cmd->add_option("--part", post.part,
                  "N,KE|IE|HE: kinetic, internal or hourglass energy of part N (EDPART numbers)");
  cmd->add_flag("--freq", post.freq, "print mode,frequency_hz");
  cmd->add_option("--mode", post.mode, "print the shape of mode N");
  return cmd;
}

int post_command(const PostArgs& post) {
  ResultsReader reader(post.file);
  if (post.freq) {
    if (reader.frequencies().empty())
      throw InputError(fmt::format(
          "'{}' holds no modal results (no modal analysis was run); --freq needs one", post.file));
    std::cout << frequencies_csv(reader);
    return kExitOk;
  }
  if (post.mode > 0) {
    std::cout << mode_shape_csv(reader, post.mode);
    return kExitOk;
  }
  std::vector<PostRequest> requests;
  for (const auto& s : post.nsol) requests.push_back(parse_nsol(s));
  for (const auto& s : post.esol) requests.push_back(parse_esol(s));
  for (const auto& s : post.gapf) requests.push_back(parse_gapf(s));
  for (const auto& s : post.rcforc) requests.push_back(parse_rcforc(s));
  for (const auto& s : post.part) requests.push_back(parse_part_energy(s));
  if (requests.empty()) {
    std::cerr << "error: give --nsol, --esol, --gapf, --rcforc, --part, --freq or --mode\n";
    return kExitInput;
  }
  std::cout << post_csv(reader, requests);
  return kExitOk;
}

struct ExportArgs {
  std::string file, dir = ".", format = "vtu";
};

CLI::App* add_export(CLI::App& app, ExportArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "export",
      "write the results for ParaView: compressed VTU files + a PVD collection (default, any "
      "ParaView or VTK) or one VTKHDF 2.0 file (ParaView 5.12 or later)");
  cmd->add_option("results", args.file, "results file (.h5)")->required();
  cmd->add_option("-o,--output", args.dir, "output directory (default .)");
  cmd->add_option("--format", args.format,
                  "vtu (default: <stem>.pvd + <stem>_NNNNN.vtu, zlib-compressed) | vtkhdf "
                  "(<stem>.vtkhdf, VTKHDF 2.0: its time steps need ParaView 5.12 / VTK 9.3 or "
                  "later)")
      ->check(CLI::IsMember({"vtkhdf", "vtu"}));
  return cmd;
}

int export_command(const ExportArgs& args) {
  ResultsReader reader(args.file);
  fs::create_directories(args.dir);
  const std::string stem = fs::path(args.file).stem().string();
  const bool vtu = args.format == "vtu";
  const ExportSummary s =
      vtu ? export_vtu_series(reader, args.dir, stem)
          : export_vtkhdf(reader, (fs::path(args.dir) / (stem + ".vtkhdf")).string());
  std::cout << fmt::format(
      "export: wrote {}{} ({} time points, {} points, {} cells, {:.2f} MB)\n", s.files.front(),
      s.files.size() > 1 ? fmt::format(" and {} .vtu files", s.files.size() - 1) : "", s.frames,
      s.points, s.cells, static_cast<double>(s.bytes) / 1e6);
  // Older readers (VTK 9.1, ParaView 5.11 and before) know VTKHDF 1.0 only: they warn that
  // version 2.0 is too high and show the first time step alone.
  std::cout << (vtu ? "  open the .pvd in ParaView (File > Open): every time step, any version\n"
                    : "  VTKHDF 2.0: its time steps need ParaView 5.12 or later (VTK 9.3); older "
                      "versions show the first one only (use --format vtu)\n");
  if (!s.skipped_elements.empty())
    std::cout << fmt::format("  {} element(s) not drawn (a node is not in the model), e.g. {}\n",
                             s.skipped_elements.size(), s.skipped_elements.front());
  return kExitOk;
}

struct ReportArgs {
  std::string file, out;
  ReportOptions options;
};

CLI::App* add_report(CLI::App& app, ReportArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "report", "write a self-contained HTML report (summary, plots, energy, gaps, 3-D view)");
  cmd->add_option("results", args.file, "results file (.h5)")->required();
  cmd->add_option("-o,--output", args.out,
                  "HTML file (default: the results file with extension .html)");
  cmd->add_option("--node", args.options.nodes, "node of the time-history figures (repeatable)")
      ->delimiter(',');
  cmd->add_option("--element", args.options.elements, "element of the stress figure (repeatable)")
      ->delimiter(',');
  cmd->add_option("--item", args.options.items,
                  "direction UX|UY|UZ and/or element item SEQV, SAXL, FORC, ... (repeatable)")
      ->delimiter(',');
  cmd->add_option("--max-points", args.options.max_points, "at most this many points per curve")
      ->check(CLI::Range(4, 10000000));
  cmd->add_option("--frames", args.options.max_frames, "at most this many frames in the 3-D view")
      ->check(CLI::Range(2, 1000000));
  return cmd;
}

int report_command(const ReportArgs& args) {
  ResultsReader reader(args.file);
  const std::string out =
      args.out.empty() ? fs::path(args.file).replace_extension(".html").string() : args.out;
  const auto bytes = write_report(reader, args.options, out);
  std::cout << fmt::format("report: wrote {} ({:.2f} MB)\n", out, bytes / 1e6);
  return kExitOk;
}

int spectrum_command(const std::vector<double>& xi) {
  std::vector<double> ratios;
  for (double r = 1e-3; r <= 1e3 * 1.0001; r *= std::pow(10.0, 0.1)) ratios.push_back(r);
  std::cout << houbolt_spectrum_csv(ratios, xi);
  return kExitOk;
}

struct MeshArgs {
  std::string file, out, type = "187";
  double esize = 0.0;
  bool triangles = false;
};

CLI::App* add_mesh(CLI::App& app, MeshArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "mesh",
      "mesh a CAD file (IGES or STEP) with Gmsh and write the nodes and elements as a CDB "
      "archive (the deck IGESIN, ESIZE, VMESH / AMESH, CDWRITE,DB would)");
  cmd->add_option("cad", args.file, "CAD file (.igs, .iges, .stp, .step)")->required();
  cmd->add_option("-o,--output", args.out, "CDB file to write (default <stem>.cdb)");
  cmd->add_option("--type", args.type,
                  "element type: a volume type meshes the volumes (187: SOLID187 10-node "
                  "tetrahedra, default; 185, 186: degenerate bricks), an area type the areas "
                  "(182, 183, 181)");
  cmd->add_option("--esize", args.esize, "element edge length (ESIZE; default: DESIZE's)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--triangles", args.triangles,
                "areas: triangles (MSHAPE,1) instead of quadrilaterals");
  return cmd;
}

int mesh_command(const MeshArgs& args) {
  const fs::path cad = fs::absolute(args.file);
  const Model model = deck::mesh_cad_file({args.file, args.type, args.esize, args.triangles});
  const std::string out = args.out.empty() ? cad.stem().string() + ".cdb" : args.out;
  std::ofstream os(out);
  if (!os) throw std::runtime_error("cannot write " + out);
  deck::write_cdb(model, os);
  std::cout << fmt::format("mesh: {} volumes, {} areas from {}: {} nodes, {} elements -> {}\n",
                           model.solid.volumes.size(), model.solid.areas.size(), args.file,
                           model.nodes.size(), model.elements.size(), out);
  std::cout << deck::mesh_quality_lines(model);
  return kExitOk;
}

struct HelpArgs {
  std::string name;
  bool markdown = false;
};

CLI::App* add_help(CLI::App& app, HelpArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "help", "what impactfe does with a deck command or an element type (MAPDL names)");
  cmd->add_option("name", args.name, "command (NSUBST, /UNITS, *GET) or element type (SOLID185)");
  cmd->add_flag("--markdown", args.markdown,
                "print the whole command and element reference (docs/reference.md)");
  return cmd;
}

/// `help NAME`: the element type of that name, else the command (or its abbreviation); `help`:
/// the list of both; `help --markdown`: the reference page.
int help_command(const HelpArgs& args) {
  if (args.markdown || args.name.empty()) {
    std::cout << (args.markdown ? deck::reference_markdown() : deck::help_index());
    return kExitOk;
  }
  const std::string entry = deck::help_entry(args.name);
  if (entry.empty()) {
    std::cerr << fmt::format(
        "error: '{}' is neither a command nor an element type of impactfe (a deck that uses it "
        "stops there)\n",
        args.name);
    return kExitInput;
  }
  std::cout << entry;
  return kExitOk;
}

/// The usage line: every subcommand the program has, in the order of `impactfe --help`.
std::string usage_line(const CLI::App& app) {
  std::string names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    names += (names.empty() ? "" : "|") + sub->get_name();
  return fmt::format("usage: impactfe {{{}}} ...; impactfe --help, impactfe SUBCOMMAND --help",
                     names);
}

/// A command-line error: CLI11's message, the usage line, exit status 1 (help and --version: 0).
/// A first word that names no subcommand is said as such (CLI11 only says one is required).
int command_line_error(const CLI::App& app, const CLI::ParseError& e, int argc, char** argv) {
  if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) {
    app.exit(e);
    return kExitOk;
  }
  std::string message = e.what();
  const auto named = [&](const CLI::App* sub) { return sub->check_name(argv[1]); };
  if (argc > 1 && argv[1][0] != '-' && app.get_subcommands(named).empty())
    message = fmt::format("'{}' is not a subcommand of impactfe", argv[1]);
  std::cerr << "error: " << message << "\n" << usage_line(app) << "\n";
  return kExitInput;
}

}  // namespace

int main(int argc, char** argv) {
  map_large_blocks_on_their_own();
  CLI::App app{"impactfe: finite elements for structural impact dynamics"};
  app.set_version_flag("--version",
                       fmt::format("impactfe {} ({})", program_version(), program_commit()));
  app.require_subcommand(1);
  RunArgs run;
  CLI::App* run_cmd = add_run(app, run);
  PostArgs post;
  CLI::App* post_cmd = add_post(app, post);
  std::string info_file;
  CLI::App* info_cmd = app.add_subcommand("info", "summarise a results file");
  info_cmd->add_option("results", info_file, "results file (.h5)")->required();
  ExportArgs export_args;
  CLI::App* export_cmd = add_export(app, export_args);
  ReportArgs report;
  CLI::App* report_cmd = add_report(app, report);
  MeshArgs mesh;
  CLI::App* mesh_cmd = add_mesh(app, mesh);
  HelpArgs help;
  CLI::App* help_cmd = add_help(app, help);
  std::vector<double> xi = {0.0};
  CLI::App* spectrum_cmd = app.add_subcommand(
      "houbolt-spectrum", "spectral radius of the Houbolt amplification matrix (thesis Fig. 3-4)");
  spectrum_cmd->add_option("--xi", xi, "damping ratios");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return command_line_error(app, e, argc, argv);
  }

  try {
    if (*run_cmd && run.solver != "mumps" &&
        (run.mumps_ooc || !run.mumps_ooc_dir.empty() || run.mumps_no_refine)) {
      std::cerr << "error: --mumps-ooc, --mumps-ooc-dir and --mumps-no-refine need --solver "
                   "mumps\n";
      return kExitInput;
    }
    if (*run_cmd) return run.solver == "mumps" ? run_distributed(run) : run_command(run);
    if (*post_cmd) return post_command(post);
    if (*info_cmd) {
      std::cout << results_info(ResultsReader(info_file));
      return kExitOk;
    }
    if (*export_cmd) return export_command(export_args);
    if (*report_cmd) return report_command(report);
    if (*spectrum_cmd) return spectrum_command(xi);
    if (*mesh_cmd) return mesh_command(mesh);
    if (*help_cmd) return help_command(help);
  } catch (const InternalError& e) {
    return report_internal_error(e);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitInput;
  }
  return kExitOk;
}
