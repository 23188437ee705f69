#pragma once
/// The hooks through which expressions and the vector commands read the deck state:
///
/// * get functions (APDL_MODELING §10.3) — `NX(n)`, `NODE(x,y,z)`, `DISTND(n1,n2)`, `NSEL(n)`,
///   `UX(n)`, ...: a table of {name, argument count, function}, registered in groups like the
///   command table. A later registration of a name replaces an earlier one, so a group with
///   results or selection sets overrides the model-backed defaults registered here.
/// * *GET items (APDL_SCRIPTING §B) — {Entity, ENTNUM, Item1, IT1NUM, Item2, IT2NUM}: providers
///   tried last-registered first; the first that knows the entity and item answers. *VGET loops
///   over them; *GET reads one. *VPUT writes through put providers the same way.
#include <optional>
#include <string>
#include <vector>

#include "deck/parameters.h"

namespace impactfe::deck {

class DeckReader;
struct Command;

/// A get function: `evaluate` throws ExpressionError for a bad use (an undefined node, ...).
struct GetFunctionSpec {
  const char* name;
  int min_args;
  int max_args;
  double (*evaluate)(DeckReader& r, const std::vector<double>& args);
};

/// Every get function (all groups registered once).
const std::vector<GetFunctionSpec>& get_function_table();
/// The last registration of `upper_name`, or nullptr.
const GetFunctionSpec* find_get_function(const std::string& upper_name);

/// Model-backed get functions: NX NY NZ NODE NNEAR ENEARN DISTND CENTRX CENTRY CENTRZ NELEM, and
/// the selection functions NSEL ESEL NDNEXT ELNEXT through DeckReader::node_selected /
/// element_selected. Results functions (UX ... ROTZ, VX ..., AX ...) belong to the results group.
void register_model_get_functions(std::vector<GetFunctionSpec>& table);

/// One *GET / *VGET item request. Labels upper-case; numbers already evaluated.
struct GetItem {
  std::string entity;         // NODE, ELEM, PARM, ...
  double entnum = 0.0;        // ENTNUM (a number), or
  std::string entname;        // ENTNUM as a name (PARM,NAME / a component)
  std::string item1, it1num;  // IT1NUM as text: a label (X, FX) or a number
  std::string item2, it2num;
  bool missing_is_zero = false;  // *VGET: an absent entity gives 0 instead of an error
};

/// Answers `q` when it knows its entity and item: the value (a number or a text); nullopt when
/// the entity/item is not this provider's. Errors (absent node, ...) via r.fail(c, ...).
using GetItemProvider = std::optional<Value> (*)(DeckReader& r, const Command& c, const GetItem& q);
/// Stores `value` into the item `q` (*VPUT); false when the item is not this provider's.
using PutItemProvider = bool (*)(DeckReader& r, const Command& c, const GetItem& q, double value);

const std::vector<GetItemProvider>& get_item_providers();
const std::vector<PutItemProvider>& put_item_providers();
/// Model-backed items: NODE LOC X/Y/Z, NODE NSEL, NODE NXTH/NXTL, NODE NUM MAX/MIN, NODE COUNT;
/// ELEM NODE k, ELEM ATTR MAT/TYPE/REAL/SECN, ELEM CENT X/Y/Z, ELEM ESEL, ELEM NXTH/NXTL,
/// ELEM NUM MAX/MIN, ELEM COUNT; PARM name TYPE / DIM X|Y|Z.
void register_model_get_items(std::vector<GetItemProvider>& table);
/// Results, POST1/POST26 and database items (NODE U/V/A/RF/D/F/ANG, ELEM results/ETAB/VOLU,
/// ACTIVE, MODE, FSUM, SSUM, SORT, VARI, ETYP, RCON, MP; get_command.cpp).
void register_results_get_items(std::vector<GetItemProvider>& table);

/// The item of command fields `entity_field`.. (Entity, ENTNUM, Item1, IT1NUM, Item2, IT2NUM):
/// labels upper-cased (character parameters substituted), ENTNUM evaluated when it is a number
/// or expression, else kept as a name (PARM,Name / a component). IT1NUM / IT2NUM stay texts:
/// a provider evaluates them (DeckReader::eval) where it expects a number.
GetItem read_get_item(DeckReader& r, const Command& c, int entity_field);

/// The value of one item: the first provider (last registered first) that knows it; an error
/// naming the entity and item when none does.
Value get_item(DeckReader& r, const Command& c, const GetItem& q);
/// Stores through the put providers; an error naming the item when none takes it.
void put_item(DeckReader& r, const Command& c, const GetItem& q, double value);

}  // namespace impactfe::deck
