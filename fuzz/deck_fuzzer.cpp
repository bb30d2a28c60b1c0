// libFuzzer target for the deck loader: any text must either parse or raise DeckError (file,
// line, key, what is allowed). Any other exception, a crash, a sanitizer report, a hang or an
// unbounded allocation is a finding. The memory estimate runs on every deck that parses, as
// `check` and `run` call it before they allocate.
#include <cstddef>
#include <cstdint>
#include <string>

#include "input/deck.hpp"
#include "input/deck_error.hpp"
#include "setup/memory_estimate.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const periadapt::Deck dk = periadapt::parse_deck(text, "fuzz.yaml");
    (void)periadapt::estimate_memory(dk);
  } catch (const periadapt::DeckError&) {
  }
  return 0;
}
