// What the JSON parser accepts silently, checked with line numbers on a
// scene file's text: a key given twice in one object (the parser keeps the
// last), and a number that does not fit a double (the parser reports it
// without a position). Run on text the parser has read without a syntax
// error, up to the point it stopped.
#pragma once

#include <filesystem>
#include <string>

namespace kappa {

/// "LINE:COLUMN" (1-based) of a byte offset in `text`: where a JSON reader
/// (a scene file's, a glTF file's) points at an error.
std::string line_and_column(const std::string& text, std::size_t byte);

/// Throws InputError naming `file` and the line of the first duplicate key
/// or overflowing number.
void check_json_keys_and_numbers(const std::filesystem::path& file, const std::string& text);

}  // namespace kappa
