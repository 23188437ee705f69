#pragma once
/// Internal state of one deck read: the model being built, the current processor, the
/// parameters, the 4x load-step list and the modern open analysis. Shared by the handler files
/// (prep7_commands.cpp, solution_commands.cpp, component_commands.cpp, post1_commands.cpp, ...);
/// not a public interface.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/log.h"
#include "core/model.h"
#include "deck/deck_reader.h"
#include "deck/expression.h"
#include "deck/lexer.h"
#include "deck/modeling_state.h"
#include "deck/output.h"
#include "deck/parameters.h"
#include "deck/scripting_state.h"
#include "deck/solution_host.h"
#include "deck/solution_state.h"

namespace impactfe::deck {

/// Processors (phases) a command may be valid in; bit mask.
enum Processor : unsigned {
  kBegin = 1u,
  kPrep7 = 2u,
  kSolu = 4u,
  kPost1 = 8u,
  kPost26 = 16u,
  kStress = 32u,  // 4x /STRESS block
};
inline constexpr unsigned kAnywhere = 63u;
/// The most trips of one *DO / *DOWHILE loop, or passes of a 4x *DO over a block.
inline constexpr long long kMaxLoopTrips = 10'000'000;
inline constexpr unsigned kPrepSolu = kPrep7 | kSolu;
inline constexpr unsigned kPost = kPost1 | kPost26;
const char* processor_name(unsigned processor);

/// A command ready for its handler: resolved (upper-case) name and raw field texts.
struct Command {
  std::string name;
  std::vector<std::string> fields;        // fields[0] is field 1
  std::string rest;                       // raw text after the first comma (/TITLE, /COM)
  bool assignment = false;                // modern `Par = expr`
  std::vector<std::string> format_lines;  // the line(s) after *VWRITE / *MSG, verbatim
  BlockText block;                        // CDB block data (RawCommand::block), or none
  int block_line = 0;                     // line of the block's first line
  SourceLocation where;
  int n_fields() const { return static_cast<int>(fields.size()); }
  /// Field i (1-based), "" when absent.
  const std::string& text(int i) const;
  bool blank(int i) const { return text(i).empty(); }
  /// Index of the last non-blank field (0 when none).
  int last_given() const;
};

class DeckReader;
using Handler = void (*)(DeckReader&, const Command&);

/// One entry of the command table: name → handler and the processors it is valid in.
/// Control commands (*DO, *IF, /INPUT, ...) have a null handler; the executor runs them.
struct CommandSpec {
  const char* name;
  Handler handler;
  unsigned processors;
  /// Accepted and not carried out: why (for the command reference; the handler logs it).
  const char* ignored = nullptr;
  /// Known and refused wherever it appears: the error message (the handler is not called).
  const char* refused = nullptr;
};

/// The command table (all handler groups registered once).
const std::vector<CommandSpec>& command_table();
/// A registration group of the table: commands [begin, end) and the page that describes them.
struct CommandGroup {
  const char* title;
  const char* doc;
  std::size_t begin = 0, end = 0;
};
/// The table's groups, in table order (the command reference's sections).
const std::vector<CommandGroup>& command_groups();
/// Exact lookup of an upper-case name.
const CommandSpec* find_command(const std::string& name);
/// 4x rule (APDL_SUBSET §1.8): the unique command whose first four significant characters (after
/// a leading '/' or '*') match. nullptr when none; `ambiguous` set when several match.
const CommandSpec* find_command_by_prefix(const std::string& name, bool& ambiguous);

void register_session_commands(std::vector<CommandSpec>& table);
void register_prep7_commands(std::vector<CommandSpec>& table);
void register_generation_commands(std::vector<CommandSpec>& table);
void register_solution_commands(std::vector<CommandSpec>& table);
void register_convergence_commands(std::vector<CommandSpec>& table);
void register_dynamics_commands(std::vector<CommandSpec>& table);
void register_spectrum_commands(std::vector<CommandSpec>& table);
void register_load_commands(std::vector<CommandSpec>& table);
void register_thermal_coupling_commands(std::vector<CommandSpec>& table);
void register_constraint_equation_commands(std::vector<CommandSpec>& table);
void register_component_commands(std::vector<CommandSpec>& table);
void register_get_commands(std::vector<CommandSpec>& table);
void register_post1_commands(std::vector<CommandSpec>& table);
void register_post1_plot_commands(std::vector<CommandSpec>& table);
void register_post26_commands(std::vector<CommandSpec>& table);

struct PostState;
void register_parameter_commands(std::vector<CommandSpec>& table);
void register_array_commands(std::vector<CommandSpec>& table);
void register_output_commands(std::vector<CommandSpec>& table);
void register_database_commands(std::vector<CommandSpec>& table);
void register_cdb_commands(std::vector<CommandSpec>& table);
void register_workbench_commands(std::vector<CommandSpec>& table);

/// Modern dialect (MAPDL): a name of at least four significant characters that begins exactly
/// one table command is that command (`SECT` → SECTYPE, `NSUBS` → NSUBST). nullptr when none;
/// `ambiguous` set when several begin with it.
const CommandSpec* find_command_by_abbreviation(const std::string& name, bool& ambiguous);

/// Modern dialect, after the exact lookup, the abbreviations and the macro search: a longer
/// spelling of a command (`/SOLUTION` → /SOLU), since MAPDL reads the first four characters of a
/// command name (Command Reference §1.2, "Command name"), when exactly one table command has
/// those four. A macro of that name (SOLVIT.MAC) comes first, as in MAPDL.
const CommandSpec* find_command_by_longer_spelling(const std::string& name);

/// --skip-unknown: true for the MAPDL commands this program does not carry out that cannot
/// change a result (graphics, picture files, printed listings, GUI macros such as JPGPRF):
/// an explicit list (skippable_commands.cpp), abbreviations and longer spellings included.
bool cannot_change_results(const std::string& upper_name);
/// That list, names as MAPDL spells them in full.
const std::vector<std::string_view>& commands_without_effect_on_results();

// Model building (APDL_MODELING): registered before the post commands, whose NSEL/ESEL/ALLSEL
// entries they take over outside /POST1 and /POST26.
void register_csys_commands(std::vector<CommandSpec>& table);
void register_solid_model_commands(std::vector<CommandSpec>& table);
void register_solid_edit_commands(std::vector<CommandSpec>& table);
void register_mesh_commands(std::vector<CommandSpec>& table);
void register_contact_commands(std::vector<CommandSpec>& table);
void register_entity_selection_commands(std::vector<CommandSpec>& table);
void register_mesh_selection_commands(std::vector<CommandSpec>& table);
void register_surface_load_commands(std::vector<CommandSpec>& table);
void register_material_commands(std::vector<CommandSpec>& table);
void register_explicit_commands(std::vector<CommandSpec>& table);

/// A part of explicit dynamics as EDPART numbers them: one combination of element type,
/// material and real set, numbered from 1 in ascending (type, material, real) order.
struct ExplicitPart {
  int number = 0, type = 0, mat = 0, real = 0;
  std::vector<int> elements;  // ascending ids
};
class DeckReader;
/// The part whose number field `field` of `c` gives (`name` the field's MAPDL name); fails
/// when the field is not a part number of the model.
ExplicitPart explicit_part(DeckReader& r, const Command& c, int field, const char* name);

class DeckReader {
 public:
  DeckReader(const DeckOptions& options, Dialect dialect, const std::string& jobname);

