#pragma once
/// \file utf8.h
/// Text leaving tirpol as JSON or HTML must be valid UTF-8, whatever bytes came in (an EXR string
/// attribute, a region name, a file name). One policy everywhere: each invalid byte becomes U+FFFD
/// (the Unicode replacement character), valid text passes unchanged.

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "tirpol/core/image.h"

namespace tirpol {

/// `text` with every byte that is not part of a well-formed UTF-8 sequence (RFC 3629: no overlong
/// forms, no surrogates, nothing above U+10FFFF) replaced by U+FFFD.
std::string valid_utf8(std::string_view text);

/// True if `text` is well-formed UTF-8.
bool is_valid_utf8(std::string_view text);

/// `json.dump(indent)` with invalid UTF-8 in any string replaced by U+FFFD instead of throwing
/// json type_error 316. Use for every JSON tirpol writes or prints.
std::string json_text(const nlohmann::json& json, int indent = -1);

/// Image header attributes as a JSON object (int, number, string, list of numbers).
nlohmann::json attributes_json(const Attributes& attributes);

}  // namespace tirpol
