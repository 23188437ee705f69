#pragma once
/// Changes of the model between the load steps of an analysis. An analysis keeps the model of
/// its first SOLVE (its structure, factorization and state are built from it), so a change made
/// by MP, MPDATA, TB, R, RMODIF, ET, KEYOPT, SECDATA, N or E before a later SOLVE of the same
/// analysis would not act on that load step: such a SOLVE is refused, naming the change, rather
/// than solved with the old model (a silent wrong answer).
#include <string>

#include "core/model.h"

namespace impactfe::deck {

/// The first difference between `began` (the snapshot of the open analysis) and `now` in what
/// the analysis keeps: element types and KEYOPTs, real constants, materials and their TB
/// tables, sections, the selected elements (those the analysis solves) and the nodes. "" when
/// none.
std::string model_change(const Model& began, const Model& now);

}  // namespace impactfe::deck