  /// Reads and executes a deck file (`where` = the /INPUT command, empty for the main deck).
  void run_file(const std::string& path, const SourceLocation& where);
  /// Executes lexed text (the main deck of read_deck_text).
  void run_text(const std::string& text, const std::string& path);
  /// As run_text; the CDB blocks of `text` are read in place (views of the shared text).
  void run_shared_text(const std::shared_ptr<const std::string>& text, const std::string& path);
  /// Closes open blocks at the end of the deck and returns the job.
  Job finish();

  // ---- field access (1-based field numbers as in the spec) --------------------------------
  std::optional<double> opt_real(const Command& c, int i) const;
  double real(const Command& c, int i, double fallback) const;
  std::optional<int> opt_int(const Command& c, int i) const;
  int integer(const Command& c, int i, int fallback) const;
  /// Upper-cased trimmed label ("" when blank). A field naming a character parameter or a CHAR
  /// array entry gives its text (APDL_SCRIPTING §A.5 rule 2); quotes keep the text as written.
  std::string label(const Command& c, int i) const;
  /// A text field with its case kept (file names): character parameters substituted, quotes
  /// removed.
  std::string text_field(const Command& c, int i) const;
  /// Field i as a number or a text (expressions evaluated; blank → 0).
  Value value(const Command& c, int i) const;
  /// Evaluates an expression with the parameters and the get functions; errors name `c`.
  double eval(const Command& c, const std::string& expression) const;
  Value eval_value(const Command& c, const std::string& expression) const;
  /// The same, throwing ExpressionError, for callers that fall back to a label or word their
  /// own message (*GET fields: `*GET,S,NODE,NODE(10,0,-1),U,Y`).
  Value evaluate_expression(std::string_view expression) const;
  /// `%expr%` substitution (§A.5 rule 3) of one text; `%%` is a literal %.
  std::string substitute_percent(const Command& c, const std::string& text) const;
  /// ON/OFF/1/0/YES/NO (blank → fallback).
  bool on_off(const Command& c, int i, bool fallback) const;
  [[noreturn]] void fail(const Command& c, const std::string& message) const;
  void warn(const Command& c, const std::string& message) const;
  /// Counts `units` of interpreted work at `c` and fails past DeckOptions::max_commands. A
  /// command whose cost is far above a parameter assignment weighs more than one unit (SAVE and
  /// RESUME: database_work), so that a loop of them stays within the same budget of time.
  void count_work(const Command& c, long long units);
  /// Work units of one database write or read (SAVE, RESUME) of `bytes` bytes: a file opened
  /// (kDatabaseWork, about the time of 10³ interpreted commands) plus the model and parameters
  /// serialized or parsed, whose time grows with the file (one unit per kDatabaseBytesPerWork
  /// bytes; measured: a 14.5 kB database of a 12 × 12 shell plate takes 0.4 ms to write or read,
  /// an assignment 0.7 µs, so about 24 bytes per unit).
  static constexpr long long kDatabaseWork = 1000;
  static constexpr long long kDatabaseBytesPerWork = 16;
  static long long database_work(std::size_t bytes) {
    return kDatabaseWork + static_cast<long long>(bytes) / kDatabaseBytesPerWork;
  }
  /// Records a command as accepted and not carried out; the log gives the reason its command
  /// table entry carries (CommandSpec::ignored, also printed by the command reference).
  void ignore(const Command& c);

