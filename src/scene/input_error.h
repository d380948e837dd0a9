// InputError: bad input (exit 2). Its message names the file, the place and what is wrong.
#pragma once

#include <stdexcept>
#include <string>

namespace luz {

struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace luz
