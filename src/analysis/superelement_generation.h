#pragma once
/// Superelement generation (KAN,7 / ANTYPE,SUBSTR; spec §10.6): Guyan condensation of the
/// substructure model to its master DOFs, reduced load vectors and unit-acceleration vectors,
/// and the data the expansion needs.
#include <string>

#include "analysis/structure.h"
#include "io/superelement_file.h"

namespace impactfe {

/// Figures of a generation for the run summary and the results file.
struct GenerationSummary {
  int n_masters = 0;
  int n_slaves = 0;
  int n_constrained = 0;
  double total_mass[3] = {0.0, 0.0, 0.0};    // rᵀ M r of the full substructure per direction
  double reduced_mass[3] = {0.0, 0.0, 0.0};  // r_mᵀ g_d: the part the masters carry
  double seconds = 0.0;
  int factorizations = 0;  // of K_ss
};

/// Generates the superelement of `structure` for `request` (its load steps give the reduced
/// load vectors). `name`: the superelement name (SEOPT Sename or the jobname).
/// Throws InputError for non-zero D, a master on a constrained or missing DOF, or no masters;
/// ModelError when K_ss is singular.
SuperelementData generate_superelement(const Structure& structure, const AnalysisRequest& request,
                                       const std::string& name, GenerationSummary& summary);

}  // namespace impactfe
