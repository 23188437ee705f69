#pragma once
/// Helpers of the selection, POST1, POST26 and *GET handlers: the selected sets, components,
/// results access (the deck layer reads results through the solution host and ResultsReader;
/// it never solves), the current POST1 set, element and nodal item look-ups, and printing.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "deck/deck_context.h"
#include "deck/output.h"
#include "deck/parameters.h"
#include "deck/post_state.h"
#include "elements/element_registry.h"

namespace impactfe::deck {

// ---- selection ------------------------------------------------------------------------------

/// Selected node / element numbers (ascending).
std::vector<int> selected_nodes(const DeckReader& r);
std::vector<int> selected_elements(const DeckReader& r);
/// The same, failing with "no nodes are selected" when the set is empty (a command acting on
/// ALL or on the current set).
std::vector<int> require_selected_nodes(const DeckReader& r, const Command& c);
std::vector<int> require_selected_elements(const DeckReader& r, const Command& c);
/// The members of component `name` when it names one of kind `entity` ("NODE" or "ELEM");
/// nullopt when `name` is not a component; an error when it is one of another kind. Members
/// deleted since CM drop out.
std::optional<std::vector<int>> component_members(const DeckReader& r, const Command& c,
                                                  const std::string& name,
                                                  const std::string& entity);
/// Node list of a NODE field: a number, ALL (the selected nodes) or a component name.
std::vector<int> nodes_of_field(DeckReader& r, const Command& c, int field);
/// The model an analysis solves: MAPDL assembles only the selected elements (APDL_MODELING
/// §1.0); unselected ones are left out, with a note.
Model solution_model(const DeckReader& r, const Command& c);

// ---- results --------------------------------------------------------------------------------

PostState& post_state(DeckReader& r);
/// The results file of this deck, opened (reopened after new solutions): what the deck solved
/// (the host finishes what is pending), else FILE, else `--results`, else <case>.h5 for a
/// deck named <case>_post, else <jobname>.h5, else the only *.h5 of the working directory.
/// A deck without a model (post-only) takes its nodes and elements from the file.
const ResultsReader& results(DeckReader& r, const Command& c);
/// FILE,Fname,Ext: MAPDL's result extensions (rst, rdsp, rth, rmg; blank) name <Fname>.h5.
std::string results_file_name(const std::string& fname, const std::string& ext);
/// The current POST1 set: the one SET read, or — before any SET since the last solution — the
/// last set of the file.
const SetData& current_set(DeckReader& r, const Command& c);
/// Makes `data` the current set.
void make_current(DeckReader& r, SetData data);

/// Value of a nodal label (parse_nodal_item) at `node` in the current set; 0 where the DOF does
/// not exist, an error for a slave DOF of a reduced run that was not expanded.
double nodal_result(DeckReader& r, const Command& c, int node, const std::string& label);
/// Value of an element item (SMISC,1, LS,1, S,EQV, VOLU, a stored name) of element e in the
/// current set; nullopt when the element's type has no such item.
std::optional<double> element_result(DeckReader& r, const Command& c, int element,
                                     const std::string& item, const std::string& comp);
/// element_result as the element stores it: stress and strain components in the element's
/// result axes, whatever RSYS says.
std::optional<double> stored_element_result(DeckReader& r, const Command& c, int element,
                                            const std::string& item, const std::string& comp);
/// The stored column of a shell surface item at the SHELL location: a result name ending in
/// "_TOP" (the sequence tables name the top) with MID or BOT in its place under SHELL,MID/BOT;
/// any other name unchanged.
std::string shell_location_column(DeckReader& r, const std::string& name);
/// Stress and strain items whose X..XZ components are a tensor that RSYS rotates (S, EPEL,
/// EPPL, EPTO, EPTH, EPCR); `direction` is the index of Comp in X Y Z XY YZ XZ, or -1.
bool is_tensor_item(const std::string& item);
int tensor_direction(const std::string& comp);
/// Component `direction` of a stress or strain tensor of element e given in the element's result
/// axes (`stored`: X Y Z XY YZ XZ, engineering shears for strains), in the results system at
/// `location`: global (RSYS,0) or the axes of RSYS,KCN there; as stored under RSYS,SOLU.
double tensor_in_results_system(DeckReader& r, const Command& c, int element,
                                const std::string& item, const std::array<double, 6>& stored,
                                int direction, const Vec3& location);
/// ANSYS type name of element e ("" when unknown).
std::string element_type_name(const DeckReader& r, int element);
/// Cell kind of element e (its type's VtkCell; PolyVertex when unknown).
VtkCell element_cell(const DeckReader& r, int element);
/// Undeformed volume of element e (spar L·A, shell ∫t dA, brick ∫dV); nullopt for elements
/// without one. Needs the model's real constants and materials.
std::optional<double> element_volume(DeckReader& r, const Command& c, int element);
/// Centroid of element e: mean of its distinct nodes.
Vec3 element_centroid(const DeckReader& r, int element);

// ---- printing -------------------------------------------------------------------------------

/// A number as MAPDL prints it in listings: 5 significant digits, fixed between 0.1 and 1e5
/// ("-100.00", "1.2346", "0.0000"), else "0.12346E-01"; right-aligned in `width`.
std::string listing_number(double value, int width = 12);
/// "  LOAD STEP=     1  SUBSTEP=     1\n   TIME=  1.0000  ..." heading of a POST1 listing.
std::string set_heading(const SetData& data);
/// Writes text to the output sink.
void print(DeckReader& r, const std::string& text);

/// Writes an x-y graph (PLVAR, PLPATH, PLSECT) as the next picture file
/// `<jobname or /SHOW name>NNN.svg`; it ends the /NOERASE drawing of model pictures.
void write_graph(DeckReader& r, const Command& c, const std::vector<GraphCurve>& curves,
                 const GraphOptions& options);

}  // namespace impactfe::deck
