// The error every typed_json reader throws unless its caller names another (Reader's `raise`).
// A header of its own, without nlohmann-json, so that a module's public header can derive its
// error from it (casefile::CaseError) cheaply.
#pragma once

#include <stdexcept>
#include <string>

namespace glrc::typed_json {

// what() is one line: "<source>: <field path>: expected <what>[, got <what>]".
struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Throws E(message): a Reader's `raise` for the error type a module's callers catch.
template <class E>
[[noreturn]] void raise_as(const std::string& message) {
  throw E(message);
}

}  // namespace glrc::typed_json