  // ---- model helpers ---------------------------------------------------------------------
  /// Node numbers NODE..NEND step NINC (field numbers given); NODE may be ALL (the selected
  /// nodes) or a component name. Missing nodes in a range are skipped; a single missing node (or
  /// an empty range, or nothing selected) is an error.
  std::vector<int> node_range(const Command& c, int node_field, int end_field, int inc_field);
  void require_node(const Command& c, int id) const;
  /// Selection state as the get functions (NSEL(n), NODE(x,y,z), NDNEXT, ...) see it: defined
  /// and selected (NSEL, ESEL, ...).
  bool node_selected(int id) const;
  bool element_selected(int id) const;
  /// Checks the node count against the element type and stores the record (repeats allowed).
  /// The midside nodes of a quadratic cell that E does not give are 0 until EMORE gives them
  /// (an element still without one is refused by validate_elements).
  void add_element(const Command& c, int id, std::vector<int> nodes);
  /// Checks that every element has the real set / material / section its type needs
  /// (done when an analysis is frozen, since ANSYS allows R and MP after E).
  /// Before that, an element whose SECNUM is the modern default 1 (SECNUM never issued) and names
  /// no defined section gets SECNUM 0 (real constants are used).
  void validate_elements();
  /// Hands job.steps[step] (new, or grown by a load step) to the solution host, if any.
  void solve_step(std::size_t step);
  /// Largest previous load-step end time (TIME must increase).
  std::optional<double> previous_time() const;

  // ---- state (handlers are friends of the deck layer; kept public for simplicity) -----------
  // Session: the options, the job being built and its model, the dialect and the processor.
  DeckOptions options;
  Job job;
  Model& model;
  Dialect dialect;
  unsigned processor = kBegin;
  bool jobname_from_option = false;
  /// --skip-unknown: name → how often skipped, first location (the run summary's table).
  std::map<std::string, std::pair<int, SourceLocation>> skipped;
  std::size_t solutions = 0;  // solution requests handed to the host so far

  // The state of each processor's commands (what the model and the job do not hold yet).
  Parameters params;         // *SET, *DIM, ...: read by every processor's fields
  OutputSink output;         // /OUT: every printed line goes through it
  ScriptingState scripting;  // *SET increments, *BEGIN blocks, *CREATE files, *CFOPEN, *V settings
  ModelingState modeling;    // PREP7: attribute pointers, continuation targets, generation memory
  SolutionState solution;    // SOLUTION: the analysis being defined, 4x /STRESS, expansion pass
  /// POST1/POST26: the current set, element table, plot settings, POST26 variables
  /// (deck/post_state.h). The selection and the components are in the Model.
  std::shared_ptr<PostState> post;

  /// /CLEAR: a new, empty database (model, job, parameters, processor, output to the terminal);
  /// *CREATE files survive. The solution host closes the current job first.
  void clear_database(const Command& c);
  /// Runs a macro (in-memory *CREATE file or macro file on disk) with ARG1..AR19 set from
  /// `args`; false when no macro of that name exists.
  bool call_macro(const Command& c, const std::string& name, const std::vector<Value>& args);

