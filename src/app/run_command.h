#pragma once
/// `impactfe run`: a deck run from the command line, on one process or on MPI ranks.
#include <string>

namespace impactfe::app {

struct RunArgs {
  std::string deck;
  std::string out_dir = ".";
  std::string jobname;
  int threads = 0;                      // 0: all cores
  std::string results_thread = "auto";  // auto | on | off
  bool skip_unknown = false;
  std::string dialect = "auto";
  std::string results;
  std::string superelement;
  bool continue_on_nonconvergence = false;
  bool accept_energy_error = false;
  bool no_condense = false;
  std::string solver = "cholmod";  // cholmod | mumps (MPI, docs/scaling.md)
  bool mumps_ooc = false;
  std::string mumps_ooc_dir;
  bool mumps_no_refine = false;
  std::string memory;  // --memory SIZE ("4G"): the most the run may use; "" = what the machine has
};

/// Runs the deck in this process; returns the exit status.
int run_command(const RunArgs& args);

/// `--solver mumps`: MPI up, the deck run on every rank, one exit status for all, MPI down.
int run_distributed(RunArgs args);

}  // namespace impactfe::app
