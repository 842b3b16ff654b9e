#pragma once
// What a reader or writer refused: the InputError's message, naming the file and line or field,
// or "accepted" where it took the input.
#include <string>

#include "common/input_error.hpp"

namespace rcsim::testing {

template <typename F>
std::string refusal_of(F&& act) {
  try {
    act();
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace rcsim::testing
