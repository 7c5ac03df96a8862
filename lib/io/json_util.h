// JSON files (configs, models, reports) with errors that name the file and,
// for syntax errors, line and column.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rk::io {

using Json = nlohmann::json;

// Parses a JSON file ("-" = stdin). Syntax errors → DataError(file, line, col).
Json LoadJson(const std::string& path);
Json ParseJson(const std::string& text, const std::string& name);

// Field access that fails with DataError("file: field 'a.b' ...") when a
// required field is missing or of the wrong type. `where` names the object
// ("camera.json" or "camera.json: mount_deg").
double RequireNumber(const Json& j, const std::string& key, const std::string& where);
double NumberOr(const Json& j, const std::string& key, double fallback, const std::string& where);
std::vector<double> RequireNumbers(const Json& j, const std::string& key, std::size_t min_n, std::size_t max_n,
                                   const std::string& where);
std::string RequireString(const Json& j, const std::string& key, const std::string& where);

// Writes pretty JSON atomically ("-" = stdout).
void WriteJson(const std::string& path, const Json& j);
// The text WriteJson writes.
std::string JsonText(const Json& j);

}  // namespace rk::io
