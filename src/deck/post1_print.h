#pragma once
/// POST1 listings (PRNSOL, PRESOL, PRRSOL, SET,LIST, PRETAB) in a layout close to MAPDL's, so
/// that users can diff them; and the nodal values the listings and the contour plots share.
#include <optional>
#include <string>
#include <vector>

#include "deck/post_support.h"

namespace impactfe::deck {

/// The labels of PRNSOL / PLNSOL Item,Comp: DOF results (UX, USUM, ...) or averaged element
/// items ("S,X" as item S comp X). Fails for an unknown item.
struct NodalItem {
  std::string heading;                // PRINT U / PRINT S ...
  std::vector<std::string> labels;    // column labels: UX UY UZ USUM, SX SY ...
  std::vector<std::string> elements;  // for element items: the Comp of each column ("" = DOF)
  std::string element_item;           // S, EPEL (empty for DOF results)
};
NodalItem nodal_item(DeckReader& r, const Command& c, const std::string& item,
                     const std::string& comp);

/// Value of column k of a nodal item at node n: a DOF result, or the average over the selected
/// elements at the node that have the element item (nullopt when none has it).
std::optional<double> nodal_item_value(DeckReader& r, const Command& c, const NodalItem& item,
                                       std::size_t k, int node);
/// Column k of an element item (S, EPEL, ...) of element e at its node: its values extrapolated
/// to the node where it has them, else its centroid value, in the results system (RSYS);
/// nullopt when it has no such item.
std::optional<double> element_item_value_at_node(DeckReader& r, const Command& c,
                                                 const NodalItem& item, std::size_t k, int e,
                                                 int node);

/// PRETAB's table: one row per element, then MINIMUM / MAXIMUM VALUES.
std::string element_table_listing(const std::vector<int>& elements,
                                  const std::vector<std::string>& labels,
                                  const std::vector<std::vector<double>>& columns);
/// SET,LIST.
void print_set_list(DeckReader& r, const std::vector<ResultSet>& sets);

void register_post1_print_commands(std::vector<CommandSpec>& table);

}  // namespace impactfe::deck
