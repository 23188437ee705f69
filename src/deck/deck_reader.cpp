// Placeholder until the deck reader lands.
#include "deck/deck_reader.h"

namespace impactfe {

Job read_deck(const std::string& path, const DeckOptions&) {
  throw InputError("deck reader not implemented yet: " + path);
}

Job read_deck_text(const std::string&, const std::string& virtual_path, const DeckOptions&) {
  throw InputError("deck reader not implemented yet: " + virtual_path);
}

}  // namespace impactfe
