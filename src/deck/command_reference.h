#pragma once
/// The command reference, generated from the command table (command_table.cpp): for each command
/// the processors that accept it, whether it is carried out, run by the executor, or accepted and
/// ignored (with why), and the page that describes it. `impactfe help COMMAND` prints an entry;
/// docs/reference.md is the whole reference (`impactfe help --markdown`).
#include <string>

namespace impactfe::deck {

/// One command's entry; "" when the name (or its abbreviation) is not a command.
std::string command_help(const std::string& name);
/// The command reference as Markdown: a section per command group, one line per command, then
/// the unknown commands that --skip-unknown may skip.
std::string command_reference_markdown();

/// docs/reference.md: the command reference, then the element reference.
std::string reference_markdown();
/// `impactfe help NAME`: the element type of that name, else the command; "" when neither.
std::string help_entry(const std::string& name);
/// `impactfe help`: how to ask, and the element types.
std::string help_index();

}  // namespace impactfe::deck
