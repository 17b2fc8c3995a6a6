#pragma once
// One exception type for every failure a user can cause or meet (bad input,
// missing device, kernel build failure, out of memory). main() prints its
// message and exits non-zero; nothing else catches it.
#include <stdexcept>
#include <string>

namespace clpath {

struct Error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Bad usage: an option or environment value the program cannot accept (as
// opposed to a run that failed). main() exits 2 for these, 1 for the rest.
struct UsageError : Error {
    using Error::Error;
};

}  // namespace clpath
