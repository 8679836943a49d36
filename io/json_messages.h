#pragma once
// Pieces of the error messages of the JSON readers (shape and scene files), so that both name
// bad values and their JSON paths the same way.

#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

namespace dnurbs {

/// A double with 17 significant digits ("%.17g"), which JSON readers take back as the same
/// double; negative zero is "-0.0" (JSON "-0" reads as the integer 0, losing the sign).
std::string format_json_number(double value);
/// A short description of a JSON value: `string "abc"`, `an array of 2 values`, `number 3`.
std::string describe_json_value(const nlohmann::json& value);
/// The JSON path of element `index` of the array at `path`: `path[index]`.
std::string json_index_path(const std::string& path, std::size_t index);

/// Parses a whole JSON document. Any failure of nlohmann's parser (a syntax error, or a number
/// that overflows a double such as 1e999) throws Error "`source`: (document): expected valid
/// JSON at line L, column C: <what>" (the position of an overflowing number is found in `text`).
nlohmann::json parse_json_document(const std::string& text, const std::string& source);

}  // namespace dnurbs
