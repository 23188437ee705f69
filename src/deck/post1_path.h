#pragma once
/// POST1 path operations: results interpolated at points along a path (PATH, PPATH, PDEF,
/// PCALC, PVECT, PDOT, PCROSS, PRPATH, PLPATH, PADELE, *GET,Par,PATH) and the linearized stresses
/// of a section through a wall (PRSECT, PLSECT). docs/post_processing.md, "Paths".
#include <string>
#include <vector>

#include "deck/post_support.h"

namespace impactfe::deck {

/// The current path with all its points defined (fails naming what is missing).
PathDefinition& complete_path(DeckReader& r, const Command& c);

/// The values of path item `label` of `path` (fails when the path has no such item).
const std::vector<double>& path_item(DeckReader& r, const Command& c, const PathDefinition& path,
                                     const std::string& label);

/// Interpolates nodal result Item,Comp (one component: U X, S EQV, EPEL XY, ...) at the points
/// of `path` (AVG: averaged nodal values; NOAV: the values of the element the point lies in).
std::vector<double> interpolate_on_path(DeckReader& r, const Command& c, const PathDefinition& path,
                                        const std::string& item, const std::string& comp,
                                        bool average);

/// The same at any points (PRSECT's section).
std::vector<double> interpolate_at(DeckReader& r, const Command& c, const std::vector<Vec3>& points,
                                   const std::string& item, const std::string& comp, bool average);

/// *GET,Par,PATH,0,MAX|MIN|LAST|FIRST,Lab: the extremes, last or first value of a path item of
/// the current path; *GET,Par,PATH,0,ITEM,Lab,PATHPT,n: its value at point n (1-based).
double get_path_value(DeckReader& r, const Command& c, const std::string& what,
                      const std::string& label, int point = 0);

void register_post1_path_commands(std::vector<CommandSpec>& table);
void register_post1_section_commands(std::vector<CommandSpec>& table);

}  // namespace impactfe::deck
