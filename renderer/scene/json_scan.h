// What the JSON parser accepts silently, checked with line numbers on a
// scene file's text: a key given twice in one object (the parser keeps the
// last), and a number that does not fit a double (the parser reports it
// without a position). Run on text the parser has read without a syntax
// error, up to the point it stopped.
#pragma once

#include <filesystem>
#include <string>

namespace kappa {

/// Throws InputError naming `file` and the line of the first duplicate key
/// or overflowing number.
void check_json_keys_and_numbers(const std::filesystem::path& file, const std::string& text);

}  // namespace kappa
