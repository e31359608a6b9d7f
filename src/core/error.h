// Error categories. InputError is the user's mistake (bad file, bad option):
// the CLI prints its one-line message and exits with code 2. Anything else is
// an internal failure (exit code 1).
#pragma once

#include <stdexcept>
#include <string>

namespace pathlab {

struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace pathlab