 private:
  struct Program;
  struct Frame;
  enum class Flow { Normal, Exit, Cycle, Jump, Stop, EndFile };
  /// Runs the commands (the caller's own copy: the executed top-level commands of a program
  /// without labels are released as it goes, see Program::release_before).
  void run_program(std::vector<RawCommand>& cmds, const std::string& frame_name,
                   const SourceLocation& where);
  Flow run_range(Frame& f, std::size_t begin, std::size_t end);
  Flow run_do(Frame& f, std::size_t i, const Command& c);
  Flow run_dowhile(Frame& f, std::size_t i, const Command& c);
  Flow run_if(Frame& f, std::size_t i, const Command& c);
  bool if_condition(const Command& c, int first_field, bool& has_second);
  void run_block_macro(const Command& c, const std::string& name);
  /// *CREATE (a macro file in memory) or 4x *BEGIN (a block for *DO): records `body`.
  void record_block(const Command& c, std::vector<RawCommand> body);
  void run_use(const Command& c);    // *USE,Name,ARG1..AR18
  void run_input(const Command& c);  // /INPUT,Fname,Ext,Dir
  /// 4x *DO,Block,N1,N2 over a recorded *BEGIN block; false when `c` is an APDL *DO loop.
  bool run_block_do(const Command& c);
  void repeat_previous(const Command& c);
  /// Counts one unit of interpreted work at `c` (a command, a loop trip, a *REPEAT repetition,
  /// a block pass) and fails past DeckOptions::max_commands.
  void count_executed(const Command& c) { count_work(c, 1); }
  Command resolve(const RawCommand& raw);
  const CommandSpec* lookup(Command& c);
  /// A name the table does not know: runs its macro (true), or resolves a longer spelling
  /// (`spec` set), or skips it under --skip-unknown (true); otherwise stops.
  bool run_unknown(Command& c, const CommandSpec*& spec);
  void dispatch(const Command& c, const CommandSpec& spec);

  std::string last_name_;
  std::optional<Command> last_command_;  // *REPEAT source
  std::vector<std::string> active_;      // files and macros being run (recursion guard)
  int nesting_ = 0;                      // executor recursion depth (blocks, files, macros)
  long long executed_ = 0;               // interpreted work so far (runaway-loop guard)
  bool stopped_ = false;                 // STOP / /EOF at the top level
  struct FunctionBridge : FunctionHost {
    DeckReader* reader = nullptr;  // non-const: results functions (UX, ...) open the results
    bool call(const std::string& name, const std::vector<double>& args,
              double& result) const override;
  } functions_;
};

/// Reads a whole text file; InputError at `where` (or naming the deck) when it cannot be read.
std::string read_text_file(const std::string& path, const SourceLocation& where);
/// /INPUT,Fname,Ext,Dir: the file relative to the including deck (or Dir); without an extension
/// also Fname.inp and Fname.mac.
std::string resolve_input(const std::string& includer, const std::string& fname,
                          const std::string& ext, const std::string& dir = {});
/// DOF labels of D/M/DDELE: Lab in `lab_field`, extra labels in `extra_first..extra_last`. In 4x a
/// DOF label in a numeric range field (`end_field`, `inc_field`) starts the extra-label list
/// (APDL_SUBSET §1.11); the range fields it consumes are set to 0. ALL gives all six DOFs.
std::vector<Dof> parse_dof_labels(DeckReader& r, const Command& c, int lab_field, int& end_field,
                                  int& inc_field, int extra_first, int extra_last);

/// Model building at a solution request (SOLVE, LSWRITE): transfers the solid-model loads to the
/// mesh and checks that the materials the elements use are supported.
void prepare_model_for_solution(DeckReader& r, const Command& c);
/// Largest node or element number a deck may use (the field limit of DeckReader::opt_int).
inline constexpr long long kMaxEntityNumber = 2'000'000'000;
/// Fails at `c` when the model would hold more than DeckOptions::max_nodes nodes or
/// max_elements elements after adding `new_nodes` and `new_elements` (counts, not checked for
/// duplicates: an upper bound).
void check_model_size(const DeckReader& r, const Command& c, long long new_nodes,
                      long long new_elements);
/// Fails at `c` when the active type is TARGE170 and `nodes` (E/EN fields) do not make the shape
/// the last TSHAP set (APDL_MODELING §8.4; deck/contact_commands.cpp).
void check_target_shape(DeckReader& r, const Command& c, const std::vector<int>& nodes);
/// Fails at `c` when a generated node or element number is outside 1..kMaxEntityNumber.
int checked_number(const DeckReader& r, const Command& c, long long number, const char* what);
/// An ESYS number (ESYS, EMODIF, KATT/AATT/VATT): 0 or a local system number > 10 (the system
/// need exist only when a SOLVE builds the elements).
void check_esys_number(DeckReader& r, const Command& c, int kcn);

/// Closes a 4x /STRESS block (END, FINISH or the end of the deck): its requests become an
/// expansion pass of the preceding reduced transient.
void close_stress_block(DeckReader& r, const SourceLocation& where);

/// 4x `/INPUT,27`: appends the analysis frozen by AFWRITE as a Job::Step.
void run_frozen_analysis(DeckReader& r, const Command& c);

}  // namespace impactfe::deck
