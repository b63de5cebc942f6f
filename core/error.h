// Errors in user input (InputError, core/input_error.h): one-line messages
// naming the file (and line), which the command line prints and turns into
// exit code 2; and reading the input files they name.
#pragma once

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/input_error.h"
#include "core/input_file.h"  // read_input_file: every reader's one check

namespace kappa {

/// "file: message" or "file:line: message" (line 0 means the whole file).
std::string located(const std::filesystem::path& file, std::size_t line, const std::string& message);

[[noreturn]] void fail(const std::filesystem::path& file, std::size_t line, const std::string& message);

/// An output that could not be written once the work was done (a full disk,
/// a file-size limit): not the input's fault, so exit 1, but one line naming
/// the output and the system's reason, as for bad input.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Throws OutputError "file: message: <strerror(err)>" (without the reason
/// when err is 0).
[[noreturn]] void fail_output(const std::filesystem::path& file, const std::string& message, int err);

/// `message` as one line of valid UTF-8: messages quote file content, which
/// may hold newlines or bytes that are not UTF-8 (Latin-1 names); those bytes
/// become \xNN and line breaks become spaces.
std::string printable_line(const std::string& message);

/// Warnings gathered while loading, printed by the caller through the
/// process's WarningLog (core/warning_log.h), and inspected by tests.
using Warnings = std::vector<std::string>;

}  // namespace kappa
