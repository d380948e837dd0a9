// What the API's calls throw: SceneError (bad input, exit 2), FileError (an output not
// written), Cancelled (the calling thread's CancelScope flag was set).
#pragma once

#include <atomic>
#include <stdexcept>
#include <string>

namespace luz {

/// Bad input: the message is one line naming the file (or `<dict>`, `--set …`) and the place
/// (line:column or key path). Every API call reports bad input with it; none ends the process.
struct InputError : std::runtime_error {
    /// A NUL quoted from the input is kept as "\u0000": what() is a C string, and would end
    /// the message there, before the reason.
    explicit InputError(const std::string& message) : std::runtime_error(without_nul(message)) {}
    explicit InputError(const char* message) : std::runtime_error(message) {}

  private:
    static std::string without_nul(const std::string& s);  // scene/input_error.cpp
};

using SceneError = InputError;

/// An output that could not be written (the message names the file).
struct FileError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// A stream output not written because the cancel flag was set while it waited for a reader.
struct WriteCancelled : FileError {
    using FileError::FileError;
};

/// Thrown when the calling thread's cancel flag is set. Not a std::exception, so that no handler
/// of those turns it into an error message: it ends the work and is caught where the flag was
/// set (the CLI's main, the Python module's call).
struct Cancelled {};

/// While alive, `flag` is the calling thread's cancel flag (nullptr: none): a load, build or
/// encoding on this thread then stops with Cancelled; the previous flag is restored afterwards.
class CancelScope {
  public:
    explicit CancelScope(const std::atomic<bool>* flag);
    ~CancelScope();
    CancelScope(const CancelScope&) = delete;
    CancelScope& operator=(const CancelScope&) = delete;

  private:
    const std::atomic<bool>* previous_;
};

}  // namespace luz
