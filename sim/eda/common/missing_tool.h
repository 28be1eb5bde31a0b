// The error every EDA flow of shadesim area throws when a program or file it needs is not
// installed: its message names the tool and the Debian package that provides it. The CLI exits 2
// on it, before any figure is printed.
#pragma once

#include <stdexcept>

namespace shadesim {

class MissingToolError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace shadesim
