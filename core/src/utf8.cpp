#include "tirpol/core/utf8.h"

#include <algorithm>
#include <cstdint>

#include "tirpol/core/error.h"
#include "tirpol/core/output_guard.h"

namespace tirpol {

namespace {
constexpr std::string_view kReplacement = "\xEF\xBF\xBD";  // U+FFFD

/// Length of the well-formed UTF-8 sequence at the start of `s`, 0 if there is none.
std::size_t sequence_length(std::string_view s) {
    const auto byte = [&](std::size_t i) { return static_cast<std::uint8_t>(s[i]); };
    const std::uint8_t b0 = byte(0);
    if (b0 < 0x80) return 1;
    std::size_t n = 0;
    std::uint8_t lo = 0x80, hi = 0xBF;  // allowed range of the second byte (RFC 3629 table)
    if (b0 >= 0xC2 && b0 <= 0xDF)
        n = 2;
    else if (b0 == 0xE0)
        n = 3, lo = 0xA0;
    else if (b0 == 0xED)
        n = 3, hi = 0x9F;  // no UTF-16 surrogates
    else if (b0 >= 0xE1 && b0 <= 0xEF)
        n = 3;
    else if (b0 == 0xF0)
        n = 4, lo = 0x90;
    else if (b0 == 0xF4)
        n = 4, hi = 0x8F;  // nothing above U+10FFFF
    else if (b0 >= 0xF1 && b0 <= 0xF3)
        n = 4;
    else
        return 0;
    if (s.size() < n || byte(1) < lo || byte(1) > hi) return 0;
    for (std::size_t i = 2; i < n; ++i)
        if (byte(i) < 0x80 || byte(i) > 0xBF) return 0;
    return n;
}
}  // namespace

std::string valid_utf8(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    while (!text.empty()) {
        const std::size_t n = sequence_length(text);
        if (n == 0) {
            out += kReplacement;
            text.remove_prefix(1);
        } else {
            out += text.substr(0, n);
            text.remove_prefix(n);
        }
    }
    return out;
}

// Declared in input_file.h: the check every YAML/JSON reader makes, using the decoder above.
std::size_t first_invalid_utf8(std::string_view text) {
    std::size_t offset = 0;
    while (offset < text.size()) {
        const std::size_t n = sequence_length(text.substr(offset));
        if (n == 0) return offset;
        offset += n;
    }
    return std::string_view::npos;
}

void check_utf8_text(std::string_view text, std::string_view source) {
    const std::size_t bad = first_invalid_utf8(text);
    if (bad == std::string_view::npos) return;
    const std::string_view before = text.substr(0, bad);
    const std::size_t line =
        1 + static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
    const std::size_t line_start = before.rfind('\n');
    const std::size_t column =
        bad - (line_start == std::string_view::npos ? 0 : line_start + 1) + 1;
    fail(
        "{}:{}:{}: invalid UTF-8 (byte 0x{:02X}); the file must be UTF-8 text (re-save it as "
        "UTF-8)",
        source, line, column, static_cast<unsigned>(static_cast<unsigned char>(text[bad])));
}

bool is_valid_utf8(std::string_view text) {
    while (!text.empty()) {
        const std::size_t n = sequence_length(text);
        if (n == 0) return false;
        text.remove_prefix(n);
    }
    return true;
}

std::string json_text(const nlohmann::json& json, int indent) {
    return json.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

nlohmann::json attributes_json(const Attributes& attributes) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [name, value] : attributes)
        out[name] = std::visit([](const auto& x) { return nlohmann::json(x); }, value);
    return out;
}

}  // namespace tirpol
